"""What an episode runs: a benchmark task (with its ground-truth goal) or a typed instruction.

Both are :class:`EpisodeTask` s; the pipeline takes either, so an instruction typed on the
command line is not dressed up as a benchmark task. A benchmark task is an instruction in
a floor plan for a team, with its ground-truth goal.

Task files write the goal in the goal language (``["inside(Apple, Fridge)", "off(LightSwitch)"]``)
and the team as SMART-LLM profile numbers (``[23, 25]``); both are accepted here, as are the
model's own dumps. Unknown fields are rejected, so a typo in a task file (``"robot": [1]``)
is an error rather than a silently ignored key.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator

from emboteam.errors import EmboTeamError
from emboteam.sim.setup import StateChange, apply_changes
from emboteam.world.checker import validate_goal
from emboteam.world.goals import Goal
from emboteam.world.navgrid import load_grid
from emboteam.world.robots import RobotProfile, parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

Category = Literal["parallel", "temporal", "imported"]


class InvalidTaskError(EmboTeamError):
    """A task that does not fit its scene: unknown floor plan, robot or object, or a goal
    the scene cannot satisfy."""


class BenchTask(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid")

    id: str = Field(min_length=1, description="unique within the suite")
    suite: str
    floor_plan: str
    robots: tuple[str, ...] = Field(min_length=1, description="profile numbers or names")
    category: Category
    instruction: str
    goal: Goal
    setup: tuple[StateChange, ...] = Field((), description="initial-state changes")
    starts: tuple[tuple[float, float], ...] = Field(
        (), description="start cells (x, z) of the first robots, in team order (e.g. one parked in a "
                        "doorway); the others start as usual")
    notes: str = ""

    @field_validator("robots", mode="before")
    @classmethod
    def _robot_numbers(cls, value: Any) -> Any:
        """Task files list profile numbers as JSON integers, like SMART-LLM's ``robot list``."""
        if isinstance(value, (list, tuple)):
            return tuple(str(v) if isinstance(v, int) and not isinstance(v, bool) else v for v in value)
        return value

    @field_validator("goal", mode="before")
    @classmethod
    def _goal_text(cls, value: Any) -> Any:
        """A goal written as condition strings (or one ``&``-joined string) is parsed."""
        if isinstance(value, str) or (isinstance(value, (list, tuple)) and value
                                      and all(isinstance(v, str) for v in value)):
            try:
                return Goal.parse(list(value) if not isinstance(value, str) else value)
            except EmboTeamError as exc:
                raise ValueError(str(exc)) from None
        return value

    @field_validator("setup", mode="before")
    @classmethod
    def _setup_fields(cls, value: Any) -> Any:
        """StateChange itself ignores unknown keys; a task file must not."""
        if isinstance(value, (list, tuple)):
            known = set(StateChange.model_fields)
            for change in value:
                if isinstance(change, dict):
                    unknown = sorted(set(change) - known)
                    if unknown:
                        raise ValueError(f"unknown initial-state field(s) {unknown}; "
                                         f"known: {sorted(known)}")
        return value

    @property
    def key(self) -> str:
        """``SUITE/ID``, as the CLI takes it."""
        return f"{self.suite}/{self.id}"

    def team(self) -> tuple[RobotProfile, ...]:
        """The robot profiles of the team (a typed error for an unknown profile)."""
        return parse_team(list(self.robots))

    def initial_state(self) -> WorldState:
        """A fresh state of the floor plan with the team placed and the setup applied."""
        state = initial_state(self.floor_plan, self.team(), self.setup)
        for robot, start in zip(state.robots.values(), self.starts, strict=False):
            robot.position = start
        return state

    @property
    def ground_truth(self) -> Goal | None:
        """The goal the episode is scored against (None for a goal without conditions)."""
        return self.goal if self.goal.conditions else None

    def check(self) -> None:
        """Raise :class:`InvalidTaskError` unless the floor plan, the team, the setup and
        the goal all fit (every goal reference exists in the scene and can take the
        predicate; see :func:`emboteam.world.checker.validate_goal`)."""
        try:
            scene = load_scene(self.floor_plan)
            if scene.floor_plan != self.floor_plan:
                raise InvalidTaskError(f"floor plan {self.floor_plan!r} must be written "
                                       f"{scene.floor_plan!r}")
            self.initial_state()
            if not self.goal.conditions:
                raise InvalidTaskError("the goal has no conditions")
            validate_goal(self.goal, scene)
            grid = load_grid(scene.floor_plan)
            bad = [p for p in self.starts if grid.cell_at(p) is None]
            if bad or len(set(self.starts)) < len(self.starts) or len(self.starts) > len(self.robots):
                raise InvalidTaskError(f"starts must be distinct reachable cells, one per robot at most "
                                       f"(not {', '.join(map(str, bad)) or 'repeated'})")
        except EmboTeamError as exc:
            raise InvalidTaskError(f"task {self.key}: {exc}") from None


class Instruction(BaseModel):
    """An instruction typed by a user: a floor plan and a team, but no ground-truth goal,
    so success is judged against the goal the front end understood (the episode says so
    in its ``category``, ``imported``)."""

    model_config = ConfigDict(frozen=True)

    instruction: str
    floor_plan: str
    robots: tuple[str, ...] = Field(min_length=1, description="profile numbers or names")

    setup: tuple[StateChange, ...] = ()

    @property
    def key(self) -> str:
        """How an episode of a typed instruction is keyed (the CLI's JSON contract)."""
        return "adhoc/instruction"

    @property
    def category(self) -> Category:
        return "imported"

    @classmethod
    def typed(cls, instruction: str, floor_plan: str, robots: str | Sequence[str]) -> Instruction:
        """From the command line: the floor plan normalised, the team as profile numbers."""
        fp = load_scene(floor_plan).floor_plan
        team = parse_team(robots if isinstance(robots, str) else ",".join(robots))
        return cls(instruction=instruction, floor_plan=fp, robots=tuple(str(p.number or p.name) for p in team))

    @property
    def ground_truth(self) -> Goal | None:
        return None

    def team(self) -> tuple[RobotProfile, ...]:
        return parse_team(list(self.robots))

    def initial_state(self) -> WorldState:
        return initial_state(self.floor_plan, self.team(), self.setup)


#: what the pipeline runs: a benchmark task, or an instruction typed on the command line
EpisodeTask = BenchTask | Instruction


def initial_state(floor_plan: str, team: Sequence[RobotProfile], setup: Sequence[StateChange] = ()) -> WorldState:
    """The one place an episode's initial state is built: the scene, the team placed, the
    task's setup applied."""
    state = WorldState.from_scene(load_scene(floor_plan), team)
    apply_changes(state, setup)
    return state
