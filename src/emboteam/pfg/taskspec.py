"""The PFG's output: an instruction decomposed into subtasks with goals, robots and
dependencies. Produced by a front end (oracle, offline parser or LLM), consumed by the
hybrid planner."""

from __future__ import annotations

import graphlib

from pydantic import BaseModel, ConfigDict, Field, model_validator

from emboteam.world.goals import Condition, Goal


class Subtask(BaseModel):
    """One subtask: what must hold at its end, who should do it, what must come first."""

    model_config = ConfigDict(frozen=True)

    id: str = Field(description="unique within the spec, e.g. s1")
    description: str
    robot: str | None = Field(None, description="team member name; None lets the planner allocate")
    goal: tuple[Condition, ...] = Field(min_length=1)
    depends_on: tuple[str, ...] = Field((), description="subtask ids that must finish first")
    final: bool = Field(True, description="its conditions must still hold at the end; False for "
                        "an intermediate step a later subtask undoes (rinse the lettuce in the "
                        "sink, then put it on the counter)")


class TaskSpec(BaseModel):
    """An instruction as subtasks. Dependencies form a DAG (checked)."""

    model_config = ConfigDict(frozen=True)

    instruction: str
    subtasks: tuple[Subtask, ...] = Field(min_length=1)

    @model_validator(mode="after")
    def _dag(self) -> TaskSpec:
        ids = [s.id for s in self.subtasks]
        if len(ids) != len(set(ids)):
            raise ValueError(f"duplicate subtask ids in {ids}")
        known = set(ids)
        for s in self.subtasks:
            missing = [d for d in s.depends_on if d not in known]
            if missing:
                raise ValueError(f"subtask {s.id} depends on unknown {missing}")
        try:
            graphlib.TopologicalSorter({s.id: set(s.depends_on) for s in self.subtasks}).prepare()
        except graphlib.CycleError as exc:
            raise ValueError(f"subtask dependencies form a cycle: {' -> '.join(exc.args[1])}") from None
        return self

    def goal(self) -> Goal:
        """The final subtasks' conditions as one conjunction (duplicates removed, order
        kept): what must hold when the whole task is done."""
        seen: dict[str, Condition] = {}
        for s in self.subtasks:
            if not s.final:
                continue
            for c in s.goal:
                seen.setdefault(str(c), c)
        return Goal(conditions=tuple(seen.values()))

    def subtask(self, sid: str) -> Subtask:
        return next(s for s in self.subtasks if s.id == sid)
