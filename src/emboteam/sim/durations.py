"""How long actions take in simulated seconds.

Navigation: AI2-THOR agents move on a 0.25 m grid of reachable cells, one MoveAhead
(0.25 m) or one 90° rotation per agent action; a drive is a shortest sequence of such
actions from the robot's cell to the target's interaction pose
(:mod:`emboteam.world.navigation`), and one action takes 0.25 m / speed (0.25 s at the
profiles' 1 m/s, AI2-THOR's ~4 actions per second). Without a floor plan (or between points
the grid cannot join) the Manhattan distance at the profile's speed stands in. Manipulation: fixed durations per skill, in the range AI2-THOR's
physics settles them (arm motion and object settling take about a second).
"""

from __future__ import annotations

from emboteam.world.actions import Skill
from emboteam.world.navgrid import GRID
from emboteam.world.navigation import navigator

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


def agent_action_seconds(speed: float) -> float:
    """One agent action (a 0.25 m MoveAhead or a 90° turn) at ``speed`` m/s."""
    return GRID / speed


def navigation_seconds(a: tuple[float, float], b: tuple[float, float], speed: float,
                       floor_plan: str | None = None) -> float:
    """Time for a robot at floor point ``a`` (x, z) to reach the thing at ``b`` at ``speed``
    m/s: along ``floor_plan``'s navigation grid to ``b``'s interaction pose when given (the
    simulator, the planner's cost model and its bound all call this), else Manhattan."""
    if floor_plan is not None:
        actions = navigator(floor_plan).travel_actions(a, b)
        if actions is not None:
            return max(MIN_NAVIGATION_SECONDS, actions * agent_action_seconds(speed))
    manhattan = abs(a[0] - b[0]) + abs(a[1] - b[1])
    return max(MIN_NAVIGATION_SECONDS, manhattan / speed)


def action_seconds(skill: Skill) -> float:
    return ACTION_SECONDS[skill]
