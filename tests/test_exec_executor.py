"""The executor loop: event-driven time, pose sampling, stop conditions, determinism,
replanning limits and failures, blackboard hygiene, typed configuration errors."""

from __future__ import annotations

import py_trees
import pytest

from emboteam.btc.errors import PlanCompileError
from emboteam.exec.executor import ExecutionConfigError, Executor, ExecutorSettings
from emboteam.sim import Breakdown, FaultConfig
from emboteam.world.checker import GoalValidationError
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from test_btc_plans import act, fresh_state, fridge_handoff, make_plan, real_replanner, salad, team_sim


def _long_drive():  # type: ignore[no-untyped-def]
    plan = make_plan(fresh_state("FloorPlan1", "1"), {"robot1": [act("GoToObject", "Fridge_1"),
                                                               act("OpenObject", "Fridge_1")]})
    return plan, Goal.parse("open(Fridge)")


def test_time_jumps_from_event_to_event_and_poses_are_sampled() -> None:
    plan, goal = _long_drive()
    res = Executor(team_sim("FloorPlan1", "1"), plan, goal).run()
    assert res.success
    drive = res.outcomes[0]
    assert drive.end - drive.start > 3.0
    assert res.ticks <= 8  # a handful of ticks for a multi-second drive, not one per step of time
    poses = [e for e in res.trace if e.kind == "pose" and drive.start < e.t < drive.end]
    assert len(poses) >= int((drive.end - drive.start) / 0.5) - 1
    xs = [e.data["x"] for e in poses]
    assert xs == sorted(xs, reverse=xs[0] > xs[-1])  # monotone along the straight drive
    starts = [e for e in res.trace if e.kind == "pose" and e.t == 0.0]
    assert starts  # poses at action starts


def test_time_limit_stops_the_run() -> None:
    plan, goal = fridge_handoff()
    res = Executor(team_sim("FloorPlan1", "1,2"), plan, goal, settings=ExecutorSettings(time_limit=3.0)).run()
    assert not res.success and res.stop_reason == "time_limit"
    assert res.makespan == pytest.approx(3.0)


def test_tick_limit_stops_the_run() -> None:
    plan, goal = fridge_handoff()
    res = Executor(team_sim("FloorPlan1", "1,2"), plan, goal, settings=ExecutorSettings(tick_limit=3)).run()
    assert res.stop_reason == "tick_limit" and res.ticks == 3


def test_same_seed_same_trace() -> None:
    plan, goal = salad()
    runs = [Executor(team_sim("FloorPlan1", "1,2,3", seed=7, faults=FaultConfig.level(0.3)), plan, goal,
                     replanner=real_replanner()).run() for _ in range(2)]
    assert [e.model_dump() for e in runs[0].trace] == [e.model_dump() for e in runs[1].trace]
    assert runs[0].outcomes == runs[1].outcomes


def test_blackboard_is_left_clean() -> None:
    plan, goal = fridge_handoff()
    clients = len(py_trees.blackboard.Blackboard.clients)
    res = Executor(team_sim("FloorPlan1", "1,2"), plan, goal, replanner=real_replanner()).run()
    assert res.success
    assert not [k for k in py_trees.blackboard.Blackboard.storage if k.startswith("/emboteam/")]
    assert len(py_trees.blackboard.Blackboard.clients) == clients


def test_node_status_changes_are_traced() -> None:
    plan, goal = _long_drive()
    res = Executor(team_sim("FloorPlan1", "1"), plan, goal).run()
    nodes = [e for e in res.trace if e.kind == "node"]
    core = [e.data["status"] for e in nodes if e.data["node"] == "GoToObject(Fridge_1)"]
    assert core[:2] == ["RUNNING", "SUCCESS"]
    kinds = {e.data["node"]: e.data["type"] for e in nodes}
    assert kinds["GoToObject(Fridge_1)"] == "Act" and kinds["team"] == "Parallel"  # the viewer tags them
    assert all(e.data["path"].startswith("team/isolate robot1") for e in nodes if e.robot)
    quiet = Executor(team_sim("FloorPlan1", "1"), plan, goal, settings=ExecutorSettings(record_nodes=False)).run()
    assert not [e for e in quiet.trace if e.kind == "node"]


def test_failing_replanner_leaves_the_old_tree_running() -> None:
    plan, goal = salad()

    def broken(*_: object) -> object:
        raise GoalValidationError("no fridge in this scene")

    sim = team_sim("FloorPlan1", "1,2,3", faults=FaultConfig(breakdowns=(Breakdown(robot="robot2", at=1.0),)))
    res = Executor(sim, plan, goal, replanner=broken).run()  # type: ignore[arg-type]
    assert not res.success and res.error is not None and "no fridge" in res.error
    failed = [e for e in res.trace if e.kind == "replan"]
    assert failed and failed[0].data["error"] == "no fridge in this scene"
    state = sim.observe()
    assert state.objects["Lettuce_1"].is_sliced and not state.objects["LightSwitch_1"].is_on


def test_replans_are_bounded() -> None:
    plan, goal = _long_drive()
    calls: list[object] = []

    def same_plan(*args: object) -> object:
        calls.append(args)
        return plan

    sim = team_sim("FloorPlan1", "1", faults=FaultConfig(action_failure=1.0))
    res = Executor(sim, plan, goal, replanner=same_plan, settings=ExecutorSettings(max_replans=2)).run()  # type: ignore[arg-type]
    assert not res.success and res.replans == 2 and len(calls) == 2
    assert res.stop_reason == "failed"


def test_configuration_errors_are_typed() -> None:
    plan, goal = fridge_handoff()
    sim = team_sim("FloorPlan1", "1,2")
    with pytest.raises(ExecutionConfigError):
        Executor(sim, plan, goal, settings=ExecutorSettings(time_limit=0))
    with pytest.raises(ExecutionConfigError):
        Executor(sim, plan, goal, joins=[(parse_team("3")[0], -1.0)])
    with pytest.raises(PlanCompileError):
        Executor(team_sim("FloorPlan1", "1"), plan, goal).run()


def test_join_parsing() -> None:
    from emboteam.errors import UnknownRobotError
    from emboteam.exec.executor import Join
    j = Join.parse("5@30", team=["robot1", "robot5"])
    assert j.at == 30.0 and j.profile.name == "robot5b" and j.profile.number == 5
    assert Join.parse("robot3@2.5").profile.name == "robot3"
    for bad in ("5", "5@", "5@soon", "5@-1"):
        with pytest.raises(ExecutionConfigError):
            Join.parse(bad)
    with pytest.raises(UnknownRobotError):
        Join.parse("99@3")


def test_result_fills_an_episode() -> None:
    from emboteam.exec.episode import Episode
    plan, goal = fridge_handoff()
    res = Executor(team_sim("FloorPlan1", "1,2", seed=1, faults=FaultConfig.level(0.2)), plan, goal).run()
    ep = Episode(task="adhoc", instruction="apple in the fridge", floor_plan="FloorPlan1",
                 robots=plan.robots, mode="full", **res.episode_fields())  # type: ignore[arg-type]
    assert ep.success == res.success and ep.actions == len(res.outcomes)
    assert ep.exec == pytest.approx(1 - res.failed_actions / res.actions)
    assert [c.condition for c in ep.conditions] == ["inside(Apple, Fridge)", "closed(Fridge)"]
    assert len(ep.trace) == len(res.trace)
