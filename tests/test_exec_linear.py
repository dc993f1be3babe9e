"""The baselines without behavior trees: the no-BTC ablation (linear, after-respecting)
and SMART-LLM's unsynchronised per-robot sequences."""

from __future__ import annotations

from emboteam.exec.linear import run_linear, run_sequences
from emboteam.sim import FaultConfig
from test_btc_plans import fridge_handoff, salad, team_sim


def test_linear_runs_the_plan_and_respects_after() -> None:
    plan, goal = fridge_handoff()
    res = run_linear(team_sim("FloorPlan1", "1,2"), plan, goal)
    assert res.success and res.mode == "linear" and res.stop_reason == "plan_done"
    start = {e.data["step"]: e.t for e in res.trace if e.kind == "action_start"}
    end = {e.data["step"]: e.t for e in res.trace if e.kind == "action_end"}
    assert start["robot2.4"] >= end["robot1.2"] and start["robot1.3"] >= end["robot2.4"]
    assert {e.kind for e in res.trace} >= {"action_start", "action_end", "pose"}


def test_linear_skips_failed_actions_without_checks_or_recovery() -> None:
    plan, goal = fridge_handoff()
    res = run_linear(team_sim("FloorPlan1", "1,2", faults=FaultConfig(action_failure=1.0)), plan, goal)
    assert not res.success and res.stop_reason == "plan_done"
    assert len(res.outcomes) == len(plan.steps)  # every step tried exactly once
    assert res.failed_actions == len(plan.steps)
    assert not [e for e in res.trace if e.kind in ("recovery", "replan", "node", "blackboard")]
    # plain waiting: the consumer still waited for its (failed) producer to end
    start = {e.data["step"]: e.t for e in res.trace if e.kind == "action_start"}
    end = {e.data["step"]: e.t for e in res.trace if e.kind == "action_end"}
    assert start["robot2.4"] >= end["robot1.2"]


def test_sequences_do_not_synchronise() -> None:
    plan, goal = fridge_handoff()
    seqs = {r: [s.action for s in plan.for_robot(r)] for r in plan.robots}
    res = run_sequences(team_sim("FloorPlan1", "1,2"), seqs, goal)
    assert res.mode == "sequences"
    # robot2 puts as soon as it gets there, before robot1 has opened the fridge
    opened = next(o for o in res.outcomes if o.action.skill.value == "OpenObject")
    put = next(o for o in res.outcomes if o.action.skill.value == "PutObject")
    assert put.start < opened.end
    assert put.reason is not None and put.reason.value == "receptacle_closed"
    assert not res.success


def test_the_tree_beats_the_linear_ablation_under_faults() -> None:
    from emboteam.exec.executor import Executor
    plan, goal = salad()
    bt = lin = 0
    for seed in range(8):
        faults = FaultConfig.level(0.2)
        bt += Executor(team_sim("FloorPlan1", "1,2,3", seed=seed, faults=faults), plan, goal).run().success
        lin += run_linear(team_sim("FloorPlan1", "1,2,3", seed=seed, faults=faults), plan, goal).success
    assert bt >= 7 and bt - lin >= 3
