"""Typed planning errors: every way planning can fail that a user can cause or must hear
about, each with a message that names the culprit (the condition, the skill, the subtask,
Fast Downward's own words). The CLI prints the message and exits non-zero."""

from __future__ import annotations

from emboteam.errors import EmboTeamError


class PlanningError(EmboTeamError):
    """Root of the planner's errors."""


class UnknownGoalObjectError(PlanningError):
    """A goal names an object id the scene does not have."""


class ImpossibleGoalError(PlanningError):
    """A goal nothing can satisfy: no object of that kind, too few of them, a property the
    objects lack, more objects held than the team has hands, too heavy for every robot."""


class MissingSkillError(PlanningError):
    """A condition needs a skill (or a mass capacity) no robot of the team has."""

    def __init__(self, message: str, *, skill: str, condition: str) -> None:
        super().__init__(message)
        self.skill = skill
        self.condition = condition


class UnsolvableSubtaskError(PlanningError):
    """Fast Downward proved (or failed to find) no plan for a subtask."""

    def __init__(self, message: str, *, subtask: str, unmet: tuple[str, ...] = ()) -> None:
        super().__init__(message)
        self.subtask = subtask
        self.unmet = unmet


class PlannerLimitError(PlanningError):
    """Fast Downward ran out of time or memory."""


class PlannerTimeoutError(PlannerLimitError):
    """Fast Downward hit its time limit."""


class PlannerMemoryError(PlannerLimitError):
    """Fast Downward hit its memory limit."""


class PlannerInputError(PlanningError):
    """Fast Downward rejected its input or crashed; the message carries its own words."""


class PlanValidationError(PlanningError):
    """A merged plan failed in the simulator and no fallback could repair it."""
