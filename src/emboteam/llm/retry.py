"""Retry policy: exponential backoff with jitter, honouring Retry-After.

Why our own loop rather than the official clients' (``max_retries=0`` is set on both):
one policy for every backend (llama.cpp and replay have none), every attempt visible to
the usage ledger, a Retry-After cap so a server asking for ten minutes fails fast with
:class:`LLMRateLimited`, and a seeded jitter so runs are repeatable. The policy is a
small pure function; no third-party retry library is needed for it.
"""

from __future__ import annotations

import random

from pydantic import BaseModel, ConfigDict, Field


class RetryPolicy(BaseModel):
    """``max_attempts`` counts the first attempt; delays are seconds."""

    model_config = ConfigDict(frozen=True)

    max_attempts: int = Field(4, ge=1)
    base_delay: float = Field(0.5, ge=0)
    max_delay: float = Field(8.0, ge=0)
    max_retry_after: float = Field(60.0, ge=0, description="give up if the server asks to wait longer")

    def delay(self, attempt: int, rng: random.Random, retry_after: float | None = None) -> float:
        """Seconds to wait after failed attempt number ``attempt`` (1-based).

        Exponential backoff ``base * 2**(attempt-1)`` capped at ``max_delay``, with "equal
        jitter" (half fixed, half random) so concurrent workers spread out; never less
        than the server's Retry-After.
        """
        cap = min(self.max_delay, self.base_delay * 2.0 ** (attempt - 1))
        wait = cap / 2 + rng.uniform(0, cap / 2)
        if retry_after is not None:
            wait = max(wait, retry_after)
        return wait
