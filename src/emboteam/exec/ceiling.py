"""Disturbed episodes: placing the disturbance in a task, and the honest ceiling.

:func:`prepare` plans the task's ground-truth goal once without faults (the *reference
plan*, the same for every mode: the planner caches it), takes its makespan as the nominal
makespan that ``random@0.3`` refers to and its objects as the candidates of a random move,
and folds the resolved breakdowns, moves, message faults and joins into the run's
configuration.

:func:`disturbance_outcome` records, after the run, whether the goal was still reachable
from the state right after the last disturbance by the robots left: the *ceiling*. It asks
the full system's planner with the ground-truth goal; a success proves reachability without
asking. "SR of savable" (successes among episodes the ceiling calls reachable) then says
whether a savable task was lost, separately from tasks no executor could save.
"""

from __future__ import annotations

import time
from collections.abc import Sequence

from pydantic import BaseModel, ConfigDict

from emboteam.config import RunConfig
from emboteam.exec.disturbance import DisturbanceEvent, DisturbanceOutcome
from emboteam.exec.executor import UNREACHABLE_ERRORS, UnsavableTaskError
from emboteam.exec.result import ExecutionResult
from emboteam.exec.walled import check_not_walled_off
from emboteam.hp.plan import MergedPlan
from emboteam.hp.planner import HybridPlanner
from emboteam.pddl.errors import PlanningError
from emboteam.sim.disturbances import DisturbanceSpecError, Resolved, resolve
from emboteam.sim.simulator import Simulator
from emboteam.task import EpisodeTask
from emboteam.world.checker import check_goal
from emboteam.world.goals import Goal
from emboteam.world.robots import RobotProfile
from emboteam.world.state import WorldState


class Prepared(BaseModel):
    """A run configuration with its disturbance made concrete."""

    model_config = ConfigDict(frozen=True, arbitrary_types_allowed=True)

    cfg: RunConfig
    resolved: Resolved
    reference_steps: int = 0


def plan_objects(plan: MergedPlan, state: WorldState) -> list[str]:
    """Pickupable objects the plan's steps act on (slices it creates included): what a
    random move may take."""
    found: list[str] = []
    for step in plan.steps:
        oid = step.action.target
        whole = oid.partition("_Slice_")[0]
        o = state.objects.get(oid) or state.objects.get(whole)
        if o is not None and o.has("pickupable") and oid not in found:
            found.append(oid)
    return found


def prepare(task: EpisodeTask, cfg: RunConfig, state: WorldState, team: Sequence[RobotProfile],
            planner: HybridPlanner) -> Prepared:
    """The configuration of a disturbed episode (see the module docstring); ``planner``:
    the full system's."""
    spec = cfg.disturbance
    nominal, objects, steps = 0.0, [], 0
    goal = task.ground_truth
    if goal is not None:
        try:
            ref = planner.plan_goal(goal, state)
        except PlanningError as exc:
            raise DisturbanceSpecError(f"no fault-free reference plan to place the disturbance in: {exc}") from None
        nominal, objects, steps = ref.makespan, plan_objects(ref, state), len(ref.steps)
    elif spec.needs_nominal or any(m.object == "random" for m in spec.moves):
        raise DisturbanceSpecError("a time as a fraction of the nominal makespan, or a random move, needs a "
                                   "task with a ground-truth goal; give times in seconds (12s)")
    resolved = resolve(spec, team=team, seed=cfg.seed, task=task.key, nominal_makespan=nominal,
                       plan_objects=objects)
    base = cfg.fault_config()
    faults = base.model_copy(update={"breakdowns": (*base.breakdowns, *resolved.breakdowns),
                                     "moves": (*base.moves, *resolved.moves), "messages": resolved.messages})
    joins = (*cfg.joins, *(f"{p.number or p.name}@{at!r}" for p, at in resolved.joins))
    return Prepared(cfg=cfg.model_copy(update={"faults": faults, "joins": joins}), resolved=resolved,
                    reference_steps=steps)


def _ceiling(goal: Goal, state: WorldState, planner: HybridPlanner) -> tuple[bool | None, str, tuple[str, ...]]:
    left = tuple(sorted(r for r, s in state.robots.items() if not s.down))
    if check_goal(goal, state).success:
        return True, "the goal held right after the disturbance", left
    if not left:
        return False, f"{UnsavableTaskError.__name__}: no robot is left working", left
    try:
        check_not_walled_off(goal, state, left)
        plan = planner.plan_goal(goal, state)
    except UNREACHABLE_ERRORS as exc:
        return False, f"{UnsavableTaskError.__name__}: {type(exc).__name__}: {exc}", left
    except PlanningError as exc:
        return None, f"the planner could not tell: {type(exc).__name__}: {exc}", left
    return True, f"a plan of {len(plan.steps)} steps for {', '.join(left)}", left


def disturbance_outcome(task: EpisodeTask, prepared: Prepared, sim: Simulator, result: ExecutionResult,
                        success: bool, initial: WorldState, planner: HybridPlanner) -> DisturbanceOutcome:
    """The ceiling and the reaction of one disturbed episode (see the module docstring)."""
    events = tuple(DisturbanceEvent(t=round(t, 6), kind=k, detail=d) for t, k, d, _ in sim.disturbances)
    network = {k: v for k, v in result.network.items() if v}
    disturbed = bool(events) or bool(network)
    goal = task.ground_truth
    t0 = time.perf_counter()
    if success:
        savable: bool | None = True
        why = "succeeded"
        after = sim.disturbances[-1][3] if sim.disturbances else initial
        left = tuple(sorted(r for r, s in after.robots.items() if not s.down))
    elif goal is None:
        savable, why, left = None, "no ground-truth goal to plan for", tuple(sorted(sim.state.robots))
    else:
        savable, why, left = _ceiling(goal, sim.disturbances[-1][3] if sim.disturbances else initial, planner)
    return DisturbanceOutcome(
        spec=prepared.cfg.disturbance.label, nominal_makespan=round(prepared.resolved.nominal_makespan, 4),
        events=events, disturbed=disturbed, savable=savable, ceiling=why,
        ceiling_seconds=round(time.perf_counter() - t0, 4), robots_left=left,
        wall_after=result.wall_after_disturbance, stop_reason=result.stop_reason,
        joined=result.joined_robots, joiner_actions=result.joiner_actions, network=network,
    )
