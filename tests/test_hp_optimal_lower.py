"""The cheap lower bound on CP-SAT's schedule model (hp/optimal_lower.py) and the skip it
lets ``fast``'s CP-SAT stage make (hp/stages/schedule.py): never above the model's proven
optimum, and the same plans with the skip as without it."""

from __future__ import annotations

import pytest

from emboteam.bench.suites import load_suite
from emboteam.hp import optimal
from emboteam.hp.optimal import Job, Op, Problem, problem_of, solve
from emboteam.hp.optimal_lower import lower_bound
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.stages import schedule
from emboteam.pddl.problem import planning_state
from emboteam.pfg.oracle import OracleFrontend
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.actions import Skill
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
from sweep_cells import random_cell

#: MACE-THOR tasks with a carried box, a shared fridge, several robots and a pinned group
TASKS = ("fp1-coffee-and-light", "fp1-fridge-apple-tomato", "fp15-cook-egg", "fp209-pack-vases",
         "fp201-tv-corner", "fp6-salad-prep")


def _task(task_id: str) -> tuple[TaskSpec, WorldState]:
    task = next(t for t in load_suite("mace-thor").tasks if t.id == task_id)
    state = task.initial_state()
    return OracleFrontend(task.goal).decompose(task.instruction, load_scene(task.floor_plan), state, task.team()), state


def _inputs() -> list[tuple[str, TaskSpec, WorldState]]:
    cells = [(f"cell {n}x{k}", *random_cell(n, k)) for n, k in ((2, 6), (3, 10))]
    return [(t, *_task(t)) for t in TASKS] + cells


@pytest.mark.parametrize("carries", [True, False])
def test_the_bound_is_never_above_the_proven_optimum(carries: bool) -> None:
    reached = 0
    for label, spec, state in _inputs():
        plan = HybridPlanner(PlannerConfig()).plan(spec, state)
        problem = problem_of(plan, spec, planning_state(state), carries)
        assert problem is not None and problem.jobs, label
        bound = lower_bound(problem)
        assert bound is not None, label
        ref = solve(problem, plan, limit=10.0)
        assert ref.optimal, label
        assert bound / optimal.SCALE <= ref.makespan + 1e-9, (label, bound, ref.makespan)
        reached += bound / optimal.SCALE >= ref.makespan - 1e-9
    assert reached >= 2  # and not a trivial bound: it proves some optima by itself


def test_orders_in_a_cycle_give_no_bound() -> None:
    a, = parse_team(["1"])
    jobs = [Job(f"j{i}", "robot1", f"j{i}", [f"s{i}"], [Op(f"s{i}", (0.0, float(i)), f"spot{i}", 1.0, True, (0.0, float(i)))],
                {f"t{i}"}, {Skill.PickupObject}) for i in range(2)]
    problem = Problem(jobs, {j.group: ("robot1",) for j in jobs}, {"robot1": (0.0, 0.0)}, {"robot1": a},
                      [("s0", "s1"), ("s1", "s0")])
    assert lower_bound(problem) is None
    problem.precedences = [("s0", "s1")]
    bound = lower_bound(problem)
    assert bound is not None and bound >= 200  # both jobs, one after the other
    assert bound / optimal.SCALE <= solve(problem, limit=5.0).makespan + 1e-9


def test_the_skip_changes_no_plan(monkeypatch: pytest.MonkeyPatch) -> None:
    skipped: list[bool] = []
    real = schedule._no_shorter

    def counted(problem: Problem, makespan: float) -> bool:
        skipped.append(real(problem, makespan))
        return skipped[-1]

    monkeypatch.setattr(schedule, "_no_shorter", counted)
    inputs = _inputs()
    with_skip = [HybridPlanner(PlannerConfig()).plan(spec, state) for _, spec, state in inputs]
    assert any(skipped) and not all(skipped)
    monkeypatch.setattr(schedule, "_no_shorter", lambda problem, makespan: False)
    without = [HybridPlanner(PlannerConfig()).plan(spec, state) for _, spec, state in inputs]
    for (label, _, _), p, q in zip(inputs, with_skip, without, strict=True):
        assert p.steps == q.steps and p.sync == q.sync and p.makespan == q.makespan, label
