"""AI2-THOR ``errorMessage`` -> our typed :class:`FailureReason`.

AI2-THOR reports a failed action as ``lastActionSuccess == False`` plus a free-text
``errorMessage`` (its ``errorCode`` is only set for malformed calls). The patterns below
are matched in order against the message, case-insensitively; they cover the messages
AI2-THOR's agent controller emits (see tests/test_thor_failures.py for the real strings).
A message no pattern knows becomes ``actuation_fault``: a transient failure the behavior
trees retry, with AI2-THOR's text kept in the outcome's message.
"""

from __future__ import annotations

import re

from emboteam.world.actions import FailureReason, Skill

R = FailureReason

#: (pattern, reason), first match wins: specific phrases before generic ones
PATTERNS: tuple[tuple[re.Pattern[str], FailureReason], ...] = tuple(
    (re.compile(p, re.IGNORECASE), r) for p, r in (
        (r"object id appears to be invalid|could not retrieve object|object not found"
         r"|not a valid object ?id|no object with id", R.UNKNOWN_OBJECT),
        (r"has something in it already|already holding|hand is full|already has an object", R.HAND_FULL),
        (r"isn't holding anything|not holding any|only supported when holding|nothing in hand"
         r"|no object in hand|hand is empty", R.HAND_EMPTY),
        (r"must have the property canpickup|not pickupable|cannot be picked up", R.NOT_PICKUPABLE),
        (r"not an openable object|not openable", R.NOT_OPENABLE),
        (r"off to open", R.ALREADY_ON),
        (r"already open", R.ALREADY_OPEN),
        (r"already closed", R.ALREADY_CLOSED),
        (r"not toggleable|can't be toggled|cannot be toggled", R.NOT_TOGGLEABLE),
        (r"toggle object on if it's already on|already toggled on|is already on", R.ALREADY_ON),
        (r"toggle object off if it's already off|already toggled off|is already off", R.ALREADY_OFF),
        (r"does not have the canbesliced|not sliceable", R.NOT_SLICEABLE),
        (r"already sliced", R.ALREADY_SLICED),
        (r"slice: objectinteraction only supported for held object knife|must be holding a knife",
         R.NO_KNIFE),
        (r"already broken", R.ALREADY_BROKEN),
        (r"not breakable|canbreak", R.NOT_BREAKABLE),
        (r"not dirtyable|dirtyable property", R.NOT_DIRTYABLE),
        (r"already clean", R.ALREADY_CLEAN),
        (r"not a receptacle", R.NOT_A_RECEPTACLE),
        (r"must be opened|must be open|is closed|not open", R.RECEPTACLE_CLOSED),
        (r"no valid positions to place|collision is blocking held object|not a valid object type to be placed"
         r"|cannot be placed|no valid receptacle", R.NOT_ALLOWED_HERE),
        (r"occluded|not interactable|not visible|could not find a target object|no target found",
         R.NOT_VISIBLE),
        (r"too far away|not within|out of range|distance", R.NOT_REACHABLE),
        (r"is blocking|collide|collision|no path|path not found|not reachable|failed to teleport"
         r"|not a valid position|position is not valid", R.NOT_REACHABLE),
    )
)


def failure_reason(message: str, skill: Skill | None = None) -> FailureReason:
    """The typed reason of one AI2-THOR error message (``actuation_fault`` if unknown)."""
    for pattern, reason in PATTERNS:
        if pattern.search(message):
            return reason
    if skill is Skill.GoToObject:
        return R.NOT_REACHABLE
    return R.ACTUATION_FAULT
