"""A benchmark task: an instruction in a floor plan for a team, with its ground-truth goal.

Task files write the goal in the goal language (``["inside(Apple, Fridge)", "off(LightSwitch)"]``)
and the team as SMART-LLM profile numbers (``[23, 25]``); both are accepted here, as are the
model's own dumps. Unknown fields are rejected, so a typo in a task file (``"robot": [1]``)
is an error rather than a silently ignored key.
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator

from emboteam.errors import EmboTeamError
from emboteam.sim.setup import StateChange, apply_changes
from emboteam.world.checker import validate_goal
from emboteam.world.goals import Goal
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
        state = WorldState.from_scene(load_scene(self.floor_plan), self.team())
        apply_changes(state, self.setup)
        return state

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
        except EmboTeamError as exc:
            raise InvalidTaskError(f"task {self.key}: {exc}") from None
