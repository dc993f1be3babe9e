"""A cell of the latency sweep (benchmarks/plan_latency.py) as a test input: FloorPlan1,
the first ``robots`` of robots 1-4, ``conditions`` random consistent conditions from seed 0,
one subtask per condition. Shared by the re-allocation and spot-order tests."""

from __future__ import annotations

from emboteam.hp.goalgen import goal_cell
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.state import WorldState


def random_cell(robots: int, conditions: int, seed: int = 0) -> tuple[TaskSpec, WorldState]:
    return goal_cell("FloorPlan1", [1, 2, 3, 4][:robots], conditions, seed)
