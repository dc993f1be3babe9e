"""A candidate reading is checked like the reader's own: every condition names things the
scene has and can take that state (the goal checker), the goal compiler can compile it
(AI2-THOR's placement rules), and the team has the skills it needs."""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.pddl.errors import ImpossibleGoalError
from emboteam.pddl.goal_compiler import compile_condition, slicing_targets
from emboteam.sim.capability import analyse_goal
from emboteam.world.checker import GoalValidationError, validate_goal
from emboteam.world.goals import Condition, Goal
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState


def feasible(goals: tuple[Condition, ...], scene: Scene, state: WorldState, team: Sequence[RobotProfile]) -> bool:
    """Whether the goal is one the scene, the placement rules and the team allow."""
    goal = Goal(conditions=goals)
    robots = list(state.robots)
    try:
        validate_goal(goal, scene)
        slices = slicing_targets(list(goals), state, robots)
        for c in goals:
            compile_condition(c, state, robots, slices=slices, narrow=False)
    except (GoalValidationError, ImpossibleGoalError):
        return False
    return not team or analyse_goal(goal, state).team_can(team)
