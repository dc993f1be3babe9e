"""Simulated time, concurrency, contention at interaction spots, and seeded faults."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from emboteam.errors import UnknownObjectError, UnknownRobotError
from emboteam.sim import Breakdown, FaultConfig, ObjectMove, RobotBusyError, Simulator
from emboteam.sim.durations import (
    ACTION_SECONDS,
    FAILED_ACTION_SECONDS,
    MIN_NAVIGATION_SECONDS,
    navigation_seconds,
)
from emboteam.world import (
    Action,
    ActionOutcome,
    FailureReason,
    RobotProfile,
    Skill,
    WorldState,
    load_catalogue,
    load_scene,
    parse_team,
)
from emboteam.world.environment import Environment
from emboteam.world.navgrid import NavGrid
from emboteam.world.navigation import navigator

S = Skill
R = FailureReason
Snapshot = Callable[[WorldState], dict[str, Any]]


def act(sim: Simulator, robot: str, skill: Skill, target: str, receptacle: str | None = None) -> ActionOutcome:
    return sim.execute(robot, Action(skill=skill, target=target, receptacle=receptacle))


def ok(sim: Simulator, robot: str, skill: Skill, target: str, receptacle: str | None = None) -> ActionOutcome:
    out = act(sim, robot, skill, target, receptacle)
    assert out.success, str(out)
    return out


def test_simulator_is_an_environment(sim1: Simulator) -> None:
    assert isinstance(sim1, Environment)


# ---- durations ---------------------------------------------------------------------------


def test_navigation_follows_the_grid_to_the_interaction_pose() -> None:
    """A drive is a shortest sequence of 0.25 m moves and 90° turns on the reachable grid
    (one agent action each, 0.25 s at 1 m/s), never shorter than the Manhattan distance
    between the start cell and the pose cell (it was that distance to the object before the
    grid: intended change)."""
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"))  # alone: no one to drive round
    x0, z0 = sim.state.robots["robot1"].position
    fx, _, fz = sim.state.objects["Fridge_1"].position
    nav = navigator("FloorPlan1")
    best = nav.nearest_pose(nav.cell_of((x0, z0)), (fx, fz))
    assert best is not None
    pose = best[0]
    path = nav.path(nav.cell_of((x0, z0)), pose)
    assert path is not None and len(path) - 1 == best[1]
    out = ok(sim, "robot1", S.GoToObject, "Fridge_1")
    assert out.start == 0.0
    assert out.end == pytest.approx(0.25 * (len(path) - 1))
    px, pz = NavGrid.point(pose.cell)
    assert out.end >= abs(px - x0) + abs(pz - z0) - 1e-9
    assert out.end == pytest.approx(navigation_seconds((x0, z0), (fx, fz), 1.0, "FloorPlan1"))
    assert sim.state.robots["robot1"].position == (px, pz)
    assert sim.now == pytest.approx(out.end)


def test_a_faster_robot_arrives_sooner() -> None:
    fast = RobotProfile(name="fast", skills=frozenset(Skill), mass_capacity=10.0, speed=2.0)
    slow = RobotProfile(name="slow", skills=frozenset(Skill), mass_capacity=10.0, speed=1.0)
    sim = Simulator(load_scene("FloorPlan1"), (fast,))
    sim_slow = Simulator(load_scene("FloorPlan1"), (slow,))
    t_fast = ok(sim, "fast", S.GoToObject, "Fridge_1").end
    t_slow = ok(sim_slow, "slow", S.GoToObject, "Fridge_1").end
    assert t_fast == pytest.approx(t_slow / 2)


def test_short_hops_take_the_minimum(sim1: Simulator) -> None:
    ok(sim1, "robot1", S.GoToObject, "Apple_1")
    out = ok(sim1, "robot1", S.GoToObject, "Apple_1")
    assert out.end - out.start == MIN_NAVIGATION_SECONDS


@pytest.mark.parametrize(("skill", "target"), [
    (S.PickupObject, "Apple_1"), (S.OpenObject, "Fridge_1"), (S.SwitchOff, "LightSwitch_1"),
    (S.BreakObject, "Vase_1"), (S.PushObject, "Stool_1"),
])
def test_manipulation_takes_its_fixed_duration(sim1: Simulator, skill: Skill, target: str) -> None:
    ok(sim1, "robot1", S.GoToObject, target)
    out = ok(sim1, "robot1", skill, target)
    assert out.end - out.start == ACTION_SECONDS[skill]


def test_a_rejected_action_still_costs_time(sim1: Simulator) -> None:
    out = act(sim1, "robot1", S.PickupObject, "Apple_1")
    assert not out.success and out.end - out.start == FAILED_ACTION_SECONDS


# ---- concurrency -------------------------------------------------------------------------


def test_two_robots_act_at_the_same_time(sim1: Simulator) -> None:
    sim1.start("robot1", Action(skill=S.GoToObject, target="Fridge_1"))
    sim1.start("robot2", Action(skill=S.GoToObject, target="Toaster_1"))
    assert sim1.busy("robot1") and sim1.busy("robot2")
    outs = sim1.run_until_idle()
    assert {o.robot for o in outs} == {"robot1", "robot2"}
    a, b = outs
    assert a.start == b.start == 0.0 and a.end <= b.end, "outcomes come in time order"
    assert min(a.end, b.end) > max(a.start, b.start), "the two actions overlap in time"
    assert sim1.now == pytest.approx(b.end)
    assert not sim1.busy("robot1") and sim1.running("robot1") is None


def test_advance_reports_only_what_ended(sim1: Simulator) -> None:
    sim1.start("robot1", Action(skill=S.GoToObject, target="Fridge_1"))
    end = sim1.next_event_time()
    assert end is not None and end > 1.0
    assert sim1.advance(1.0) == [] and sim1.now == 1.0
    assert sim1.running("robot1") == Action(skill=S.GoToObject, target="Fridge_1")
    # the pose is interpolated along the drive meanwhile
    (x0, z0), (x1, z1) = sim1.state.robots["robot1"].position, sim1.pose("robot1")
    assert (x0, z0) != (x1, z1)
    outs = sim1.advance(end)
    assert [o.robot for o in outs] == ["robot1"] and sim1.next_event_time() is None


def test_starting_a_busy_robot_is_a_caller_error(sim1: Simulator) -> None:
    sim1.start("robot1", Action(skill=S.GoToObject, target="Fridge_1"))
    with pytest.raises(RobotBusyError):
        sim1.start("robot1", Action(skill=S.GoToObject, target="Apple_1"))
    with pytest.raises(UnknownRobotError):
        sim1.start("robot9", Action(skill=S.GoToObject, target="Apple_1"))


def test_a_robot_joins_mid_episode(sim1: Simulator) -> None:
    sim1.advance(3.0)
    newcomer = parse_team("5")[0]
    sim1.add_robot(newcomer)
    starts = {r.position for r in sim1.state.robots.values()}
    assert len(starts) == 3, "the newcomer starts on its own cell"
    assert sim1.events[-1].kind == "join" and sim1.events[-1].t == 3.0
    ok(sim1, "robot5", S.GoToObject, "Apple_1")
    with pytest.raises(UnknownRobotError):
        sim1.add_robot(newcomer)


# ---- contention --------------------------------------------------------------------------


def test_second_robot_at_a_busy_spot_gets_spot_busy(sim1: Simulator, state_snapshot: Snapshot) -> None:
    ok(sim1, "robot1", S.GoToObject, "Fridge_1")
    ok(sim1, "robot2", S.GoToObject, "Fridge_1")
    sim1.start("robot1", Action(skill=S.OpenObject, target="Fridge_1"))
    assert sim1.locks == {"Fridge_1": "robot1"}
    before = state_snapshot(sim1.state)
    sim1.start("robot2", Action(skill=S.OpenObject, target="Fridge_1"))
    first = sim1.advance(sim1.now + FAILED_ACTION_SECONDS)
    assert [(o.robot, o.reason) for o in first] == [("robot2", R.SPOT_BUSY)]
    assert "robot1 is using Fridge_1" in first[0].message
    assert state_snapshot(sim1.state) == before
    rest = sim1.run_until_idle()
    assert [(o.robot, o.success) for o in rest] == [("robot1", True)] and sim1.locks == {}


def test_an_apple_in_the_fridge_shares_the_fridge_spot(sim1: Simulator) -> None:
    ok(sim1, "robot1", S.GoToObject, "Fridge_1")
    ok(sim1, "robot1", S.OpenObject, "Fridge_1")
    ok(sim1, "robot2", S.GoToObject, "Fridge_1")
    assert sim1.state.spot_of("Egg_1") == "Fridge_1"
    sim1.start("robot1", Action(skill=S.PickupObject, target="Egg_1"))
    sim1.start("robot2", Action(skill=S.CloseObject, target="Fridge_1"))
    outs = sim1.run_until_idle()
    assert {o.robot: o.reason for o in outs} == {"robot2": R.SPOT_BUSY, "robot1": None}
    assert sim1.state.robots["robot1"].holding == "Egg_1" and sim1.state.objects["Fridge_1"].is_open


def test_different_spots_do_not_contend(sim1: Simulator) -> None:
    ok(sim1, "robot1", S.GoToObject, "Apple_1")
    ok(sim1, "robot2", S.GoToObject, "Tomato_1")
    sim1.start("robot1", Action(skill=S.PickupObject, target="Apple_1"))
    sim1.start("robot2", Action(skill=S.PickupObject, target="Tomato_1"))
    assert all(o.success for o in sim1.run_until_idle())


# ---- seeded faults -----------------------------------------------------------------------

SCRIPT = [(S.GoToObject, "Apple_1", None), (S.PickupObject, "Apple_1", None),
          (S.GoToObject, "Fridge_1", None), (S.OpenObject, "Fridge_1", None),
          (S.PutObject, "Apple_1", "Fridge_1"), (S.CloseObject, "Fridge_1", None)]


def _faulty_run(seed: int, p: float = 0.3, rounds: int = 6) -> list[tuple[str, bool, str | None, float]]:
    """Two robots each repeat the script (retrying nothing): a fixed action sequence."""
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1,2"), seed=seed, faults=FaultConfig.level(p))
    for _ in range(rounds):
        for robot in ("robot1", "robot2"):
            for skill, target, rec in SCRIPT:
                act(sim, robot, skill, target, rec)
    return [(o.robot, o.success, o.reason.value if o.reason else None, o.end) for o in sim.outcomes]


def test_same_seed_same_outcomes() -> None:
    assert _faulty_run(7) == _faulty_run(7)


def test_different_seeds_differ() -> None:
    runs = {tuple(_faulty_run(seed)) for seed in range(4)}
    assert len(runs) == 4


def test_fault_level_zero_is_fault_free() -> None:
    run = _faulty_run(3, p=0.0, rounds=1)
    assert [ok for robot, ok, _, _ in run if robot == "robot1"] == [True] * len(SCRIPT)


@pytest.mark.parametrize("p", [0.1, 0.3])
def test_failure_rate_matches_the_configured_probability(p: float) -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"), seed=11,
                    faults=FaultConfig(action_failure=p))
    n = 2000
    for i in range(n):
        act(sim, "robot1", S.GoToObject, "Apple_1" if i % 2 else "Fridge_1")
    rate = sum(o.reason is R.ACTUATION_FAULT for o in sim.outcomes) / n
    # binomial standard error at n=2000 is at most 0.011: allow four of them
    assert abs(rate - p) < 0.045, rate


def test_one_robots_faults_do_not_depend_on_the_others() -> None:
    """Draws are keyed by (seed, robot, its own action index): adding robot2's actions
    leaves robot1's outcomes as they were."""
    def robot1_outcomes(with_robot2: bool) -> list[bool]:
        sim = Simulator(load_scene("FloorPlan1"), parse_team("1,2"), seed=5,
                        faults=FaultConfig(action_failure=0.4))
        for i in range(40):
            act(sim, "robot1", S.GoToObject, "Apple_1" if i % 2 else "Fridge_1")
            if with_robot2:
                act(sim, "robot2", S.GoToObject, "Toaster_1" if i % 2 else "Fridge_1")
        return [o.success for o in sim.outcomes if o.robot == "robot1"]
    assert robot1_outcomes(True) == robot1_outcomes(False)


def test_occlusion_is_cleared_by_a_re_approach(state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"), faults=FaultConfig(occlusion=1.0))
    ok(sim, "robot1", S.GoToObject, "Apple_1")
    before = state_snapshot(sim.state)
    for _ in range(2):  # occluded until the robot moves
        out = act(sim, "robot1", S.PickupObject, "Apple_1")
        assert out.reason is R.NOT_VISIBLE and "re-approach" in out.message
    assert state_snapshot(sim.state) == before
    assert any(e.kind == "occlusion" for e in sim.events)
    ok(sim, "robot1", S.GoToObject, "Apple_1")
    ok(sim, "robot1", S.PickupObject, "Apple_1")


def test_breakdown_fails_the_action_in_flight_and_drops_the_load(state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1,2"),
                    faults=FaultConfig(breakdowns=(Breakdown(robot="robot1", at=6.0),)))
    ok(sim, "robot1", S.GoToObject, "Apple_1")
    ok(sim, "robot1", S.PickupObject, "Apple_1")
    t0 = sim.now
    assert t0 < 6.0
    sim.start("robot1", Action(skill=S.GoToObject, target="Shelf_1"))  # a 5 s drive
    where_at_6 = None
    outs = []
    while sim.busy("robot1"):
        nxt = sim.next_event_time()
        assert nxt is not None
        if where_at_6 is None and nxt >= 6.0:
            sim.advance(6.0 - 1e-6)
            where_at_6 = sim.pose("robot1")
        outs += sim.advance(nxt)
    assert [(o.robot, o.reason, o.end) for o in outs] == [("robot1", R.ROBOT_DOWN, 6.0)]
    r, apple = sim.state.robots["robot1"], sim.state.objects["Apple_1"]
    assert r.down and r.holding is None
    assert apple.held_by is None and apple.parent == "Floor_1"
    assert where_at_6 is not None and r.position == pytest.approx(where_at_6, abs=1e-3), "stops mid-drive"
    assert (apple.position[0], apple.position[2]) == r.position
    assert [e.kind for e in sim.events][-2:] == ["breakdown", "drop"]
    assert sim.state.invariant_violations() == []
    before = state_snapshot(sim.state)
    assert act(sim, "robot1", S.GoToObject, "Apple_1").reason is R.ROBOT_DOWN
    assert state_snapshot(sim.state) == before
    ok(sim, "robot2", S.GoToObject, "Apple_1")  # the others carry on
    ok(sim, "robot2", S.PickupObject, "Apple_1")


def test_breakdown_releases_the_spot() -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1,2"),
                    faults=FaultConfig(breakdowns=(Breakdown(robot="robot1", at=1.0),)))
    sim.start("robot1", Action(skill=S.SwitchOff, target="LightSwitch_1"))  # not in reach: fails
    sim.run_until_idle()
    assert sim.locks == {}


def test_someone_else_moves_an_object() -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"),
                    faults=FaultConfig(moves=(ObjectMove(object="Apple_1", at=1.0, to="CounterTop_1"),)))
    ok(sim, "robot1", S.GoToObject, "Apple_1")  # drives to where the apple was at the start
    assert sim.now > 1.0
    assert sim.state.objects["Apple_1"].parent == "CounterTop_1"
    assert sim.state.robots["robot1"].at is None
    assert any(e.kind == "moved" and "Apple_1 -> CounterTop_1" in e.detail for e in sim.events)
    assert act(sim, "robot1", S.PickupObject, "Apple_1").reason is R.NOT_REACHABLE
    ok(sim, "robot1", S.GoToObject, "Apple_1")
    ok(sim, "robot1", S.PickupObject, "Apple_1")


def test_random_moves_are_valid_and_seeded() -> None:
    def destination(seed: int) -> str | None:
        sim = Simulator(load_scene("FloorPlan1"), parse_team("1"), seed=seed,
                        faults=FaultConfig(moves=(ObjectMove(object="Apple_1", at=0.0),)))
        sim.advance(0.0)
        return sim.state.objects["Apple_1"].parent
    dests = [destination(s) for s in range(8)]
    assert dests == [destination(s) for s in range(8)]
    assert len(set(dests)) > 1
    cat, state = load_catalogue(), WorldState.from_scene(load_scene("FloorPlan1"))
    for d in dests:
        assert d is not None and d != "CounterTop_2"
        rec = state.objects[d]
        assert cat.can_place("Apple", rec.type)
        assert rec.type not in cat.must_be_open or rec.is_open


def test_moves_of_held_objects_are_skipped() -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"),
                    faults=FaultConfig(moves=(ObjectMove(object="Apple_1", at=5.0, to="Pan_1"),)))
    ok(sim, "robot1", S.GoToObject, "Apple_1")
    ok(sim, "robot1", S.PickupObject, "Apple_1")
    assert sim.now < 5.0
    sim.advance(10.0)
    assert sim.state.robots["robot1"].holding == "Apple_1"
    assert any(e.kind == "move-skipped" for e in sim.events)


@pytest.mark.parametrize("move", [ObjectMove(object="Unicorn_1", at=1.0),
                                  ObjectMove(object="Apple_1", at=1.0, to="Nowhere_1")])
def test_faults_naming_unknown_objects_are_typed_errors(move: ObjectMove) -> None:
    with pytest.raises(UnknownObjectError):
        Simulator(load_scene("FloorPlan1"), parse_team("1"), faults=FaultConfig(moves=(move,)))


def test_moves_may_name_pieces_that_do_not_exist_yet() -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"),
                    faults=FaultConfig(moves=(ObjectMove(object="Apple_1_Slice_1", at=0.0),)))
    sim.advance(1.0)
    assert [e.kind for e in sim.events] == ["move-skipped"]
