"""Point of doubt: which scene type a noun phrase names ("the table": the dining table or
the coffee table; "the cup": cup or mug), when the scene has more than one that fits.

The reader picks the lexicon's first present type; the alternatives are the others the
word can name here, in every goal condition that uses the pick.
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.sentences import type_name
from emboteam.world.goals import Condition, ObjectRef

KIND = "scene_type"


def _swap(c: Condition, old: str, new: str) -> Condition:
    def ref(r: ObjectRef | None) -> ObjectRef | None:
        if r is None or r.id is not None or r.types != (old,):
            return r
        return ObjectRef(types=(new,))
    return c.model_copy(update={"subject": ref(c.subject), "receptacle": ref(c.receptacle)})


def narrowing(ctx: DoubtContext) -> list[Doubt]:
    """A goal on "any of several types" ("the computer": Desktop|Laptop; "the lamp":
    DeskLamp|FloorLamp) may mean one of them."""
    out: list[Doubt] = []
    for c in ctx.goals:
        for role in ("subject", "receptacle"):
            ref = getattr(c, role)
            if ref is None or ref.id is not None or len(ref.types) < 2:
                continue
            choices = [Choice(AS_READ, f"any {' or '.join(type_name(t) for t in ref.types)}")]
            for t in ref.types:
                alt = c.model_copy(update={role: ObjectRef(types=(t,)), "count": 1 if role == "subject" else c.count})
                choices.append(Choice("one_type", f"the {type_name(t)}", drop=(c,), add=(alt,)))
            if role == "subject" and c.count >= len(ref.types):
                each = tuple(c.model_copy(update={"subject": ObjectRef(types=(t,)), "count": 1}) for t in ref.types)
                choices.append(Choice("each_type", "one of each", drop=(c,), add=each))
            out.append(Doubt(KIND, str(c), tuple(choices)))
    return out


def doubts(ctx: DoubtContext) -> list[Doubt]:
    out: list[Doubt] = narrowing(ctx)
    done: set[tuple[str, ...]] = set()
    for _, item, types in ctx.mentions():
        if len(types) < 2 or types in done:
            continue
        done.add(types)
        for chosen in types:
            using = [c for c in ctx.goals if _swap(c, chosen, "X") != c]
            if not using:
                continue
            choices = [Choice(AS_READ, f"{item.text!r} as the {type_name(chosen)}")]
            for other in types:
                if other != chosen:
                    swapped = tuple(_swap(c, chosen, other) for c in using)
                    choices.append(Choice("other_type", f"{item.text!r} as the {type_name(other)}",
                                          drop=tuple(using), add=swapped))
            out.append(Doubt(KIND, item.text, tuple(choices)))
            break
    return out
