"""The usage ledger (calls and tokens per stage) and the per-run budget.

The ledger is what the benchmark reports as ``llm_calls`` and ``tokens``; the budget
turns a runaway loop (a model that never produces valid output, a misconfigured repair
count) into a typed :class:`LLMBudgetExceeded` instead of an unbounded bill. Both are
thread-safe: benchmark workers may share one client.
"""

from __future__ import annotations

import threading

from pydantic import BaseModel, ConfigDict, Field

from emboteam.llm.errors import LLMBudgetExceeded


class StageUsage(BaseModel):
    model_config = ConfigDict(frozen=True)

    calls: int = 0
    attempts: int = Field(0, description="HTTP attempts, retries included")
    input_tokens: int = 0
    output_tokens: int = 0

    @property
    def tokens(self) -> int:
        return self.input_tokens + self.output_tokens


class Budget(BaseModel):
    """Limits for one run; ``None`` means unlimited."""

    model_config = ConfigDict(frozen=True)

    max_calls: int | None = Field(None, ge=0)
    max_tokens: int | None = Field(None, ge=0)


class Usage:
    """Stage -> calls, attempts, input tokens, output tokens."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._stages: dict[str, StageUsage] = {}

    def record(self, stage: str, *, input_tokens: int, output_tokens: int, attempts: int = 1) -> None:
        with self._lock:
            s = self._stages.get(stage, StageUsage())
            self._stages[stage] = StageUsage(
                calls=s.calls + 1, attempts=s.attempts + attempts,
                input_tokens=s.input_tokens + input_tokens, output_tokens=s.output_tokens + output_tokens)

    def record_attempts(self, stage: str, attempts: int) -> None:
        """Attempts of a call that failed: they cost time, not tokens, and are no call."""
        with self._lock:
            s = self._stages.get(stage, StageUsage())
            self._stages[stage] = s.model_copy(update={"attempts": s.attempts + attempts})

    def by_stage(self) -> dict[str, StageUsage]:
        with self._lock:
            return dict(self._stages)

    @property
    def calls(self) -> int:
        return sum(s.calls for s in self.by_stage().values())

    @property
    def input_tokens(self) -> int:
        return sum(s.input_tokens for s in self.by_stage().values())

    @property
    def output_tokens(self) -> int:
        return sum(s.output_tokens for s in self.by_stage().values())

    @property
    def tokens(self) -> int:
        return self.input_tokens + self.output_tokens

    def to_dict(self) -> dict[str, object]:
        """JSON-ready: totals plus the per-stage breakdown."""
        return {
            "calls": self.calls, "input_tokens": self.input_tokens, "output_tokens": self.output_tokens,
            "tokens": self.tokens,
            "stages": {k: v.model_dump() for k, v in sorted(self.by_stage().items())},
        }

    def check(self, budget: Budget, stage: str) -> None:
        """Raise before a call that the budget no longer allows."""
        if budget.max_calls is not None and self.calls >= budget.max_calls:
            raise LLMBudgetExceeded(f"call budget spent: {self.calls} of {budget.max_calls} calls made",
                                    stage=stage)
        if budget.max_tokens is not None and self.tokens >= budget.max_tokens:
            raise LLMBudgetExceeded(f"token budget spent: {self.tokens} of {budget.max_tokens} tokens used",
                                    stage=stage)

    def check_tokens(self, budget: Budget, stage: str) -> None:
        """Raise after a call that took the run over its token budget."""
        if budget.max_tokens is not None and self.tokens > budget.max_tokens:
            raise LLMBudgetExceeded(f"token budget exceeded: {self.tokens} of {budget.max_tokens} tokens used",
                                    stage=stage)
