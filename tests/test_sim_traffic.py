"""Robots on the grid: one cell each, reservations, waiting, yielding, breakdowns, and the
independent trace checker that counts conflicts."""

from __future__ import annotations

import itertools

from emboteam.exec.nav_check import check_motion
from emboteam.sim import Breakdown, FaultConfig, Simulator
from emboteam.sim.simulator import NAV_RETRY_SECONDS
from emboteam.sim.traffic import INF, Reservations, Step, intervals
from emboteam.world import Action, FailureReason, WorldState, load_scene, parse_team
from emboteam.world.actions import Skill as S
from emboteam.world.navgrid import NavGrid, largest_component, load_grid


def _positions_over_time(sim: Simulator, robots: list[str], until: float, dt: float = 0.05
                         ) -> list[dict[str, tuple[float, float]]]:
    out = []
    t = 0.0
    while t <= until:
        out.append({r: sim.traffic.point(r, t) for r in robots})
        t += dt
    return out


def _crossing_drives(avoidance: bool) -> Simulator:
    """Four robots in FloorPlan401's small bathroom, each sent to an object on the far side
    of the others."""
    sim = Simulator(load_scene("FloorPlan401"), parse_team("1,2,3,4"), avoidance=avoidance)
    targets = ["Toilet_1", "Sink_1", "Bathtub_1", "Towel_1"]
    robots = sorted(sim.state.robots)
    for robot, target in zip(robots, reversed(targets), strict=True):
        sim.start(robot, Action(skill=S.GoToObject, target=target))
    sim.run_until_idle()
    for robot, target in zip(robots, targets, strict=True):
        sim.start(robot, Action(skill=S.GoToObject, target=target))
    sim.run_until_idle()
    return sim


def test_reservations_rule_out_shared_cells_and_swaps() -> None:
    path = [Step(0.0, (0, 0), 0), Step(0.25, (0, 1), 0), Step(0.5, (0, 1), 1)]
    held = intervals(path)
    assert held == [((0, 0), 0.0, 0.25), ((0, 1), 0.0, INF)]  # a move holds both cells
    res = Reservations()
    for cell, a, b in held:
        res.add("a", cell, a, b)
    assert not res.free((0, 0), 0.1, 0.2, "b")  # a swap would enter (0, 0) during the move
    assert res.free((0, 0), 0.25, 0.5, "b")
    assert not res.free((0, 1), 5.0, 6.0, "b")  # parked there for good
    res.release_after("a", 1.0)
    assert res.free((0, 1), 1.0, 2.0, "b")


def test_with_avoidance_no_two_robots_share_a_cell_and_the_checker_agrees() -> None:
    sim = _crossing_drives(avoidance=True)
    record = sim.nav_record()
    assert record["moves"], "the robots did move"
    check = check_motion(record)
    assert check.collisions == 0, check
    robots = sorted(sim.state.robots)
    for sample in _positions_over_time(sim, robots, sim.now):
        cells = [sim.traffic.nav.grid.nearest(p) for p in sample.values()]
        # sampled positions mid-move may round either way; distinct robots stay >= one cell
        # apart in the checker's sense, which the checker verified above
        assert len(cells) == len(robots)
    assert all(o.success for o in sim.outcomes)


def test_without_avoidance_the_checker_counts_collisions() -> None:
    sim = _crossing_drives(avoidance=False)
    check = check_motion(sim.nav_record())
    assert check.collisions > 0
    assert sim.traffic.waits == 0 and sim.traffic.replans == 0


def test_the_checker_sees_vertex_and_edge_conflicts_in_a_made_up_record() -> None:
    record = {
        "starts": {"a": [0.0, 0, 0], "b": [0.0, 0, 1], "c": [0.0, 5, 5], "d": [0.0, 5, 7]},
        "moves": [["a", 0.0, 0.25, 0, 0, 0, 1], ["b", 0.0, 0.25, 0, 1, 0, 0],  # swap
                  ["c", 1.0, 1.25, 5, 5, 5, 6], ["d", 1.0, 1.25, 5, 7, 5, 6]],  # same cell
    }
    check = check_motion(record)
    assert len(check.edge) == 1 and check.edge[0][:2] == ("a", "b")
    assert any(v[:2] == ("c", "d") for v in check.vertex)
    clean = {"starts": {"a": [0.0, 0, 0], "b": [0.0, 0, 2]},
             "moves": [["a", 0.0, 0.25, 0, 0, 0, 1], ["b", 1.0, 1.25, 0, 2, 0, 3]]}
    assert check_motion(clean).collisions == 0


def _doorway() -> tuple[WorldState, tuple[int, int], set[tuple[int, int]]]:
    """FloorPlan5's grid has a one-cell doorway at (3, 1): the 37 cells by the counters lie
    behind it. Robot 2 is parked in it, robot 1 starts on the other side."""
    grid = load_grid("FloorPlan5")
    door = (3, 1)
    assert door in grid.cells
    other_side = largest_component(set(grid.cells) - {door})
    state = WorldState.from_scene(load_scene("FloorPlan5"), parse_team("1,2"))
    state.robots["robot2"].position = NavGrid.point(door)
    state.robots["robot1"].position = NavGrid.point(min(other_side))
    return state, door, other_side


def test_an_idle_robot_parked_in_the_doorway_steps_aside() -> None:
    state, _door, other_side = _doorway()
    sim = Simulator(load_scene("FloorPlan5"), parse_team("1,2"), state=state, avoidance=True)
    out = sim.execute("robot1", Action(skill=S.GoToObject, target="Apple_1"))
    assert out.success, out
    assert sim.traffic.yields == 1 and any(e.kind == "nav-yield" for e in sim.events)
    assert check_motion(sim.nav_record()).collisions == 0
    assert sim.traffic.nav.grid.cell_at(sim.state.robots["robot1"].position) not in other_side


def test_a_broken_robot_in_the_doorway_walls_the_way_off_with_a_typed_failure() -> None:
    """A broken robot never moves: a drive to a target whose every pose lies behind it
    fails ``not_reachable`` at once, naming it (waiting could never help), instead of
    waiting out its retries or hanging."""
    state, door, other_side = _doorway()
    state.robots["robot2"].down = True
    sim = Simulator(load_scene("FloorPlan5"), parse_team("1,2"), state=state, avoidance=True)
    egg = sim.state.objects["Egg_1"]
    assert all(p.cell not in other_side for p in sim.traffic.nav.poses_for((egg.position[0], egg.position[2])))
    out = sim.execute("robot1", Action(skill=S.GoToObject, target="Egg_1"))
    assert not out.success and out.reason is FailureReason.NOT_REACHABLE
    assert "robot2 broke down" in out.message
    assert out.end - out.start < NAV_RETRY_SECONDS
    assert sim.traffic.cell("robot2", sim.now).cell == door


def test_a_drive_past_a_broken_robot_ends_at_a_pose_on_its_own_side() -> None:
    """The apple is within reach from cells on both sides of the doorway: with a broken
    robot in it, the drive ends at a pose it can reach instead of waiting for the door."""
    state, _door, other_side = _doorway()
    state.robots["robot2"].down = True
    sim = Simulator(load_scene("FloorPlan5"), parse_team("1,2"), state=state, avoidance=True)
    out = sim.execute("robot1", Action(skill=S.GoToObject, target="Apple_1"))
    assert out.success, out
    assert sim.traffic.nav.grid.cell_at(sim.state.robots["robot1"].position) in other_side
    assert sim.state.in_reach("robot1", "Apple_1")


def test_a_broken_robot_is_an_obstacle_and_others_replan_around_it() -> None:
    scene = load_scene("FloorPlan401")
    team = parse_team("1,2")
    sim = Simulator(scene, team, faults=FaultConfig(breakdowns=(Breakdown(robot="robot2", at=0.6),)),
                    avoidance=True)
    sim.start("robot2", Action(skill=S.GoToObject, target="Toilet_1"))
    sim.start("robot1", Action(skill=S.GoToObject, target="Toilet_1"))
    sim.run_until_idle()
    broken = sim.traffic.cell("robot2", sim.now).cell
    assert sim.state.robots["robot2"].down
    for later in itertools.chain([sim.now + 1.0]):
        assert sim.traffic.cell("robot2", later).cell == broken
    assert check_motion(sim.nav_record()).collisions == 0
    r1 = sim.state.robots["robot1"]
    assert sim.traffic.nav.grid.cell_at(r1.position) != broken
