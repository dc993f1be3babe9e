"""The cycle collector is paused while a plan is made (emboteam.hp.collector), which is only
sound while planning leaves (almost) nothing in reference cycles for it to find."""

from __future__ import annotations

import gc
from collections.abc import Iterator

import pytest

from emboteam.hp import planner as planner_module
from emboteam.hp.collector import collector_paused
from emboteam.hp.goalgen import sweep_cell
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.stages.context import Context, Draft


@pytest.fixture
def collector_on() -> Iterator[None]:
    was = gc.isenabled()
    gc.enable()
    yield
    (gc.enable if was else gc.disable)()


def test_planning_leaves_next_to_nothing_in_cycles(collector_on: None) -> None:
    # a 4-robot, 16-goal cell grounds hundreds of steps; each grounding's recursive
    # search once left its states in a cycle (about 90,000 objects a plan this size).
    # What is left now is OR-Tools' (a CP-SAT model keeps about 370 objects in cycles: 3,000
    # for this cell's re-allocation)
    spec, state = sweep_cell("FloorPlan1", 4, 16, 0)
    planner = HybridPlanner(PlannerConfig())
    planner.plan(spec, state)  # caches filled: what is left below is this call's
    gc.collect()
    flags = gc.get_debug()
    gc.disable()
    gc.set_debug(gc.DEBUG_SAVEALL)
    try:
        planner.plan(spec, state)
        gc.collect()
        left = len(gc.garbage)
    finally:
        gc.set_debug(flags)
        gc.garbage.clear()
        gc.enable()
    assert left < 10_000, f"a plan left {left} objects in reference cycles"


def test_the_collector_is_off_while_planning_and_on_after(collector_on: None,
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    seen: list[bool] = []
    real = planner_module.plan_decomposed

    def spy(ctx: Context) -> Draft:
        seen.append(gc.isenabled())
        return real(ctx)

    monkeypatch.setattr(planner_module, "plan_decomposed", spy)
    spec, state = sweep_cell("FloorPlan1", 2, 4, 0)
    HybridPlanner(PlannerConfig()).plan(spec, state)
    assert seen == [False]
    assert gc.isenabled()


def test_overlapping_pauses_resume_once_and_respect_a_collector_left_off(collector_on: None) -> None:
    with collector_paused():
        with collector_paused():
            assert not gc.isenabled()
        assert not gc.isenabled()  # the outer call is still planning
    assert gc.isenabled()
    gc.disable()
    with collector_paused():
        pass
    assert not gc.isenabled()  # the caller had turned it off: it stays off


def test_an_error_while_planning_resumes_the_collector(collector_on: None) -> None:
    with pytest.raises(RuntimeError), collector_paused():
        raise RuntimeError("planning failed")
    assert gc.isenabled()
