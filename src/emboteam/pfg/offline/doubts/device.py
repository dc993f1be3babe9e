"""Point of doubt: which device a room-dependent phrase means ("the light": the ceiling
light's switch, or the desk or floor lamp; "the lamp" in a room with both lamps).

Alternatives: the same switching on each other light source of the scene.
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.goals import Condition, ObjectRef, Predicate

KIND = "device"

LIGHTS = ("LightSwitch", "DeskLamp", "FloorLamp")
_SWITCHING = frozenset({Predicate.switched_on, Predicate.switched_off})


def doubts(ctx: DoubtContext) -> list[Doubt]:
    present = [t for t in LIGHTS if t in ctx.scene_types]
    out = []
    for c in ctx.goals:
        if c.predicate not in _SWITCHING or c.subject.id is not None or len(c.subject.types) != 1 \
                or c.subject.types[0] not in LIGHTS:
            continue
        choices = [Choice(AS_READ, clause(c))]
        for other in present:
            if other != c.subject.types[0] and not any(
                    g.subject.types == (other,) and g.predicate is c.predicate for g in ctx.goals):
                alt: Condition = c.model_copy(update={"subject": ObjectRef(types=(other,))})
                choices.append(Choice("other_device", f"the {type_name(other)}: {clause(alt)}",
                                      drop=(c,), add=(alt,)))
        if len(choices) > 1:
            out.append(Doubt(KIND, str(c), tuple(choices)))
    return out
