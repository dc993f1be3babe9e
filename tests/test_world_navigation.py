"""The navigation model: ALFRED's reachable grid in the package, interaction poses, grid
paths and their lengths, the per-scene fit report and the capability check."""

from __future__ import annotations

import itertools
import json
import math
from importlib import resources

import pytest
from typer.testing import CliRunner

from emboteam.cli import app
from emboteam.errors import EXIT_BAD_INPUT
from emboteam.sim.durations import navigation_seconds
from emboteam.world.goals import Goal
from emboteam.world.navfit import UnreachableObjectError, check_reachable, nav_fit
from emboteam.world.navgrid import GRID, STEPS, NavGrid, load_grid, turns_between
from emboteam.world.navigation import navigator
from emboteam.world.poses import REACH
from emboteam.world.scene import load_scene, scene_ids

runner = CliRunner()


def test_every_floor_plan_has_a_grid_and_the_licence_ships() -> None:
    for fp in scene_ids():
        grid = load_grid(fp)
        assert len(grid.cells) >= 20, fp
    licence = resources.files("emboteam.world.data").joinpath("nav/LICENSE.txt").read_text()
    assert "MIT License" in licence and "ALFRED" in licence


def test_the_grid_keeps_only_the_connected_floor() -> None:
    """FloorPlan29's AI2-THOR 2.1 grid falls in two parts (35 and 30 cells); a robot in the
    smaller one could never leave it, so only the larger is kept, and the report says so
    (with the six cells added for AI2-THOR 5.x objects: 41)."""
    grid = load_grid("FloorPlan29")
    assert grid.dropped == 30 and len(grid.cells) == 41 and len(grid.added) == 6
    seen = {grid.ordered[0]}
    stack = [grid.ordered[0]]
    while stack:
        for n in grid.neighbours(stack.pop()):
            if n not in seen:
                seen.add(n)
                stack.append(n)
    assert seen == set(grid.cells)


@pytest.mark.parametrize("fp", ["FloorPlan1", "FloorPlan201", "FloorPlan414"])
def test_poses_are_reachable_cells_in_reach_facing_the_object(fp: str) -> None:
    scene = load_scene(fp)
    nav = navigator(fp)
    for o in scene.objects:
        if o.type == "Floor":
            continue
        for pose in nav.poses_for((o.position[0], o.position[2])):
            assert pose.cell in nav.grid.cells
            x, z = NavGrid.point(pose.cell)
            assert math.hypot(o.position[0] - x, o.position[2] - z) <= REACH + 1e-9
            bearing = math.degrees(math.atan2(o.position[0] - x, o.position[2] - z)) % 360
            off = abs((bearing - 90 * pose.heading + 180) % 360 - 180)
            alfred = nav.grid.openable.get(o.thor_id)
            if alfred is None or nav.grid.cell_at(alfred[:2]) != pose.cell:
                assert off <= 45 + 1e-6 or math.hypot(o.position[0] - x, o.position[2] - z) < 1e-6


def test_alfred_openable_pose_is_used_where_it_fits() -> None:
    """FloorPlan1's fridge: ALFRED opened it from (-1.0, 1.0) facing 270°."""
    scene = load_scene("FloorPlan1")
    fridge = scene.get("Fridge_1")
    pose = navigator("FloorPlan1").pose_for((fridge.position[0], fridge.position[2]))
    assert pose is not None
    assert NavGrid.point(pose.cell) == (-1.0, 1.0) and pose.heading == 3


def _one_action_apart(a: tuple[tuple[int, int], int], b: tuple[tuple[int, int], int]) -> bool:
    (ca, ha), (cb, hb) = a, b
    if ca == cb:
        return turns_between(ha, hb) == 1
    di, dj = STEPS[ha]
    return ha == hb and cb == (ca[0] + di, ca[1] + dj)


@pytest.mark.parametrize("fp", ["FloorPlan1", "FloorPlan15", "FloorPlan209", "FloorPlan414"])
def test_paths_are_legal_action_sequences_and_their_length_is_the_travel_time(fp: str) -> None:
    scene = load_scene(fp)
    nav = navigator(fp)
    start = scene.robot_start(0)
    checked = 0
    for o in scene.objects[:25]:
        point = (o.position[0], o.position[2])
        best = nav.nearest_pose(nav.cell_of(start), point)
        if best is None:
            continue
        pose, n = best
        path = nav.path(nav.cell_of(start), pose)
        assert path is not None and path[-1] == (pose.cell, pose.heading)
        assert nav.grid.cells.issuperset({c for c, _ in path})
        assert all(_one_action_apart(a, b) for a, b in itertools.pairwise(path))
        assert len(path) - 1 == n
        assert navigation_seconds(start, point, 1.0, fp) == pytest.approx(max(0.5, n * GRID))
        checked += 1
    assert checked >= 20


def test_a_wall_makes_the_drive_longer_than_the_straight_line() -> None:
    """Over the whole of FloorPlan1 some drives must go round the island: the grid distance
    exceeds the Manhattan distance between the cells for at least one pair."""
    nav = navigator("FloorPlan1")
    scene = load_scene("FloorPlan1")
    start = nav.cell_of(scene.robot_start(0))
    longer = 0
    for o in scene.objects:
        best = nav.nearest_pose(start, (o.position[0], o.position[2]))
        if best is None:
            continue
        pose, _n = best
        path = nav.path(start, pose) or []
        moves = sum(1 for a, b in itertools.pairwise(path) if a[0] != b[0])
        if moves > abs(pose.cell[0] - start[0]) + abs(pose.cell[1] - start[1]):
            longer += 1
    assert longer > 0


def test_fit_report_names_objects_out_of_reach() -> None:
    assert nav_fit("FloorPlan1").unposed == ()
    fit = nav_fit("FloorPlan29")
    assert fit.unposed == ("GarbageCan_1",)
    assert "out of reach of every cell: GarbageCan_1" in fit.summary()


def test_scene_command_shows_the_fit() -> None:
    res = runner.invoke(app, ["scene", "29", "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    nav = data["navigation"]
    assert nav["unposed"] == ["GarbageCan_1"] and nav["dropped_cells"] == 30
    assert any("within reach of Egg_1" in c["reason"] for c in nav["added_cells"])
    res = runner.invoke(app, ["scene", "29"])
    text = " ".join(res.stdout.split())
    assert res.exit_code == 0 and "out of reach of every cell: GarbageCan_1" in text
    assert "cells added for AI2-THOR 5.x objects (to reach Egg_1, LightSwitch_1, Tomato_1)" in text


def test_a_goal_needing_an_unreachable_object_is_a_capability_error() -> None:
    scene = load_scene("FloorPlan211")
    with pytest.raises(UnreachableObjectError, match="Plate_1"):
        check_reachable(Goal.parse("broken(Plate_1)"), scene)
    with pytest.raises(UnreachableObjectError, match="Laptop"):
        check_reachable(Goal.parse("switched_on(Laptop)"), scene)  # the only laptop is out of reach
    check_reachable(Goal.parse("switched_on(LightSwitch)"), scene)  # reachable: no error
    # FloorPlan29's egg and tomato are reached from the cells added for AI2-THOR 5.x
    check_reachable(Goal.parse("sliced(Tomato)"), load_scene("FloorPlan29"))


def test_run_rejects_such_a_task_with_exit_2() -> None:
    res = runner.invoke(app, ["run", "break the plate", "--scene", "211", "--robots", "1", "--frontend",
                              "offline", "--json"])
    assert res.exit_code == EXIT_BAD_INPUT, res.output
    assert "Plate_1" in res.output and "navigation grid" in res.output
