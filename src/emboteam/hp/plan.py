"""The hybrid planner's output: one partially ordered multi-robot plan.

Each :class:`PlanStep` is one robot's action, grounded, with the PDDL literals that must
hold before it (``pre``) and that it makes true (``post``); ``after`` lists the steps of
*other* robots that must end before it starts (the sync points the behavior-tree compiler
turns into blackboard waits; a robot's own steps run in list order); ``resources`` are the
interaction spots it holds.
"""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

from emboteam.pddl.literal import Literal
from emboteam.world.actions import Action


class PlanStep(BaseModel):
    model_config = ConfigDict(frozen=True)

    id: str = Field(description="unique, e.g. robot1.3")
    robot: str
    action: Action
    subtask: str = Field(description="id of the subtask it serves")
    after: tuple[str, ...] = Field((), description="ids of other robots' steps to wait for")
    resources: tuple[str, ...] = Field((), description="interaction spots held while acting")
    pre: tuple[Literal, ...] = ()
    post: tuple[Literal, ...] = ()
    est_start: float = 0.0
    est_end: float = 0.0

    def __str__(self) -> str:
        return f"{self.id} {self.robot}: {self.action}"


class SyncPoint(BaseModel):
    """A cross-robot dependency: ``consumer`` may start once ``producer`` has ended."""

    model_config = ConfigDict(frozen=True)

    producer: str
    consumer: str
    reason: str = ""


class MergedPlan(BaseModel):
    """Per-robot action lists plus the cross-robot dependencies between them."""

    model_config = ConfigDict(frozen=True)

    robots: tuple[str, ...]
    steps: tuple[PlanStep, ...] = Field(description="a topological order of the partial order")
    sync: tuple[SyncPoint, ...] = ()
    makespan: float = Field(0.0, description="simulated seconds, from the validating simulation")
    lower_bound: float = Field(0.0, description="max(critical path, busiest robot's work)")
    resource_bound: float = Field(0.0, description="max(total work / robots, longest subtask of one robot, "
                                  "busiest spot's serial time with the least time before and after it, "
                                  "serial time on the busiest object, a carried box's put-down and the work into it "
                                  "after): bounds any schedule of these actions")
    joint: bool = Field(False, description="solved as one joint multi-robot problem (fallback)")
    planner_calls: int = 0
    plan_seconds: float = 0.0
    notes: tuple[str, ...] = Field((), description="how the planner got there: allocation, replanning, "
                                   "fallbacks (human-readable)")

    def for_robot(self, robot: str) -> list[PlanStep]:
        return [s for s in self.steps if s.robot == robot]

    def step(self, step_id: str) -> PlanStep:
        return next(s for s in self.steps if s.id == step_id)
