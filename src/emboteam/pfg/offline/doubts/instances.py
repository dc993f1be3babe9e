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


def doubts(ctx: DoubtContext) -> list[Doubt]:
    out = []
    for c in ctx.goals:
        alt: Condition = c.model_copy(update={"subject": _any(c.subject), "receptacle": _any(c.receptacle)})
        if alt != c and alt not in ctx.goals:
            out.append(Doubt(KIND, str(c), (Choice(AS_READ, clause(c)),
                                            Choice("any_instance", clause(alt), drop=(c,), add=(alt,)))))
    return out
