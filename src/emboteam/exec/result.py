"""What an execution returns: outcome, metrics inputs and the full trace."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from emboteam.exec.episode import ConditionOutcome
from emboteam.exec.trace import TraceEvent
from emboteam.hp.plan import MergedPlan
from emboteam.world.actions import ActionOutcome
from emboteam.world.checker import GoalReport

StopReason = Literal["success", "plan_done", "failed", "stalled", "time_limit", "tick_limit", "error",
                     "unsavable"]


class ExecutionResult(BaseModel):
    """One run of a plan (reactive tree or linear baseline) against an environment."""

    model_config = ConfigDict(frozen=True)

    mode: str = Field(description="bt | linear | sequences")
    seed: int = Field(0, description="the run's seed, as given (faults are seeded in the environment)")
    success: bool
    stop_reason: StopReason
    report: GoalReport | None = Field(None, description="the goal check at the end (None: no goal given)")
    makespan: float = Field(description="simulated seconds from the start until the run stopped")
    ticks: int = 0
    replans: int = 0
    recoveries: int = Field(0, description="recovery subtrees started (protocol waits excluded)")
    failed_robots: tuple[str, ...] = Field((), description="robots whose branch failed at least once")
    broken_robots: tuple[str, ...] = ()
    joined_robots: tuple[str, ...] = ()
    outcomes: tuple[ActionOutcome, ...] = ()
    plans: tuple[MergedPlan, ...] = Field((), description="the initial plan, then each replan's")
    error: str | None = None
    trace: tuple[TraceEvent, ...] = ()
    network: dict[str, int] = Field(default_factory=dict,
                                    description="lost_releases, lock_timeouts, late_reads of the blackboard")
    wall_after_disturbance: float | None = Field(
        None, description="wall-clock seconds from the first breakdown, join or move to the end of the run")

    @property
    def joiner_actions(self) -> int:
        """Actions the robots that joined mid-run carried out successfully."""
        joined = set(self.joined_robots)
        return sum(1 for o in self.outcomes if o.success and o.robot in joined)

    @property
    def gcr(self) -> float:
        return self.report.gcr if self.report is not None else 0.0

    @property
    def actions(self) -> int:
        return len(self.outcomes)

    @property
    def failed_actions(self) -> int:
        return sum(1 for o in self.outcomes if not o.success)

    @property
    def exec_rate(self) -> float:
        """Share of executed actions that succeeded (the paper's Exec)."""
        return (self.actions - self.failed_actions) / self.actions if self.outcomes else 0.0

    def episode_fields(self) -> dict[str, object]:
        """The :class:`~emboteam.exec.episode.Episode` fields this run determines
        (``Episode(task=..., ..., **result.episode_fields())``)."""
        conditions = () if self.report is None else tuple(
            ConditionOutcome(condition=str(r.condition), holds=r.holds, satisfied=r.satisfied,
                             required=r.required) for r in self.report.results)
        return {
            "success": self.success, "gcr": self.gcr, "exec": self.exec_rate, "makespan": self.makespan,
            "actions": self.actions, "failed_actions": self.failed_actions, "recoveries": self.recoveries,
            "replans": self.replans, "conditions": conditions, "trace": self.trace,
            "plan": self.plans[0] if self.plans else None,
        }
