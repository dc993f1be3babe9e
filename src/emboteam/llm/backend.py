"""The backend interface: one provider's wire protocol, nothing else.

A backend sends one attempt of a request and returns an :class:`LLMResponse`, or raises
:class:`TransientFailure` (worth retrying: 429, 5xx, time-out, connection) or
:class:`PermanentFailure` (not worth it: bad request, bad key). Retries, budget, usage
and recording live in :class:`emboteam.llm.client.LLMClient`, once for every backend.
"""

from __future__ import annotations

import os
from datetime import datetime, timezone
from email.utils import parsedate_to_datetime
from typing import Literal, Protocol

from emboteam.llm.errors import LLMConfigError
from emboteam.llm.messages import LLMRequest, LLMResponse
from emboteam.llm.scoring import ScoreRequest, ScoreResponse
from emboteam.llm.spec import LLMSpec

TransientKind = Literal["rate_limit", "server", "timeout", "connection"]
PermanentKind = Literal["auth", "request", "server", "timeout"]


class TransientFailure(Exception):
    """An attempt failed in a way a later attempt may not. ``retry_after``: the server's
    Retry-After, seconds."""

    def __init__(self, kind: TransientKind, message: str, *, retry_after: float | None = None,
                 status: int | None = None) -> None:
        super().__init__(message)
        self.kind = kind
        self.retry_after = retry_after
        self.status = status


class PermanentFailure(Exception):
    """An attempt failed in a way retrying cannot fix."""

    def __init__(self, kind: PermanentKind, message: str, *, status: int | None = None) -> None:
        super().__init__(message)
        self.kind = kind
        self.status = status


class ScoringUnsupported(Exception):
    """The backend cannot return token log-probabilities (Anthropic's API, a server
    without ``echo``/``logprobs`` on its completions endpoint)."""


class Backend(Protocol):
    """One provider. ``name`` is the spec without secrets, for logs and cassettes."""

    name: str

    def send(self, request: LLMRequest) -> LLMResponse: ...


class ScoringBackend(Protocol):
    """A backend that also returns token log-probabilities (:mod:`emboteam.llm.scoring`);
    it raises :class:`ScoringUnsupported` when the model or server turns out not to."""

    def score(self, request: ScoreRequest) -> ScoreResponse: ...


def parse_retry_after(value: str | None) -> float | None:
    """Seconds from a Retry-After header (delta-seconds or an HTTP date), or None."""
    if value is None:
        return None
    value = value.strip()
    try:
        return max(0.0, float(value))
    except ValueError:
        pass
    try:
        when = parsedate_to_datetime(value)
    except (TypeError, ValueError):
        return None
    if when.tzinfo is None:
        when = when.replace(tzinfo=timezone.utc)
    return max(0.0, (when - datetime.now(timezone.utc)).total_seconds())


def status_failure(status: int, message: str, retry_after: float | None) -> TransientFailure | PermanentFailure:
    """Classify an HTTP error status the same way for every HTTP backend."""
    if status == 429:
        return TransientFailure("rate_limit", message, retry_after=retry_after, status=status)
    if status == 408:
        return TransientFailure("timeout", message, retry_after=retry_after, status=status)
    if status >= 500:
        return TransientFailure("server", message, retry_after=retry_after, status=status)
    if status in (401, 403):
        return PermanentFailure("auth", message, status=status)
    return PermanentFailure("request", message, status=status)


#: sent to self-hosted servers that need no key (the official clients insist on one)
NO_KEY = "no-key-required"


def api_key(variable: str, spec: LLMSpec) -> str:
    """The key from the environment only; a self-hosted server (a base URL) may need none."""
    key = os.environ.get(variable)
    if key:
        return key
    if spec.base_url is None:
        raise LLMConfigError(f"{variable} is not set (needed for {spec.provider}: without a base URL)")
    return NO_KEY
