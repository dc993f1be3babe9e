"""A benchmark task: an instruction in a floor plan for a team, with its ground-truth goal."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from emboteam.sim.setup import StateChange
from emboteam.world.goals import Goal

Category = Literal["parallel", "temporal", "imported"]


class BenchTask(BaseModel):
    model_config = ConfigDict(frozen=True)

    id: str = Field(description="unique within the suite")
    suite: str
    floor_plan: str
    robots: tuple[str, ...] = Field(min_length=1, description="profile numbers or names")
    category: Category
    instruction: str
    goal: Goal
    setup: tuple[StateChange, ...] = Field((), description="initial-state changes")
    notes: str = ""

    @property
    def key(self) -> str:
        """``SUITE/ID``, as the CLI takes it."""
        return f"{self.suite}/{self.id}"
