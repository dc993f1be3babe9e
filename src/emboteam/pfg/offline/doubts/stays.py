"""Point of doubt: "X stays where it is", "leave the lamp on", "everything except X": is
keeping X as it is part of the end state?

A person who names a thing only to keep it may mean "do not touch it" (no goal, as read)
or "it must still be there, still on, at the end" (its present place or switch state as
a goal). The alternative adds the thing's present state, read from the world state. The
keeping words are data (``rule_words.json``, ``stays``).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.rule_words import load_rule_words
from emboteam.pfg.offline.doubts.wants import one_object, placed
from emboteam.pfg.sentences import clause
from emboteam.world.goals import Condition, Predicate

KIND = "stays"

def present(ctx: DoubtContext, type_: str) -> list[Condition]:
    """The present place (its receptacle's type) or switch state of the things of a type."""
    objs = list(ctx.state.of_type(type_))
    if not objs:
        return []
    o = objs[0]
    if o.has("toggleable") and type_ in ("FloorLamp", "DeskLamp", "LightSwitch", "Television", "Laptop"):
        return [one_object(Predicate.switched_on if o.is_on else Predicate.switched_off, type_)]
    if o.parent is not None and o.has("pickupable"):
        return [placed(type_, ctx.state.obj(o.parent).type)]
    return []


def doubts(ctx: DoubtContext) -> list[Doubt]:
    out = []
    keepers = frozenset(load_rule_words().stays.keepers)
    placed_types = {t for c in ctx.goals if c.predicate is Predicate.inside for t in ref_types(c.subject)}
    for k, item, types in ctx.mentions():
        start, end = ctx.clause_bounds(k)
        if not any(i.text in keepers for i in ctx.items[max(start, k - 3):min(end, k + 6)]):
            continue
        keep = [c for c in present(ctx, types[0]) if c not in ctx.goals]
        if not keep or (types[0] in placed_types and keep[0].predicate is Predicate.inside):
            continue
        family = {Predicate.inside} if keep[0].predicate is Predicate.inside else {Predicate.switched_on,
                                                                                 Predicate.switched_off}
        clash = tuple(c for c in ctx.goals if c.subject.types == (types[0],) and c.predicate in family)
        out.append(Doubt(KIND, item.text, (Choice(AS_READ, f"{item.text!r}: no goal"),
                                           Choice("keep_as_is", clause(keep[0]), drop=clash, add=tuple(keep)))))
    return out
