"""Typed errors of the LLM layer.

Every way a model call can go wrong ends in one of these (never in a client library's
own exception or a traceback), so the runner can record a failed episode with a one-line
reason and carry on. All derive from :class:`LLMError`, itself an
:class:`~emboteam.errors.EmboTeamError`.
"""

from __future__ import annotations

from emboteam.errors import EXIT_FAILED, EXIT_SERVICE, EmboTeamError


class LLMError(EmboTeamError):
    """Base class of every LLM failure. ``stage`` names the pipeline stage that asked."""

    def __init__(self, message: str, *, stage: str = "") -> None:
        super().__init__(f"[{stage}] {message}" if stage else message)
        self.stage = stage


class LLMConfigError(LLMError):
    """An unusable configuration: bad spec string, missing API key, missing model file."""


class LLMUnreachable(LLMError):
    """The server could not be reached (connection refused, DNS, TLS) after retries."""

    exit_code = EXIT_SERVICE


class LLMTimeout(LLMError):
    """Every attempt outlived the configured time-out."""

    exit_code = EXIT_SERVICE


class LLMRateLimited(LLMError):
    """The server kept answering 429 after the retries (or asked to wait too long)."""

    exit_code = EXIT_SERVICE


class LLMServerError(LLMError):
    """A 5xx answer after the retries, or a 4xx the request cannot recover from."""

    exit_code = EXIT_SERVICE

    def __init__(self, message: str, *, stage: str = "", status: int | None = None) -> None:
        super().__init__(message, stage=stage)
        self.status = status


class LLMRefusal(LLMError):
    """The model declined to answer (the provider's refusal signal)."""

    exit_code = EXIT_FAILED  # the service answered; the task was not done


class LLMMalformedOutput(LLMError):
    """The answer still broke the schema or the scene's rules after the repair rounds."""

    exit_code = EXIT_FAILED  # the service answered; the task was not done


class LLMReplayMiss(LLMError):
    """Replay found no recorded response for a request: the cassette does not cover it."""

    def __init__(self, message: str, *, stage: str = "", key: str = "") -> None:
        super().__init__(message, stage=stage)
        self.key = key


class LLMBudgetExceeded(LLMError):
    """The run's budget of calls or tokens is spent."""


class LLMScoringUnsupported(LLMError):
    """The backend gives no token log-probabilities, so it cannot score candidates
    (Anthropic; an OpenAI-compatible server without ``echo``/``logprobs``). A caller
    keeps its other way of deciding (the hybrid front end keeps its review)."""
