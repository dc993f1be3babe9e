"""Replanning: how the executor gets a new plan when a branch is lost, a robot joins, or
the plan ran out with the goal unmet.

A :data:`Replanner` is any callable ``(state, goal, working robots) -> MergedPlan``; no
LLM is involved: the hybrid planner plans the goal from the current state. The executor
passes the whole goal, so conditions that already hold are kept (see ``executor.py``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Protocol

from emboteam.hp.plan import MergedPlan
from emboteam.world.goals import Goal
from emboteam.world.state import WorldState

Replanner = Callable[[WorldState, Goal, Sequence[str]], MergedPlan]


class GoalPlanner(Protocol):
    """What :func:`planner_replanner` needs: ``HybridPlanner.plan_goal``'s shape."""

    def plan_goal(self, goal: Goal, state: WorldState) -> MergedPlan: ...


def restrict_team(state: WorldState, robots: Sequence[str]) -> WorldState:
    """A copy of the state whose team is only ``robots`` (the broken-down ones removed:
    the planner must not give them work). Objects they held were dropped when they broke
    down, so no object is left attached to a removed robot."""
    keep = set(robots)
    out = state.copy()
    for name in [r for r in out.robots if r not in keep]:
        held = out.robots[name].holding
        if held is not None and held in out.objects:
            out.objects[held].held_by = None
        del out.robots[name]
    return out


def planner_replanner(planner: GoalPlanner) -> Replanner:
    """Replan with a goal planner (``HybridPlanner``) restricted to the working robots."""
    def replan(state: WorldState, goal: Goal, robots: Sequence[str]) -> MergedPlan:
        return planner.plan_goal(goal, restrict_team(state, robots))
    return replan
