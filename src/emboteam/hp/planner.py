"""The hybrid planner: subtasks -> Fast Downward -> one validated partially ordered plan.

``HybridPlanner(config).plan(spec, state)`` checks the goals against the state and the
team (unknown objects, impossible goals, skills or mass capacity the team lacks: a typed
error early), then runs a short pipeline of stages (:mod:`emboteam.hp.stages`), each its
own module with one entry point:

1. :mod:`~emboteam.hp.stages.decomposed`: decompose, solve, eliminate, merge -> a draft
   (a validated plan and how it was made);
2. the improvements ``PlannerConfig`` turns on, each ``(Context, Draft) -> Draft``, kept
   only when the simulated makespan is shorter: re-allocation, cluster split, spot order,
   container split (then the spot order again), the jobs on shorter routes with their
   drives planned again (then the spot order again), jobs of the robot that ends last given
   to robots that end early (then the spot order again), the drives that waited for their
   object sent ahead to where it is brought (then the spot order again), a switch others
   waited for done by one of them (then the spot order again), CP-SAT over the whole schedule
   (small plans with ``schedule="fast"``, every plan it can model with ``"optimal"``);
   when one robot's cluster is far above the team's mean load on a small plan, the
   improvements also run on the plan with that cluster split in two, and the shorter
   plan is kept (:mod:`~emboteam.hp.stages.fork`);
3. if decomposition fails (subtasks interleave, a unit keeps failing, the merge does not
   validate), :mod:`~emboteam.hp.stages.joint`: the whole goal as ONE joint problem.

``merge="concatenate"`` with ``validate=False`` is the paper's no-HP ablation
(:mod:`~emboteam.hp.stages.concatenate`). Every budget that shapes the plan counts search
steps (problems asked, moves tried, CP-SAT's deterministic time), never seconds: the same
input gives the same plan on any machine (issue 28).
"""

from __future__ import annotations

import time
from collections.abc import Callable

from emboteam.hp.collector import collector_paused
from emboteam.hp.config import PlannerConfig
from emboteam.hp.decompose import decompose_goal
from emboteam.hp.plan import MergedPlan
from emboteam.hp.requirements import check_team, need_of
from emboteam.hp.stages.concatenate import plan_concatenated
from emboteam.hp.stages.context import Context, Draft, Fallback, Solver
from emboteam.hp.stages.decomposed import plan_decomposed
from emboteam.hp.stages.drive_ahead import drive_ahead
from emboteam.hp.stages.fork import improved
from emboteam.hp.stages.idle import give_idle
from emboteam.hp.stages.joint import plan_joint
from emboteam.hp.stages.reallocate import reallocate
from emboteam.hp.stages.reorder import reorder
from emboteam.hp.stages.route import reorder_after, reroute
from emboteam.hp.stages.schedule import schedule, schedule_small
from emboteam.hp.stages.split import split_clusters, split_containers
from emboteam.hp.stages.take_over import take_over
from emboteam.pddl.errors import PlanningError
from emboteam.pddl.goal_compiler import shared_view
from emboteam.pddl.problem import planning_state
from emboteam.pddl.runner import FastDownward, PlanCache
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Goal
from emboteam.world.state import WorldState

__all__ = ["HybridPlanner", "PlannerConfig", "Stage", "improvements"]

#: an improvement stage: a draft in, a draft out (the same when nothing is shorter)
Stage = Callable[[Context, Draft], Draft]


def _then_reorder(improve: Stage, reorder_too: bool,
                  worth: Callable[[Context, Draft], bool] | None = None) -> Stage:
    """``improve``, and the spot order again when it changed the plan (and ``worth`` says
    it pays on the draft ``improve`` was given)."""
    def stage(ctx: Context, draft: Draft) -> Draft:
        out = improve(ctx, draft)
        if not reorder_too or out.plan is draft.plan or (worth is not None and not worth(ctx, draft)):
            return out
        return reorder(ctx, out)
    stage.__name__ = f"{improve.__name__}_then_reorder"
    return stage


def improvements(config: PlannerConfig) -> tuple[Stage, ...]:
    """The improvement stages ``config`` turns on, in order (none without validation:
    each keeps a plan only when its simulated makespan is shorter)."""
    if not config.validate:
        return ()
    stages: list[Stage] = []
    if config.rebalance != "off":
        stages.append(reallocate)
    if config.split_clusters:
        stages.append(split_clusters)
    if config.spot_order:
        stages.append(reorder)
    if config.split_containers:
        stages.append(_then_reorder(split_containers, config.spot_order))
    if config.route:
        stages.append(_then_reorder(reroute, config.spot_order, reorder_after))
    if config.idle:
        stages.append(_then_reorder(give_idle, config.spot_order))
    if config.drive_ahead:
        stages.append(_then_reorder(drive_ahead, config.spot_order))
    if config.take_over:
        stages.append(_then_reorder(take_over, config.spot_order))
    stages.append(schedule if config.schedule == "optimal" else schedule_small)
    return tuple(stages)


class HybridPlanner:
    """Plans TaskSpecs (and bare goals) for the robots of a state. Reusable: its plan
    cache persists across calls (and changes no plan: the budgets count problems asked
    in the call, cache hits too)."""

    def __init__(self, config: PlannerConfig | None = None) -> None:
        self.config = config or PlannerConfig()
        self.cache = PlanCache(self.config.cache_dir)
        self.fd = FastDownward(self.config.alias, time_limit=self.config.time_limit,
                               memory_limit_mb=self.config.memory_limit_mb, cache=self.cache,
                               planner_input=self.config.planner_input,
                               action_costs=self.config.action_costs,
                               refine_cost=self.config.refine_cost)
        self.solver = Solver(self.fd, self.config.workers)
        self.stages = improvements(self.config)

    def plan(self, spec: TaskSpec, state: WorldState) -> MergedPlan:
        """A validated multi-robot plan for ``spec`` from ``state`` (not modified)."""
        with collector_paused():  # see emboteam.hp.collector: it found nothing, at 10-15% of the CPU
            return self._plan(spec, state)

    def _plan(self, spec: TaskSpec, state: WorldState) -> MergedPlan:
        t0 = time.perf_counter()
        calls0 = self.fd.calls
        self.solver.reset()
        team = [r for r, rs in state.robots.items() if not rs.down]
        if not team:
            raise PlanningError("no working robot in the team")
        start = planning_state(state)
        view = shared_view(start)
        needs = {t.id: [need_of(c, start, team, view) for c in t.goal] for t in spec.subtasks}
        check_team([n for ns in needs.values() for n in ns], [start.robots[r].profile for r in team])
        ctx = Context(self.config, self.solver, spec, start, team, needs)
        plan = self._pipeline(ctx)
        return plan.model_copy(update={"planner_calls": self.fd.calls - calls0,
                                       "plan_seconds": round(time.perf_counter() - t0, 4),
                                       "notes": tuple(ctx.notes)})

    def plan_goal(self, goal: Goal, state: WorldState) -> MergedPlan:
        """Plan a bare goal from ``state`` (e.g. mid-run, robots holding things): related
        conditions become subtasks, the allocator spreads them over the working robots."""
        return self.plan(decompose_goal(goal, state), state)

    def _pipeline(self, ctx: Context) -> MergedPlan:
        if self.config.merge == "concatenate":
            return plan_concatenated(ctx)
        if not self.config.decompose:
            return plan_joint(ctx)
        try:
            draft = plan_decomposed(ctx)
            if self.config.split_critical and not self.config.split_clusters and self.stages:
                draft = improved(ctx, draft, self.stages)
            else:
                for stage in self.stages:
                    draft = stage(ctx, draft)
        except Fallback as fb:
            ctx.notes.append(f"decomposition failed ({fb}): planned as one joint problem")
            return plan_joint(ctx)
        return draft.plan

