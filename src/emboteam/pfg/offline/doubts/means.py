"""Point of doubt: whether the means named with an act is part of the end state.

"Heat the potato in the microwave" may ask only that the potato be hot, or that it be in
the microwave at the end (and the microwave left on); "make me a coffee" that the mug be
full, or that it stand in the running coffee machine; "toast" that the bread be cooked,
or that its slice be in the toaster, switched on. The alternatives add the means' end
state to the reading (and, for coffee, let go of the reader's "hot").
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.wants import one_object, placed
from emboteam.pfg.sentences import clause
from emboteam.world.goals import Condition, Predicate

KIND = "means"
P = Predicate


def _said(ctx: DoubtContext, type_: str) -> bool:
    return any(type_ in types for _, _, types in ctx.mentions())


def _choice(label: str, drop: tuple[Condition, ...], add: list[Condition]) -> Choice:
    return Choice(label, "; ".join(clause(c) for c in add), drop=drop, add=tuple(add))


def doubts(ctx: DoubtContext) -> list[Doubt]:
    out: list[Doubt] = []
    have = set(ctx.goals)
    for c in ctx.goals:
        subject = ref_types(c.subject)
        if len(subject) != 1 or c.subject.id is not None:
            continue
        thing = next(iter(subject))
        if c.predicate in (P.hot, P.cooked) and "Microwave" in ctx.scene_types and (
                _said(ctx, "Microwave") or any(w in ("microwave", "nuke", "nuker", "micro") for w in ctx.words)):
            add = [a for a in (placed(thing, "Microwave"),) if a not in have]
            if add:
                out.append(Doubt(KIND, "microwave", (Choice(AS_READ, clause(c)),
                                                     _choice("left_in_device", (), add),
                                                     _choice("left_running", (), [*add, one_object(P.switched_on,
                                                                                              "Microwave")]))))
        elif c.predicate is P.filled and c.liquid == "coffee" and "CoffeeMachine" in ctx.scene_types:
            hot = tuple(g for g in ctx.goals if g.predicate is P.hot and ref_types(g.subject) == subject)
            add = [a for a in (placed(thing, "CoffeeMachine"), one_object(P.switched_on, "CoffeeMachine"))
                   if a not in have]
            if add:
                out.append(Doubt(KIND, "coffee", (Choice(AS_READ, clause(c)),
                                                  _choice("left_in_device", hot, add[:1]),
                                                  _choice("left_running", hot, add))))
        elif c.predicate is P.cooked and thing == "Bread" and "Toaster" in ctx.scene_types:
            add = [a for a in (placed("BreadSliced", "Toaster"), one_object(P.switched_on, "Toaster"))
                   if a not in have]
            if add:
                out.append(Doubt(KIND, "toast", (Choice(AS_READ, clause(c)),
                                                 _choice("left_in_device", (), add[:1]),
                                                 _choice("left_running", (), add))))
    return out
