"""The oracle front end: the benchmark's ground-truth goal as a TaskSpec.

Used to measure the planner, compiler and executor without parsing errors: one subtask
per ground-truth condition, no robot (the hybrid planner allocates), no dependencies
(conditions of a goal are a conjunction; the planner orders what must be ordered).
"""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.errors import EmboTeamError
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.goals import Goal
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState


class OracleGoalError(EmboTeamError):
    """A ground-truth goal the oracle cannot turn into subtasks (it has no conditions)."""


class OracleFrontend:
    """Front end that ignores the instruction and returns the ground-truth goal."""

    name = "oracle"

    def __init__(self, goal: Goal) -> None:
        if not goal.conditions:
            raise OracleGoalError("the oracle needs a goal with at least one condition")
        self.goal = goal

    def decompose(self, instruction: str, scene: Scene, state: WorldState,
                  team: Sequence[RobotProfile]) -> TaskSpec:
        """One subtask per condition, in the goal's order; duplicates are kept once."""
        return self.spec(instruction)

    def spec(self, instruction: str) -> TaskSpec:
        """The TaskSpec of the goal (it needs no scene: the stand-in model answers with it)."""
        seen: dict[str, int] = {}
        subtasks: list[Subtask] = []
        for cond in self.goal.conditions:
            key = str(cond)
            if key in seen:
                continue
            seen[key] = len(subtasks)
            subtasks.append(Subtask(id=f"s{len(subtasks) + 1}", description=key, goal=(cond,)))
        return TaskSpec(instruction=instruction, subtasks=tuple(subtasks))
