"""Point of doubt: one particular object, or any of its kind ("the toilet paper on the
floor" singles one roll out; "the sink" may be any basin).

The reader names an instance when the words single one out; the alternative is any
object of that type (an end state that holds whichever one ends up there).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.sentences import clause
from emboteam.world.goals import Condition, ObjectRef

KIND = "instance"


def _any(ref: ObjectRef | None) -> ObjectRef | None:
    if ref is None or ref.id is None or "_Slice_" in ref.id:
        return ref
    return ObjectRef(types=(ref.id.split("_")[0],))


def _counted(ctx: DoubtContext) -> list[Doubt]:
    """"The two CDs ... on the shelf": one goal per instance, or two of the type."""
    groups: dict[tuple[object, ...], list[Condition]] = {}
    for c in ctx.goals:
        if c.subject.id is not None and "_Slice_" not in c.subject.id:
            key = (c.predicate, c.subject.id.split("_")[0], str(c.receptacle), c.liquid)
            groups.setdefault(key, []).append(c)
    out = []
    for (_, type_, _, _), same in groups.items():
        if len(same) > 1:
            alt = same[0].model_copy(update={"subject": ObjectRef(types=(str(type_),)), "count": len(same)})
            out.append(Doubt(KIND, str(type_), (Choice(AS_READ, "those ones"),
                                                 Choice("any_instances", clause(alt), drop=tuple(same), add=(alt,)))))
    return out


def doubts(ctx: DoubtContext) -> list[Doubt]:
    out = _counted(ctx)
    for c in ctx.goals:
        alt: Condition = c.model_copy(update={"subject": _any(c.subject), "receptacle": _any(c.receptacle)})
        if alt != c and alt not in ctx.goals:
            out.append(Doubt(KIND, str(c), (Choice(AS_READ, clause(c)),
                                            Choice("any_instance", clause(alt), drop=(c,), add=(alt,)))))
    return out
