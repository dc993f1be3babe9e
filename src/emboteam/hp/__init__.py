"""HP (Hybrid Planner): validation, allocation, Fast Downward per subtask, merge into one plan.

``HybridPlanner(PlannerConfig()).plan(spec, state)`` (docs/planning.md)."""

from emboteam.hp.plan import MergedPlan, PlanStep, SyncPoint
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.pddl.errors import (
    ImpossibleGoalError,
    MissingSkillError,
    PlannerInputError,
    PlannerLimitError,
    PlannerMemoryError,
    PlannerTimeoutError,
    PlanningError,
    PlanValidationError,
    UnknownGoalObjectError,
    UnsolvableSubtaskError,
)

__all__ = [
    "HybridPlanner", "ImpossibleGoalError", "MergedPlan", "MissingSkillError", "PlanStep",
    "PlanValidationError", "PlannerConfig", "PlannerInputError", "PlannerLimitError", "PlannerMemoryError",
    "PlannerTimeoutError", "PlanningError", "SyncPoint", "UnknownGoalObjectError", "UnsolvableSubtaskError",
]
