"""The LLM client: one backend plus the policies every backend shares.

:meth:`LLMClient.complete` checks the budget, sends the request with retries
(exponential backoff with jitter on 429, 5xx, time-outs and connection errors), records
calls and tokens per stage, turns every failure into a typed :class:`LLMError`, raises
:class:`LLMRefusal` when the provider signals one, and parses structured answers into
``response.parsed``. :func:`make_client` builds one from a spec string.
"""

from __future__ import annotations

import json
import logging
import random
import re
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from emboteam.llm.backend import Backend, PermanentFailure, ScoringUnsupported, TransientFailure
from emboteam.llm.cassette import RecordingBackend, ReplayBackend
from emboteam.llm.errors import (
    LLMConfigError,
    LLMError,
    LLMRateLimited,
    LLMRefusal,
    LLMScoringUnsupported,
    LLMServerError,
    LLMTimeout,
    LLMUnreachable,
)
from emboteam.llm.messages import LLMRequest, LLMResponse
from emboteam.llm.retry import RetryPolicy
from emboteam.llm.scoring import ScoreRequest, ScoreResponse
from emboteam.llm.spec import LLMSpec, parse_llm_spec
from emboteam.llm.usage import Budget, Usage

log = logging.getLogger(__name__)

_T = TypeVar("_T")

#: the CLI's ``--llm-timeout`` default, seconds per attempt
DEFAULT_TIMEOUT = 60.0


class LLMClient:
    """Thread-safe; share one per run. :meth:`scoped` gives a per-task ledger."""

    def __init__(self, backend: Backend, *, budget: Budget | None = None, retry: RetryPolicy | None = None,
                 seed: int = 0, sleep: Callable[[float], None] = time.sleep,
                 parent: LLMClient | None = None) -> None:
        self.backend = backend
        self.budget = budget or Budget()
        self.retry = retry or RetryPolicy()
        self.usage = Usage()
        self._rng = random.Random(seed)
        self._sleep = sleep
        self._parent = parent

    @property
    def name(self) -> str:
        return self.backend.name

    def scoped(self, budget: Budget | None = None) -> LLMClient:
        """A client on the same backend with its own usage ledger (and optionally its own
        budget) whose calls also count against this client's ledger and budget: one per
        benchmark task gives per-episode ``llm_calls`` and ``tokens``."""
        return LLMClient(self.backend, budget=budget, retry=self.retry, seed=self._rng.randrange(2**31),
                         sleep=self._sleep, parent=self)

    # ---- budget and ledger over the chain of scopes --------------------------------
    def _chain(self) -> list[LLMClient]:
        chain: list[LLMClient] = []
        node: LLMClient | None = self
        while node is not None:
            chain.append(node)
            node = node._parent
        return chain

    def _check_budget(self, stage: str) -> None:
        for c in self._chain():
            c.usage.check(c.budget, stage)

    def _record(self, stage: str, response: LLMResponse | None, attempts: int) -> None:
        for c in self._chain():
            if response is None:
                c.usage.record_attempts(stage, attempts)
            else:
                c.usage.record(stage, input_tokens=response.input_tokens, output_tokens=response.output_tokens,
                               attempts=attempts)

    # ---- the call ------------------------------------------------------------------
    def complete(self, request: LLMRequest) -> LLMResponse:
        """Send ``request``; return the answer or raise a typed :class:`LLMError`."""
        stage = request.stage
        self._check_budget(stage)
        response, attempts = self._send_with_retries(request)
        self._record(stage, response, attempts)
        log.debug("llm %s %s: %d+%d tokens in %.2fs (%d attempt(s)%s)", stage, request.key()[:12],
                  response.input_tokens, response.output_tokens, response.latency, attempts,
                  ", replayed" if response.replayed else "")
        for c in self._chain():
            c.usage.check_tokens(c.budget, stage)
        if response.refusal:
            raise LLMRefusal(f"the model refused: {_short(response.refusal)}", stage=stage)
        if request.json_schema is not None:
            response = response.model_copy(update={"parsed": extract_json_object(response.text)})
        return response

    def score(self, request: ScoreRequest) -> ScoreResponse:
        """Token log-probabilities of each candidate sentence (:mod:`emboteam.llm.scoring`),
        with the budget, retries, ledger and recording of :meth:`complete`; a backend
        without log-probabilities raises :class:`LLMScoringUnsupported` (before any call
        for one that never has them)."""
        stage = request.stage
        score: Callable[[ScoreRequest], ScoreResponse] | None = getattr(self.backend, "score", None)
        if score is None:
            raise LLMScoringUnsupported(f"{self.name} gives no token log-probabilities: it cannot score "
                                        "candidates", stage=stage)
        self._check_budget(stage)
        response, attempts = self._with_retries(stage, lambda: score(request))
        for c in self._chain():
            c.usage.record(stage, input_tokens=response.input_tokens, output_tokens=0, attempts=attempts)
        log.debug("llm %s %s: %d candidates, %d tokens (%d evaluated) in %.2fs%s", stage, request.key()[:12],
                  len(response.scores), response.input_tokens, response.evaluated_tokens, response.latency,
                  ", replayed" if response.replayed else "")
        for c in self._chain():
            c.usage.check_tokens(c.budget, stage)
        return response

    def _send_with_retries(self, request: LLMRequest) -> tuple[LLMResponse, int]:
        return self._with_retries(request.stage, lambda: self.backend.send(request))

    def _with_retries(self, stage: str, attempt_once: Callable[[], _T]) -> tuple[_T, int]:
        policy = self.retry
        last: TransientFailure | None = None
        for attempt in range(1, policy.max_attempts + 1):
            try:
                return attempt_once(), attempt
            except ScoringUnsupported as exc:
                self._record(stage, None, attempt)
                raise LLMScoringUnsupported(f"{self.name} cannot score candidates: {exc}", stage=stage) from None
            except TransientFailure as failure:
                last = failure
                if failure.retry_after is not None and failure.retry_after > policy.max_retry_after:
                    self._record(stage, None, attempt)
                    too_long = (f"{self.name} asks to retry after {failure.retry_after:g} s "
                                f"(more than the {policy.max_retry_after:g} s allowed)")
                    if failure.kind == "rate_limit":
                        raise LLMRateLimited(too_long, stage=stage) from None
                    raise LLMServerError(too_long, stage=stage, status=failure.status) from None
                if attempt == policy.max_attempts:
                    break
                wait = policy.delay(attempt, self._rng, failure.retry_after)
                log.warning("llm %s: attempt %d/%d failed (%s); retrying in %.2fs", stage, attempt,
                            policy.max_attempts, failure, wait)
                self._sleep(wait)
            except PermanentFailure as failure:
                self._record(stage, None, attempt)
                raise _permanent_error(failure, self.name, stage) from None
            except LLMError:
                self._record(stage, None, attempt)
                raise
        assert last is not None
        self._record(stage, None, policy.max_attempts)
        raise _exhausted_error(last, self.name, stage, policy.max_attempts)


def _permanent_error(failure: PermanentFailure, name: str, stage: str) -> LLMError:
    if failure.kind == "auth":
        return LLMConfigError(f"{name} rejected the credentials ({failure}); check the API key variable",
                              stage=stage)
    if failure.kind == "timeout":
        return LLMTimeout(f"{name}: {failure}", stage=stage)
    return LLMServerError(f"{name} rejected the request: {failure}", stage=stage, status=failure.status)


def _exhausted_error(failure: TransientFailure, name: str, stage: str, attempts: int) -> LLMError:
    tail = f"after {attempts} attempt(s): {failure}"
    if failure.kind == "rate_limit":
        return LLMRateLimited(f"{name} is rate limiting {tail}", stage=stage)
    if failure.kind == "timeout":
        return LLMTimeout(f"{name} did not answer in time {tail}", stage=stage)
    if failure.kind == "connection":
        return LLMUnreachable(f"{name} is unreachable {tail}", stage=stage)
    return LLMServerError(f"{name} failed {tail}", stage=stage, status=failure.status)


_FENCE = re.compile(r"```(?:json)?\s*(.*?)```", re.DOTALL)


def extract_json_object(text: str) -> dict[str, Any] | None:
    """The JSON object in an answer, or None.

    Schema-constrained backends return bare JSON; an unconstrained OpenAI-compatible
    server may wrap it in a Markdown fence or a sentence, so the fence content and then
    the outermost ``{...}`` span are tried too. Only an object counts.
    """
    candidates = [text.strip()]
    candidates += [m.group(1).strip() for m in _FENCE.finditer(text)]
    first, last = text.find("{"), text.rfind("}")
    if 0 <= first < last:
        candidates.append(text[first:last + 1])
    for c in candidates:
        try:
            value = json.loads(c)
        except ValueError:
            continue
        if isinstance(value, dict):
            return value
    return None


def _short(text: str, limit: int = 200) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit] + "..."


def make_backend(spec: LLMSpec, *, timeout: float) -> Backend:
    """The backend a spec names (imports the provider's client only when used)."""
    if spec.provider == "openai":
        from emboteam.llm.openai_backend import OpenAIBackend

        return OpenAIBackend(spec, timeout=timeout)
    if spec.provider == "anthropic":
        from emboteam.llm.anthropic_backend import AnthropicBackend

        return AnthropicBackend(spec, timeout=timeout)
    if spec.provider == "llamacpp":
        from emboteam.llm.llamacpp_backend import LlamaCppBackend

        return LlamaCppBackend(spec, timeout=timeout)
    return ReplayBackend(spec.model)


def make_client(spec: LLMSpec | str, *, timeout: float = DEFAULT_TIMEOUT, budget: Budget | None = None,
                record_dir: str | Path | None = None, retry: RetryPolicy | None = None,
                seed: int = 0) -> LLMClient:
    """A client for ``PROVIDER:MODEL[@BASE_URL]``; with ``record_dir`` every answer is also
    written to that cassette folder (replay it later with ``replay:DIR``)."""
    if isinstance(spec, str):
        spec = parse_llm_spec(spec)
    if timeout <= 0:
        raise LLMConfigError(f"the LLM time-out must be positive, got {timeout}")
    backend = make_backend(spec, timeout=timeout)
    if record_dir is not None:
        if spec.provider == "replay":
            raise LLMConfigError("recording a replay is pointless: the cassette already holds the answers")
        backend = RecordingBackend(backend, record_dir)
    return LLMClient(backend, budget=budget, retry=retry, seed=seed)
