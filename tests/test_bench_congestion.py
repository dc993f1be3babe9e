"""The congestion suite: what it promises about its tasks (the solving itself is
measured by benchmarks/navigation.py)."""

from __future__ import annotations

from emboteam.bench.suites import get_task, load_suite
from emboteam.world.navgrid import largest_component, load_grid


def test_the_suite_has_crowded_small_rooms() -> None:
    suite = load_suite("congestion")
    assert len(suite.tasks) >= 20
    for task in suite.tasks:
        assert 4 <= len(task.robots) <= 8, task.id
        fp = int(task.floor_plan.removeprefix("FloorPlan"))
        assert fp >= 401 or len(load_grid(task.floor_plan).cells) <= 180, task.id  # bathrooms, small kitchens
        task.check()


def test_doorway_tasks_park_a_robot_in_a_one_cell_doorway() -> None:
    doorways = [t for t in load_suite("congestion").tasks if t.starts]
    assert len(doorways) >= 4
    for task in doorways:
        grid = load_grid(task.floor_plan)
        door = grid.cell_at(task.starts[0])
        assert door is not None
        rest = set(grid.cells) - {door}
        assert len(largest_component(rest)) < len(rest), f"{task.id}: {door} is not a doorway"
        state = task.initial_state()
        first = next(iter(state.robots.values()))
        assert first.position == task.starts[0]


def test_tasks_resolve_by_key() -> None:
    task = load_suite("congestion").tasks[0]
    assert get_task(f"congestion/{task.id}") == task
