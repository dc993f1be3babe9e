"""Replanning: how the executor gets a new plan when a branch is lost, a robot joins, or
the plan ran out with the goal unmet.

A :data:`Replanner` is any callable ``(state, goal, working robots) -> MergedPlan``; no
LLM is involved: the hybrid planner plans the goal from the current state. The executor
passes the whole goal, so conditions that already hold are kept (see ``executor.py``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Protocol

from emboteam.errors import EmboTeamError
from emboteam.exec.walled import check_not_walled_off
from emboteam.hp.decompose import decompose_goal
from emboteam.hp.plan import MergedPlan
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.checker import check_goal
from emboteam.world.goals import Goal
from emboteam.world.state import WorldState

Replanner = Callable[[WorldState, Goal, Sequence[str]], MergedPlan]


class GoalPlanner(Protocol):
    """What :func:`planner_replanner` needs: ``HybridPlanner``'s ``plan_goal`` and ``plan``."""

    def plan_goal(self, goal: Goal, state: WorldState) -> MergedPlan: ...

    def plan(self, spec: TaskSpec, state: WorldState) -> MergedPlan: ...


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


class PlannerReplanner:
    """Replan with a goal planner (``HybridPlanner``) restricted to the working robots.

    :meth:`giving_work_to` is what the executor calls when robots join: a robot that joins
    must receive work, but a makespan-minded allocation gives none to a newcomer that
    enters far from the objects while the team is close to them. So when the plain plan
    leaves a newcomer idle, each unmet subtask it could take alone is tried with it
    assigned, and the shortest such plan is used (the plain plan when none works)."""

    def __init__(self, planner: GoalPlanner) -> None:
        self.planner = planner

    def __call__(self, state: WorldState, goal: Goal, robots: Sequence[str]) -> MergedPlan:
        check_not_walled_off(goal, state, robots)  # the planner's drive costs ignore broken robots
        return self.planner.plan_goal(goal, restrict_team(state, robots))

    def giving_work_to(self, state: WorldState, goal: Goal, robots: Sequence[str],
                       newcomers: Sequence[str]) -> MergedPlan:
        check_not_walled_off(goal, state, robots)
        team = restrict_team(state, robots)
        plain = self.planner.plan_goal(goal, team)
        idle = [r for r in newcomers if r in team.robots and not plain.for_robot(r)]
        if not idle:
            return plain
        spec = decompose_goal(goal, team)
        report = check_goal(goal, team)
        unmet = {str(c) for c in report.unmet()}
        best: MergedPlan | None = None
        for robot in idle:
            for sub in spec.subtasks:
                if not any(str(c) in unmet for c in sub.goal):
                    continue
                assigned = spec.model_copy(update={"subtasks": tuple(
                    t.model_copy(update={"robot": robot}) if t.id == sub.id else t for t in spec.subtasks)})
                try:
                    plan = self.planner.plan(assigned, team)
                except EmboTeamError:
                    continue
                if plan.for_robot(robot) and (best is None or plan.makespan < best.makespan):
                    best = plan
        return best if best is not None else plain


def planner_replanner(planner: GoalPlanner) -> PlannerReplanner:
    """Replan with a goal planner (``HybridPlanner``) restricted to the working robots."""
    return PlannerReplanner(planner)
