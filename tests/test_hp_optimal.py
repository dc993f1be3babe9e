"""CP-SAT's exact reference for the schedule (hp/optimal.py) and the "optimal" schedule."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from emboteam.bench.suites import load_suite
from emboteam.hp.optimal import Job, Op, Problem, reference, solve, travel
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.validate import simulate
from emboteam.pddl.problem import planning_state
from emboteam.pfg.oracle import OracleFrontend
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.actions import Skill
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
from sweep_cells import random_cell

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))  # benchmarks/ is no package
from plan_dump import sweep_input


def _job(i: int, robot: str, place: tuple[float, float], seconds: float) -> Job:
    return Job(f"j{i}", robot, f"j{i}", [f"s{i}"], [Op(f"s{i}", place, f"spot{i}", seconds, True, place)],
               {f"t{i}"}, {Skill.PickupObject})


def test_the_model_spreads_jobs_and_counts_the_drives() -> None:
    a, b = parse_team(["1", "1"])
    profiles = {"robot1": a, "robot2": b}
    places = [(2.0, 0.0), (0.0, 2.0), (2.0, 2.0)]
    jobs = [_job(i, "robot1", p, 10.0) for i, p in enumerate(places)]
    problem = Problem(jobs, {j.group: ("robot1", "robot2") for j in jobs},
                      {"robot1": (0.0, 0.0), "robot2": (0.0, 0.0)}, profiles)
    ref = solve(problem, limit=5.0)
    assert ref.optimal
    # three 10 s jobs on two robots: one robot does two, driving between them
    d = {(i, k): travel(a, places[i], places[k]) for i in range(3) for k in range(3)}
    start = [travel(a, (0.0, 0.0), p) for p in places]
    best = min(max(start[i] + 10 + d[(i, k)] + 10, start[m] + 10)
               for i in range(3) for k in range(3) for m in range(3) if len({i, k, m}) == 3)
    assert abs(ref.makespan - best) < 0.05
    assert set(ref.robots.values()) == {"robot1", "robot2"}
    assert solve(problem, limit=5.0) == ref  # one worker, a seed, deterministic time


def _salad() -> tuple[TaskSpec, WorldState]:
    task = next(t for t in load_suite("mace-thor").tasks if t.id == "fp6-salad-prep")
    state = task.initial_state()
    return OracleFrontend(task.goal).decompose(task.instruction, load_scene(task.floor_plan), state, task.team()), state


@pytest.mark.parametrize("make", [lambda: random_cell(2, 6), _salad], ids=["FloorPlan1 2x6", "fp6-salad-prep"])
def test_the_reference_of_a_plan_is_proven_and_never_above_it(make: Callable[[], tuple[TaskSpec, WorldState]]
                                                               ) -> None:
    # the salad: two robots cut with one knife, one after the other (one robot per object)
    spec, state = make()
    plan = HybridPlanner(PlannerConfig(schedule="fast")).plan(spec, state)
    ref = reference(plan, spec, planning_state(state), limit=10.0)
    assert ref is not None and ref.optimal
    assert ref.bound <= ref.makespan <= plan.makespan + 1e-6


def test_the_optimal_schedule_is_valid_and_never_longer() -> None:
    spec, state = random_cell(3, 10)
    fast = HybridPlanner(PlannerConfig()).plan(spec, state)
    best = HybridPlanner(PlannerConfig(schedule="optimal")).plan(spec, state)
    assert best.makespan <= fast.makespan + 1e-6
    timing = simulate(best, planning_state(state), spec.goal())
    assert timing.ok, timing.failure


def test_a_subtask_the_spec_gives_to_a_robot_stays_with_it() -> None:
    """The schedule may move the planner's own choices, never a spec's allocation (a
    joining robot given work, an LLM's or a user's robot per subtask)."""
    spec, state = random_cell(2, 6)
    # the planner's own allocation, each subtask on one robot (the route stage may part a
    # subtask's jobs among robots); then the whole pipeline, route stage too, must keep it
    plain = HybridPlanner(PlannerConfig(schedule="optimal", route=False)).plan(spec, state)
    for sub in spec.subtasks:
        other = next(r for r in plain.robots if not any(s.subtask == sub.id for s in plain.for_robot(r)))
        pinned = spec.model_copy(update={"subtasks": tuple(
            t.model_copy(update={"robot": other}) if t.id == sub.id else t for t in spec.subtasks)})
        plan = HybridPlanner(PlannerConfig(schedule="optimal")).plan(pinned, state)
        assert {s.robot for s in plan.steps if s.subtask == sub.id} == {other}, sub.id


def test_the_routes_prove_an_eight_robot_cell_the_load_bound_could_not() -> None:
    """FloorPlan1, 8 robots, 32 goals, goal seed 1 (a quick-sweep cell): with each job's
    cheapest way in as the only drive bound, 10 deterministic seconds ended at a bound of
    25.0 against 27.25; each robot's route length over its circuit arcs, in the LP,
    proves the optimum."""
    _, spec, state = sweep_input("FloorPlan1", 8, 32, 1)
    plan = HybridPlanner(PlannerConfig()).plan(spec, state)
    ref = reference(plan, spec, planning_state(state), limit=10.0)
    assert ref is not None and ref.optimal
    assert ref.bound <= ref.makespan <= plan.makespan + 1e-6
