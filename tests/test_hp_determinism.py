"""The same input gives the same plan on an idle and on a loaded machine, and with a cold
or a warm plan cache (issue 28): every budget that shapes a plan counts search steps
(problems asked, moves tried, CP-SAT's deterministic time), never seconds."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Iterator

import pytest

from emboteam.bench.suites import load_suite
from emboteam.hp.goalgen import sweep_cell
from emboteam.hp.plan import MergedPlan
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.pfg.oracle import OracleFrontend
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
from sweep_cells import random_cell

#: MACE-THOR tasks with several robots and subtasks, and a sweep cell the re-allocation,
#: the spot order and the container split all work on
TASKS = ("fp303-clear-floor", "fp15-cook-egg")


def _inputs() -> list[tuple[str, TaskSpec, WorldState]]:
    out = []
    suite = {t.id: t for t in load_suite("mace-thor").tasks}
    for tid in TASKS:
        task = suite.get(tid)
        if task is None:
            continue
        state = task.initial_state()
        spec = OracleFrontend(task.goal).decompose(task.instruction, load_scene(task.floor_plan), state, task.team())
        out.append((tid, spec, state))
    spec, state = random_cell(3, 16)
    out.append(("FloorPlan1 3x16", spec, state))
    return out


def _content(plan: MergedPlan) -> list[object]:
    """Everything a user compares between runs: steps, waits, spots, sync, makespan."""
    return [[(s.id, s.robot, str(s.action), s.subtask, s.after, s.resources, s.est_start, s.est_end)
             for s in plan.steps], [(p.producer, p.consumer) for p in plan.sync], plan.makespan, plan.notes]


@pytest.fixture
def busy_cpu() -> Iterator[None]:
    """A busy loop on every core for as long as the test runs."""
    code = "while True:\n    pass\n"
    procs = [subprocess.Popen([sys.executable, "-c", code]) for _ in range(os.cpu_count() or 1)]
    try:
        yield
    finally:
        for p in procs:
            p.kill()
        for p in procs:
            p.wait()


def _plan_all(planner: HybridPlanner | None = None) -> dict[str, list[object]]:
    inputs = _inputs()
    assert len(inputs) >= 2
    return {label: _content((planner or HybridPlanner(PlannerConfig())).plan(spec, state))
            for label, spec, state in inputs}


def test_plans_are_the_same_on_a_loaded_machine(request: pytest.FixtureRequest) -> None:
    idle = _plan_all()
    request.getfixturevalue("busy_cpu")
    loaded = _plan_all()
    assert loaded == idle


def test_a_warm_cache_gives_the_same_plan_as_a_cold_one() -> None:
    # one planner for every input, each planned twice: the second time every Fast Downward
    # problem is a cache hit, and the re-allocation's budget must not buy more passes
    planner = HybridPlanner(PlannerConfig())
    first = _plan_all(planner)
    again = _plan_all(planner)
    assert planner.fd.cache_hits > 0
    assert again == first == _plan_all()


def test_a_plan_of_more_than_160_steps_is_the_same_on_a_loaded_machine(request: pytest.FixtureRequest) -> None:
    # the route stage's cheaper search on large plans (hp/critical_routes.py) stops on a
    # count of stops walked: a loaded machine must not cut it short
    spec, state = sweep_cell("FloorPlan1", 32, 96, 0)
    idle = HybridPlanner(PlannerConfig()).plan(spec, state)
    assert len(idle.steps) > 160 and any("late robots" in n for n in idle.notes)
    request.getfixturevalue("busy_cpu")
    assert _content(HybridPlanner(PlannerConfig()).plan(spec, state)) == _content(idle)
