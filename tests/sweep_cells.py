"""A cell of the latency sweep (benchmarks/plan_latency.py) as a test input: FloorPlan1,
the first ``robots`` of robots 1-4, ``conditions`` random consistent conditions from seed 0,
one subtask per condition. Shared by the re-allocation and spot-order tests."""

from __future__ import annotations

import random

from emboteam.hp.goalgen import random_conditions
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


def random_cell(robots: int, conditions: int, seed: int = 0) -> tuple[TaskSpec, WorldState]:
    team = parse_team(["1", "2", "3", "4"][:robots])
    state = WorldState.from_scene(load_scene("FloorPlan1"), team)
    conds = random_conditions(state, conditions, random.Random(seed))
    spec = TaskSpec(instruction=str(Goal(conditions=tuple(conds))), subtasks=tuple(
        Subtask(id=f"c{i}", description=str(c), goal=(c,)) for i, c in enumerate(conds, 1)))
    return spec, state
