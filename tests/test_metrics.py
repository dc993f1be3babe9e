"""Metrics from their definitions (docs/metrics.md): SR, GCR, Exec per episode; means,
category breakdown and the seeded bootstrap CI of SR over episodes."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from conftest import SMART_LLM
from emboteam.bench.metrics import (
    BenchSummary,
    bootstrap_ci,
    exec_from_outcomes,
    exec_rate,
    goal_condition_rate,
    success_rate,
    summarize,
)
from emboteam.bench.suites import load_suite
from emboteam.exec.episode import ConditionOutcome, Episode
from emboteam.exec.trace import TraceEvent
from emboteam.sim.simulator import Simulator
from emboteam.world.actions import Action, Skill
from emboteam.world.checker import check_goal
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

CONTRACT = {"suite", "n", "sr", "gcr", "exec", "by_category", "plan_seconds_p50", "makespan_mean",
            "llm_calls_mean", "tokens_mean", "errors"}


def act(sim: Simulator, robot: str, skill: Skill, target: str, receptacle: str | None = None) -> None:
    out = sim.execute(robot, Action(skill=skill, target=target, receptacle=receptacle))
    assert out.success, out


@pytest.fixture(scope="module")
def peers() -> Path:
    if not (SMART_LLM / "final_test").is_dir():
        pytest.skip("SMART-LLM peer data not available")
    return SMART_LLM


# ---- SR and GCR on real states ------------------------------------------------------------


def test_broken_is_checked(peers: Path) -> None:
    """SMART-LLM's script never checks BROKEN; here an unbroken vase fails the task."""
    task = load_suite(f"smart-llm:{peers}").task("FloorPlan209-2")  # break a vase, turn on the TV
    sim = Simulator(load_scene(task.floor_plan), task.team(), state=task.initial_state())
    act(sim, "robot2", Skill.GoToObject, "Television_1")
    act(sim, "robot2", Skill.SwitchOn, "Television_1")
    report = check_goal(task.goal, sim.state)
    assert success_rate(report.results) == 0.0
    assert goal_condition_rate(report.results) == 0.5
    act(sim, "robot3", Skill.GoToObject, "Vase_1")
    act(sim, "robot3", Skill.BreakObject, "Vase_1")
    report = check_goal(task.goal, sim.state)
    assert success_rate(report.results) == 1.0 and goal_condition_rate(report.results) == 1.0


def test_gcr_stays_in_0_1_for_multi_item_contains(peers: Path) -> None:
    """'Fridge contains [Potato, Lettuce]' is two conditions; three apple slices in the bin
    satisfy 'GarbageCan contains Apple' once, not three times."""
    suite = load_suite(f"smart-llm:{peers}")
    two = suite.task("FloorPlan21-3")
    state = two.initial_state()
    for item in ("Potato_1", "Lettuce_1"):
        state.move_object(item, "Fridge_1")
    report = check_goal(two.goal, state)
    assert [r.satisfied for r in report.results] == [1, 1]
    assert goal_condition_rate(report.results) == 1.0

    trash = suite.task("FloorPlan21-6")  # slice the apple and throw it in the trash
    sim = Simulator(load_scene(trash.floor_plan), parse_team("1"), state=WorldState.from_scene(
        load_scene(trash.floor_plan), parse_team("1")))
    act(sim, "robot1", Skill.GoToObject, "ButterKnife_1")
    act(sim, "robot1", Skill.PickupObject, "ButterKnife_1")
    act(sim, "robot1", Skill.GoToObject, "Apple_1")
    act(sim, "robot1", Skill.SliceObject, "Apple_1")
    act(sim, "robot1", Skill.DropHandObject, "ButterKnife_1")
    for k in (1, 2, 3):
        piece = f"Apple_1_Slice_{k}"
        act(sim, "robot1", Skill.GoToObject, piece)
        act(sim, "robot1", Skill.PickupObject, piece)
        act(sim, "robot1", Skill.GoToObject, "GarbageCan_1")
        act(sim, "robot1", Skill.ThrowObject, piece)
    report = check_goal(trash.goal, sim.state)
    assert [r.satisfied for r in report.results] == [1, 3]  # one apple sliced, three pieces in the bin
    assert goal_condition_rate(report.results) == 1.0 and success_rate(report.results) == 1.0


def test_counted_condition_contributes_its_share() -> None:
    state = WorldState.from_scene(load_scene("FloorPlan209"))
    goal = Goal.parse(["inside(2 of Vase, Box)", "switched_on(Television)"])
    state.move_object("Vase_1", "Box_1")
    report = check_goal(goal, state)
    assert goal_condition_rate(report.results) == pytest.approx(1 / 3)  # 1 of 2 vases, TV off
    assert success_rate(report.results) == 0.0


def test_no_conditions_scores_zero() -> None:
    assert success_rate([]) == 0.0 and goal_condition_rate([]) == 0.0


@given(st.lists(st.tuples(st.integers(0, 6), st.integers(1, 4)), min_size=1, max_size=8))
def test_gcr_is_a_share_and_sr_implies_full_gcr(pairs: list[tuple[int, int]]) -> None:
    conds = [ConditionOutcome(condition=f"c{i}", holds=s >= r, satisfied=s, required=r)
             for i, (s, r) in enumerate(pairs)]
    gcr = goal_condition_rate(conds)
    assert 0.0 <= gcr <= 1.0
    if success_rate(conds) == 1.0:
        assert gcr == 1.0
    else:
        assert gcr < 1.0


# ---- Exec ---------------------------------------------------------------------------------


def ev(kind: str, action: str, **data: object) -> TraceEvent:
    return TraceEvent(t=0.0, kind=kind, robot="robot1", data={"action": action, **data})  # type: ignore[arg-type]


TRACE = [
    ev("action_start", "GoToObject(Apple_1)"), ev("action_end", "GoToObject(Apple_1)", success=True),
    ev("action_start", "PickupObject(Apple_1)"),  # rejected at once: hand full
    ev("action_end", "PickupObject(Apple_1)", success=False, reason="hand_full"),
    ev("action_start", "DropHandObject(Knife_1)", recovery=True),  # a recovery action
    ev("action_end", "DropHandObject(Knife_1)", success=True, recovery=True),
    ev("action_start", "PickupObject(Apple_1)"), ev("action_end", "PickupObject(Apple_1)", success=True),
    ev("action_start", "GoToObject(Fridge_1)"),  # still driving when the episode stopped
    TraceEvent(t=1.0, kind="node", robot="robot1", data={"node": "x", "status": "RUNNING"}),
]


def test_exec_counts_every_started_action() -> None:
    assert exec_rate(TRACE) == pytest.approx(3 / 5)


def test_exec_without_navigation_is_smart_llms_count() -> None:
    assert exec_rate(TRACE, navigation=False) == pytest.approx(2 / 3)


def test_exec_is_undefined_without_actions() -> None:
    assert exec_rate([]) is None
    assert exec_from_outcomes([]) is None


def test_exec_from_the_simulators_outcomes() -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"))
    sim.execute("robot1", Action(skill=Skill.PickupObject, target="Apple_1"))  # not in reach: rejected
    sim.execute("robot1", Action(skill=Skill.GoToObject, target="Apple_1"))
    sim.execute("robot1", Action(skill=Skill.PickupObject, target="Apple_1"))
    assert [o.success for o in sim.outcomes] == [False, True, True]
    assert exec_from_outcomes(sim.outcomes) == pytest.approx(2 / 3)
    assert exec_from_outcomes(sim.outcomes, unfinished=1) == pytest.approx(2 / 4)
    assert exec_from_outcomes(sim.outcomes, navigation=False) == pytest.approx(1 / 2)


# ---- aggregation --------------------------------------------------------------------------


def episode(task: str, category: str, success: bool, *, gcr: float, exec: float = 1.0, actions: int = 4,
            makespan: float = 10.0, plan: float = 0.1, llm: int = 0, tokens: int = 0, seed: int = 0,
            error: str | None = None) -> Episode:
    return Episode(task=f"mace-thor/{task}", instruction="x", floor_plan="FloorPlan1", robots=("robot1",),
                   category=category, seed=seed, success=success, gcr=gcr, exec=exec, actions=actions,
                   makespan=makespan, plan_seconds=plan, llm_calls=llm, tokens=tokens, error=error)


EPISODES = [
    episode("p1", "parallel", True, gcr=1.0, exec=1.0, makespan=20.0, plan=0.2, llm=2, tokens=100),
    episode("p2", "parallel", False, gcr=0.5, exec=0.5, makespan=30.0, plan=0.4, llm=2, tokens=300),
    episode("t1", "temporal", True, gcr=1.0, exec=0.75, makespan=40.0, plan=0.1, llm=4, tokens=200),
    episode("t2", "temporal", False, gcr=0.0, exec=0.0, actions=0, makespan=0.0, plan=0.3,
            error="PlanningError: no plan"),
]


def test_summary_numbers() -> None:
    s = summarize(EPISODES)
    assert s.suite == "mace-thor" and s.n == 4
    assert s.sr == 0.5 and s.gcr == pytest.approx(2.5 / 4)
    assert s.exec == pytest.approx((1.0 + 0.5 + 0.75) / 3)  # t2 started no action: left out
    assert s.plan_seconds_p50 == pytest.approx(0.25)
    assert s.makespan_mean == pytest.approx(30.0)  # successful episodes only
    assert s.llm_calls_mean == 2.0 and s.tokens_mean == 150.0
    assert s.errors == 1
    assert list(s.by_category) == ["parallel", "temporal"]
    par, tem = s.by_category["parallel"], s.by_category["temporal"]
    assert (par.n, par.sr, par.gcr, par.exec) == (2, 0.5, 0.75, 0.75)
    assert (tem.n, tem.sr, tem.gcr, tem.exec) == (2, 0.5, 0.5, 0.75)


def test_summary_json_is_the_bench_contract() -> None:
    data = summarize(EPISODES).to_json()
    assert set(data) == CONTRACT | {"sr_ci", "collisions", "nav_waits", "nav_replans", "partly_done"}
    assert set(data["by_category"]["parallel"]) == {"n", "sr", "gcr", "exec", "sr_ci"}  # type: ignore[index]
    assert BenchSummary.model_validate(data) == summarize(EPISODES)


def test_empty_summary() -> None:
    s = summarize([])
    assert (s.n, s.sr, s.gcr, s.exec, s.errors, s.by_category) == (0, 0.0, 0.0, 0.0, 0, {})


def test_sr_ci_is_seeded_and_contains_the_mean() -> None:
    eps = [episode(f"t{i}", "parallel", i % 3 == 0, gcr=1.0) for i in range(30)]
    s = summarize(eps)
    lo, hi = s.sr_ci
    assert lo < s.sr < hi
    assert summarize(eps).sr_ci == s.sr_ci  # deterministic


def test_sr_ci_narrows_with_more_tasks() -> None:
    small = bootstrap_ci([[float(i % 2)] for i in range(10)])
    large = bootstrap_ci([[float(i % 2)] for i in range(200)])
    assert small[1] - small[0] > large[1] - large[0] > 0


def test_sr_ci_resamples_tasks_not_seeds() -> None:
    """Five seeds of one task are one sample: the interval cannot be narrower than that."""
    eps = [episode("t1", "temporal", s < 2, gcr=1.0, seed=s) for s in range(5)]
    assert summarize(eps).sr_ci == (0.4, 0.4)
    assert bootstrap_ci([[1.0] * 4]) == (1.0, 1.0)
    assert bootstrap_ci([]) == (0.0, 0.0)
