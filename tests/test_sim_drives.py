"""A grid drive as AI2-THOR agent actions (sim/drives.py), and the drives exported with a
plan's behavior tree (btc/drives.py)."""

from __future__ import annotations

import pytest

from emboteam.bench.suites import load_suite
from emboteam.btc.drives import planned_drives
from emboteam.config import RunConfig
from emboteam.modes import EpisodeContext, plan_task
from emboteam.sim.drives import NotOneActionError, action_between, cells_text, drive_steps, steps_text
from emboteam.sim.traffic import Step
from emboteam.world.actions import Skill
from emboteam.world.navgrid import STEPS, load_grid
from emboteam.world.navigation import navigator


def test_actions_between_states_are_ai2thors() -> None:
    assert action_between(((0, 0), 0), ((0, 1), 0)) == "MoveAhead"  # heading 0 faces +z
    assert action_between(((0, 0), 1), ((1, 0), 1)) == "MoveAhead"  # heading 1 faces +x
    assert action_between(((0, 0), 0), ((0, 0), 1)) == "RotateRight"  # yaw 0 -> 90
    assert action_between(((0, 0), 0), ((0, 0), 3)) == "RotateLeft"
    assert action_between(((0, 0), 2), ((0, 0), 2)) == "Wait"
    for bad in [(((0, 0), 0), ((0, 2), 0)), (((0, 0), 0), ((1, 0), 0)), (((0, 0), 0), ((0, 0), 2))]:
        with pytest.raises(NotOneActionError):
            action_between(*bad)


def test_waits_are_merged_and_the_robot_is_lined_up_without_time() -> None:
    path = [Step(1.0, (0, 0), 1), Step(1.25, (1, 0), 1), Step(1.5, (1, 0), 1), Step(1.75, (1, 0), 1),
            Step(2.0, (1, 0), 0), Step(2.25, (1, 1), 0)]
    steps = drive_steps(path, start=0.5, end=2.75, heading_before=3)
    assert [(s.action, s.start, s.end) for s in steps] == [
        ("Wait", 0.5, 1.0),  # the way was blocked before the path was found
        ("RotateRight", 1.0, 1.0), ("RotateRight", 1.0, 1.0),  # from heading 3 to 1, in no time
        ("MoveAhead", 1.0, 1.25), ("Wait", 1.25, 1.75), ("RotateLeft", 1.75, 2.0),
        ("MoveAhead", 2.0, 2.25), ("Wait", 2.25, 2.75)]
    assert steps[-1].cell == (1, 1) and steps[-1].yaw == 0
    assert steps_text(steps).startswith("Wait:0.50 RotateRight RotateRight MoveAhead Wait:0.50 RotateLeft")
    assert cells_text(path) == "0,0,90;0.25,0,0;0.25,0.25,0"


def _walk(cell: tuple[int, int], heading: int, actions: list[str]) -> tuple[tuple[int, int], int, list]:
    visited = [cell]
    for a in actions:
        if a == "MoveAhead":
            cell = (cell[0] + STEPS[heading][0], cell[1] + STEPS[heading][1])
            visited.append(cell)
        elif a in ("RotateRight", "RotateLeft"):
            heading = (heading + (1 if a == "RotateRight" else 3)) % 4
    return cell, heading, visited


def test_exported_drives_follow_the_grid_to_a_pose_and_wait_for_each_other() -> None:
    """The congestion suite's plans: every GoToObject's exported moves, walked from its
    first cell, stay on the grid and end on an interaction pose of the target facing it;
    and in crowded rooms some drives wait for another robot."""
    waited = 0
    for task in load_suite("congestion").tasks[:12]:
        ctx = EpisodeContext.open(task, RunConfig(mode="full", frontend="oracle"))
        _, plan = plan_task(ctx)
        drives = planned_drives(plan, ctx.state)
        grid, nav = load_grid(task.floor_plan), navigator(task.floor_plan)
        gotos = {s.id for s in plan.steps if s.action.skill is Skill.GoToObject}
        assert set(drives) == gotos, task.id  # every drive of the plan (some plans need none)
        for sid, drive in drives.items():
            first = drive.cells.split(";")[0].split(",")
            start = grid.cell_at((float(first[0]), float(first[1])))
            assert start is not None
            actions = [a.split(":")[0] for a in drive.moves.split()]
            first_step = drive.steps[0]  # the heading before it: undo it if it is a turn
            before = (first_step.heading - {"RotateRight": 1, "RotateLeft": -1}.get(first_step.action, 0)) % 4
            end, heading, visited = _walk(start, before, actions)
            assert all(c in grid.cells for c in visited), (task.id, sid)
            target = ctx.state.objects[plan.step(sid).action.target].position
            poses = {(p.cell, p.heading) for p in nav.poses_for((target[0], target[2]))}
            assert (end, heading) in poses, (task.id, sid)
            waited += "Wait:" in drive.moves
    assert waited > 0
