"""How long actions take in simulated seconds.

Navigation: AI2-THOR agents move on a 0.25 m grid in axis-aligned steps, so the path
length between two points of open floor is their Manhattan distance; a robot covers it at
its profile's speed. Manipulation: fixed durations per skill, in the range AI2-THOR's
physics settles them (arm motion and object settling take about a second).
"""

from __future__ import annotations

from emboteam.world.actions import Skill

ACTION_SECONDS: dict[Skill, float] = {
    Skill.PickupObject: 1.0,
    Skill.PutObject: 1.0,
    Skill.OpenObject: 1.5,
    Skill.CloseObject: 1.5,
    Skill.SwitchOn: 0.5,
    Skill.SwitchOff: 0.5,
    Skill.SliceObject: 2.0,
    Skill.BreakObject: 1.0,
    Skill.CleanObject: 3.0,
    Skill.ThrowObject: 1.0,
    Skill.DropHandObject: 0.5,
    Skill.PushObject: 1.0,
    Skill.PullObject: 1.0,
}

#: turning on the spot and aligning with an object: the least a GoToObject takes
MIN_NAVIGATION_SECONDS = 0.5

#: a rejected action (the robot notices it cannot act) still costs this much time, so a
#: retry loop always advances simulated time
FAILED_ACTION_SECONDS = 0.5


def navigation_seconds(a: tuple[float, float], b: tuple[float, float], speed: float) -> float:
    """Time to drive from floor point ``a`` to ``b`` (x, z) at ``speed`` m/s."""
    manhattan = abs(a[0] - b[0]) + abs(a[1] - b[1])
    return max(MIN_NAVIGATION_SECONDS, manhattan / speed)


def action_seconds(skill: Skill) -> float:
    return ACTION_SECONDS[skill]
