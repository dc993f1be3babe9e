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
            slices = placed("BreadSliced", "Toaster").model_copy(update={"count": c.count})
            add = [a for a in (slices, one_object(P.switched_on, "Toaster")) if a not in have]
            if add:
                out.append(Doubt(KIND, "toast", (Choice(AS_READ, clause(c)),
                                                 _choice("left_in_device", (), add[:1]),
                                                 _choice("left_running", (), add))))
    return out + results(ctx)


#: a device switched on -> the state it gives what is in or on it (the stove's knob heats
#: what stands on a burner, and cooks what is in a pan there; the toaster toasts its
#: slice; the coffee machine fills its mug)
_DEVICES: dict[str, tuple[str, Predicate, str | None]] = {
    "StoveKnob": ("StoveBurner", P.hot, None), "Toaster": ("Toaster", P.cooked, None),
    "CoffeeMachine": ("CoffeeMachine", P.filled, "coffee"), "Microwave": ("Microwave", P.hot, None),
}


def _within(ctx: DoubtContext, place: str) -> list[str]:
    """The types the reading puts in or on ``place`` (and in what stands there: a pan on
    the burner)."""
    direct = [t for c in ctx.goals if c.predicate is P.inside and c.receptacle is not None
              and place in ref_types(c.receptacle) for t in ref_types(c.subject)]
    nested = [t for c in ctx.goals if c.predicate is P.inside and c.receptacle is not None
              and ref_types(c.receptacle) & set(direct) for t in ref_types(c.subject)]
    return [*direct, *nested]


def results(ctx: DoubtContext) -> list[Doubt]:
    """Point of doubt: the reading asks for the means (the pot on a burner, the knob on)
    but maybe also for what they give (the pot's water hot)."""
    out: list[Doubt] = []
    for c in ctx.goals:
        if c.predicate is not P.switched_on or c.subject.types[:1] == () or c.subject.types[0] not in _DEVICES:
            continue
        place, pred, liquid = _DEVICES[c.subject.types[0]]
        for thing in _within(ctx, place):
            if thing in ("Pan", "Pot") and pred is P.cooked:
                continue
            want = pred if not (thing in ("Pan", "Pot", "Kettle") or pred is P.hot) else P.hot
            if place == "StoveBurner" and thing not in ("Pan", "Pot", "Kettle"):
                want = P.cooked
            made = one_object(want, thing).model_copy(update={"liquid": liquid if want is P.filled else None})
            if made not in ctx.goals:
                out.append(Doubt(KIND, str(c), (Choice(AS_READ, clause(c)),
                                                Choice("and_its_result", clause(made), add=(made,)))))
    return out
