"""Every recovery path, driven by deterministic faults, seen in the trace: re-approach
after occlusion, back off on a busy spot, open a closed receptacle (from a false
precondition and from a typed failure), open the container hiding the target, free a
full hand, bounded retries after actuation faults, and breakdown -> replan."""

from __future__ import annotations

import pytest

from emboteam.btc.config import BTConfig
from emboteam.exec.executor import Executor, ExecutorSettings
from emboteam.exec.result import ExecutionResult
from emboteam.exec.trace import TraceEvent
from emboteam.hp.plan import MergedPlan
from emboteam.sim import Breakdown, FaultConfig, Simulator
from emboteam.sim.faults import FaultInjector
from emboteam.sim.setup import StateChange, apply_changes
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from test_btc_plans import act, fresh_state, fridge_handoff, make_plan, real_replanner, salad, team_sim


def recoveries(res: ExecutionResult, strategy: str | None = None) -> list[TraceEvent]:
    return [e for e in res.trace if e.kind == "recovery" and not e.data.get("gave_up")
            and (strategy is None or e.data["strategy"] == strategy)]


def recovery_actions(res: ExecutionResult, strategy: str) -> list[TraceEvent]:
    return [e for e in res.trace if e.kind == "action_start" and e.data.get("strategy") == strategy]


def ends(res: ExecutionResult, step: str) -> list[TraceEvent]:
    return [e for e in res.trace if e.kind == "action_end" and e.data.get("step") == step
            and not e.data.get("recovery")]


def test_occlusion_is_cleared_by_reapproaching() -> None:
    plan, goal = fridge_handoff()
    sim = team_sim("FloorPlan1", "1,2", seed=3, faults=FaultConfig(occlusion=1.0))
    res = Executor(sim, plan, goal).run()
    assert res.success
    occluded = [e for e in res.trace if e.kind == "action_end" and e.data["reason"] == "not_visible"]
    # robot1 opening, robot2 picking up and putting: each first interaction with a target
    # (robot1's close of the fridge it re-approached for the open is no longer occluded)
    assert len(occluded) == 3
    for o in occluded:
        step = o.data["step"]
        redo = [e for e in recovery_actions(res, "reapproach") if e.robot == o.robot and e.t >= o.t
                and e.data["step"] == step]
        assert redo and redo[0].data["skill"] == "GoToObject"
        assert ends(res, step)[-1].data["success"]


def _drawer_sim(seed: int = 0) -> tuple[Simulator, MergedPlan, Goal, object]:
    scene, team = load_scene("FloorPlan1"), parse_team("1,2")
    sim = Simulator(scene, team, seed=seed)
    apply_changes(sim.state, [StateChange(object="Drawer_5", is_open=True)])
    acts = {"robot1": [act("GoToObject", "Spoon_1"), act("PickupObject", "Spoon_1")],
            "robot2": [act("GoToObject", "Fork_1"), act("PickupObject", "Fork_1")]}
    return sim, acts, Goal.parse("held(Spoon); held(Fork)"), sim.state  # type: ignore[return-value]


def test_spot_busy_outside_the_lock_protocol_backs_off_and_wakes_up() -> None:
    """The planner's resources say the spoon and the fork are separate spots, but both
    lie in one drawer: the simulator rejects the second pickup (spot busy), the robot
    backs off for ``wait_seconds`` and retries; the executor wakes it up on time even
    when nothing else is pending."""
    sim, acts, goal, state = _drawer_sim()
    plan = make_plan(state, acts, resources={"robot1.2": ["Spoon_1"], "robot2.2": ["Fork_1"]})
    res = Executor(sim, plan, goal, settings=ExecutorSettings(config=BTConfig(wait_seconds=1.0))).run()
    assert res.success
    busy = [o for o in res.outcomes if o.reason is not None and o.reason.value == "spot_busy"]
    assert len(busy) == 1
    assert recoveries(res, "wait_spot")
    retry = [e for e in res.trace if e.kind == "action_start" and e.robot == busy[0].robot
             and e.t > busy[0].end and e.data["step"].endswith(".2")]
    assert retry[0].t == pytest.approx(busy[0].end + 1.0)
    others_done = max(o.end for o in res.outcomes if o.robot != busy[0].robot)
    assert others_done < retry[0].t  # only the timer was pending: the wait still woke up


def test_lock_protocol_prevents_the_busy_spot() -> None:
    sim, acts, goal, state = _drawer_sim()
    plan = make_plan(state, acts)  # spots predicted: both pickups are at Drawer_5
    res = Executor(sim, plan, goal).run()
    assert res.success
    assert not [o for o in res.outcomes if o.reason is not None and o.reason.value == "spot_busy"]
    waits = [e for e in res.trace if e.kind == "recovery" and e.data.get("strategy") == "acquire_spot"]
    assert not waits  # protocol waits are not recoveries
    locks = [e.data["value"] for e in res.trace if e.kind == "blackboard" and e.data["key"] == "lock_Drawer_5"]
    assert locks[:2] == ["robot1", None] and "robot2" in locks


def _fridge_solo(strip_literals: bool = False) -> tuple[MergedPlan, Goal]:
    plan = make_plan(fresh_state("FloorPlan1", "1"), {"robot1": [
        act("GoToObject", "Apple_1"), act("PickupObject", "Apple_1"), act("GoToObject", "Fridge_1"),
        act("PutObject", "Apple_1", "Fridge_1")]})
    if strip_literals:
        plan = plan.model_copy(update={"steps": tuple(s.model_copy(update={"pre": (), "post": ()})
                                                      for s in plan.steps)})
    return plan, Goal.parse("inside(Apple, Fridge)")


@pytest.mark.parametrize("strip", [False, True], ids=["false-precondition", "typed-failure"])
def test_closed_receptacle_is_opened(strip: bool) -> None:
    plan, goal = _fridge_solo(strip)
    res = Executor(team_sim("FloorPlan1", "1"), plan, goal).run()
    assert res.success
    if strip:  # no (is-open Fridge_1) to check: the put itself fails, typed
        assert any(o.reason is not None and o.reason.value == "receptacle_closed" for o in res.outcomes)
    else:  # Pre sees (is-open Fridge_1) false and never starts the doomed put
        assert all(o.success for o in res.outcomes)
    opened = recovery_actions(res, "open")
    assert [e.data["action"] for e in opened] == ["OpenObject(Fridge_1)"]
    assert recoveries(res, "open")[0].data["object"] == "Fridge_1"


def test_target_hidden_in_a_closed_fridge_gets_the_fridge_opened() -> None:
    plan = make_plan(fresh_state("FloorPlan1", "1"), {"robot1": [act("GoToObject", "Egg_1"),
                                                               act("PickupObject", "Egg_1")]})
    res = Executor(team_sim("FloorPlan1", "1"), plan, Goal.parse("held(Egg)")).run()
    assert res.success
    rec = recoveries(res, "open")
    assert rec and rec[0].data["object"] == "Fridge_1" and "inside closed Fridge_1" in rec[0].data["why"]
    assert [e.data["action"] for e in recovery_actions(res, "open")] == ["OpenObject(Fridge_1)"]


def test_full_hand_is_emptied_before_the_pickup() -> None:
    plan = make_plan(fresh_state("FloorPlan1", "1"), {"robot1": [
        act("GoToObject", "Apple_1"), act("PickupObject", "Apple_1"),
        act("GoToObject", "Tomato_1"), act("PickupObject", "Tomato_1")]})
    sim = team_sim("FloorPlan1", "1")
    res = Executor(sim, plan, Goal.parse("held(Tomato)")).run()
    assert res.success
    freed = recovery_actions(res, "free_hand")
    assert len(freed) == 1 and freed[0].data["target"] == "Apple_1"
    assert freed[0].data["skill"] in ("PutObject", "DropHandObject")
    state = sim.observe()
    assert state.robots["robot1"].holding == "Tomato_1" and state.objects["Apple_1"].held_by is None


def test_actuation_faults_are_retried_a_bounded_number_of_times() -> None:
    plan, goal = _fridge_solo()
    sim = team_sim("FloorPlan1", "1", faults=FaultConfig(action_failure=1.0))
    res = Executor(sim, plan, goal, settings=ExecutorSettings(config=BTConfig(max_attempts=3))).run()
    assert not res.success and res.stop_reason == "failed"
    attempts = ends(res, "robot1.1")
    assert len(attempts) == 3 and all(e.data["reason"] == "actuation_fault" for e in attempts)
    assert len(recoveries(res, "retry")) == 2
    assert not [e for e in res.trace if e.kind == "action_start" and e.data.get("step") == "robot1.2"]
    assert res.failed_robots == ("robot1",)
    gave_up = [e for e in res.trace if e.kind == "recovery" and e.data.get("gave_up")]
    assert gave_up and "3 attempts failed" in gave_up[-1].data["why"]


def test_an_actuation_fault_then_success() -> None:
    def fails(seed: int, k: int) -> bool:
        return FaultInjector(FaultConfig(action_failure=0.3), seed).action_fails("robot1", k)
    # a seed whose first action fails and the rest of the run's actions do not
    seed = next(s for s in range(1000) if fails(s, 0) and not any(fails(s, k) for k in range(1, 10)))
    plan, goal = _fridge_solo()
    res = Executor(team_sim("FloorPlan1", "1", seed=seed, faults=FaultConfig(action_failure=0.3)), plan,
                   goal).run()
    assert res.success
    first = ends(res, "robot1.1")
    assert [e.data["success"] for e in first] == [False, True]
    assert len(recoveries(res, "retry")) == 1


def test_breakdown_reallocates_work_through_a_replan() -> None:
    plan, goal = fridge_handoff()
    log: list = []
    sim = team_sim("FloorPlan1", "1,2", faults=FaultConfig(breakdowns=(Breakdown(robot="robot2", at=3.0),)))
    res = Executor(sim, plan, goal, replanner=real_replanner(log)).run()
    assert res.success, res.error
    assert res.broken_robots == ("robot2",) and "robot2" in res.failed_robots
    assert res.replans >= 1 and len(res.plans) == res.replans + 1
    replan = next(e for e in res.trace if e.kind == "replan")
    assert replan.data["robots"] == ["robot1"] and replan.data["error"] is None
    assert log[0][1] == ("robot1",)
    assert {str(c) for c in log[0][0].conditions} <= {"inside(Apple, Fridge)", "closed(Fridge)"}
    # the new plan's work went to robot1 and was done after the breakdown
    puts = [o for o in res.outcomes if o.robot == "robot1" and o.action.skill.value == "PutObject" and o.success]
    assert puts and puts[0].start > 3.0
    assert sim.observe().objects["Apple_1"].parent == "Fridge_1"


def test_breakdown_without_replanner_fails_and_does_not_hang() -> None:
    plan, goal = fridge_handoff()
    sim = team_sim("FloorPlan1", "1,2", faults=FaultConfig(breakdowns=(Breakdown(robot="robot1", at=1.0),)))
    res = Executor(sim, plan, goal).run()
    assert not res.success and res.stop_reason == "failed"
    assert set(res.failed_robots) == {"robot1", "robot2"}
    why = [e.data["why"] for e in res.trace if e.kind == "recovery" and e.robot == "robot2" and e.data.get("gave_up")]
    assert any("robot1.2 will not happen" in w for w in why)
    gave_up = [(e.robot, e.data.get("step"), e.data["why"]) for e in res.trace
               if e.kind == "recovery" and e.data.get("gave_up")]
    assert len(gave_up) == len(set(gave_up)), gave_up  # each give-up is recorded once
    assert res.makespan < 30


def test_one_robots_failure_does_not_stop_the_others() -> None:
    plan, goal = salad()
    sim = team_sim("FloorPlan1", "1,2,3", faults=FaultConfig(breakdowns=(Breakdown(robot="robot2", at=1.0),)))
    res = Executor(sim, plan, goal).run()
    assert not res.success
    assert res.failed_robots == ("robot2",)
    state = sim.observe()
    assert state.objects["Lettuce_1"].is_sliced and not state.objects["LightSwitch_1"].is_on
    # sliced, off and closed (the fridge was never opened) hold; the tomato is not in
    assert res.report is not None and res.gcr == pytest.approx(0.75)


def test_joining_robot_gets_work() -> None:
    plan = make_plan(fresh_state("FloorPlan1", "1"), {"robot1": [
        act("GoToObject", "Fridge_1"), act("OpenObject", "Fridge_1"), act("GoToObject", "Apple_1"),
        act("PickupObject", "Apple_1"), act("GoToObject", "Fridge_1"), act("PutObject", "Apple_1", "Fridge_1"),
        act("CloseObject", "Fridge_1"), act("GoToObject", "LightSwitch_1"), act("SwitchOff", "LightSwitch_1")]})
    goal = Goal.parse("inside(Apple, Fridge); closed(Fridge); off(LightSwitch)")
    robot3 = parse_team("3")[0]
    log: list = []
    sim = team_sim("FloorPlan1", "1")
    res = Executor(sim, plan, goal, replanner=real_replanner(log), joins=[(robot3, 2.0)]).run()
    assert res.success, res.error
    assert res.joined_robots == ("robot3",)
    replan = next(e for e in res.trace if e.kind == "replan")
    assert replan.t == pytest.approx(2.0, abs=5.0) and "robot3 joined" in replan.data["reason"]
    assert set(log[0][1]) == {"robot1", "robot3"}
    worked = [o for o in res.outcomes if o.robot == "robot3" and o.success]
    assert worked and min(o.start for o in worked) >= 2.0
    joined = [e for e in res.trace if e.kind == "sim" and e.data["kind"] == "join"]
    assert joined and joined[0].robot == "robot3"
