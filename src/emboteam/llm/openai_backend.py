"""OpenAI-compatible chat completions (OpenAI, vLLM, Ollama, llama.cpp's server) through
the official ``openai`` client.

Structured output uses strict JSON-schema mode
(``response_format={"type": "json_schema", "json_schema": {..., "strict": true}}``):
the server constrains decoding to the schema. Strict mode accepts a subset of JSON
Schema, so :func:`strict_subset` drops length, range and item-count bounds before
sending (the full schema is still checked on our side, and a violation goes back to the
model as feedback). The client's own retries are off (``max_retries=0``): see
:mod:`emboteam.llm.retry`.
"""

from __future__ import annotations

import time
from typing import Any
from urllib.parse import urlsplit

import openai

from emboteam.llm.backend import (
    ScoringUnsupported,
    TransientFailure,
    api_key,
    parse_retry_after,
    status_failure,
)
from emboteam.llm.messages import LLMRequest, LLMResponse
from emboteam.llm.scoring import CandidateScore, ScoreRequest, ScoreResponse
from emboteam.llm.spec import LLMSpec

#: keywords OpenAI's strict mode rejects or ignores; dropped from the wire schema only
_UNPORTABLE = frozenset({"minLength", "maxLength", "minimum", "maximum", "exclusiveMinimum",
                         "exclusiveMaximum", "minItems", "maxItems", "pattern", "format", "default"})

#: what local servers get when no key is set: they ignore it, but the client insists on one


def strict_subset(schema: Any) -> Any:
    """The schema without keywords outside OpenAI strict mode's portable subset."""
    if isinstance(schema, dict):
        return {k: strict_subset(v) for k, v in schema.items() if k not in _UNPORTABLE}
    if isinstance(schema, list):
        return [strict_subset(v) for v in schema]
    return schema


def _is_openai_proper(base_url: str | None) -> bool:
    return base_url is None or (urlsplit(base_url).hostname or "").endswith("openai.com")


class OpenAIBackend:
    """One OpenAI-compatible endpoint. The API key comes from ``OPENAI_API_KEY`` only."""

    def __init__(self, spec: LLMSpec, *, timeout: float) -> None:
        key = api_key("OPENAI_API_KEY", spec)
        self.name = str(spec)
        self.model = spec.model
        self._official = _is_openai_proper(spec.base_url)
        self._client = openai.OpenAI(api_key=key, base_url=spec.base_url, timeout=timeout, max_retries=0)

    def _params(self, request: LLMRequest) -> dict[str, Any]:
        params: dict[str, Any] = {
            "model": self.model,
            "messages": [{"role": m.role, "content": m.content} for m in request.messages],
            "temperature": request.temperature,
            "seed": request.seed,
        }
        # OpenAI's current models take max_completion_tokens and reject max_tokens;
        # vLLM, Ollama and llama.cpp's server take max_tokens.
        params["max_completion_tokens" if self._official else "max_tokens"] = request.max_tokens
        if request.json_schema is not None:
            params["response_format"] = {
                "type": "json_schema",
                "json_schema": {"name": request.schema_name, "schema": strict_subset(request.json_schema),
                                "strict": True},
            }
        return params

    def send(self, request: LLMRequest) -> LLMResponse:
        start = time.monotonic()
        try:
            completion = self._client.chat.completions.create(**self._params(request))
        except openai.APITimeoutError as exc:
            raise TransientFailure("timeout", f"no answer within the time-out ({exc.__class__.__name__})") from None
        except openai.APIConnectionError as exc:
            raise TransientFailure("connection", f"cannot reach {self.name}: {exc.message}") from None
        except openai.APIStatusError as exc:
            retry_after = parse_retry_after(exc.response.headers.get("retry-after"))
            raise status_failure(exc.status_code, f"HTTP {exc.status_code}: {_short(exc.message)}",
                                 retry_after) from None
        except (openai.OpenAIError, ValueError) as exc:  # undecodable body, schema mismatch
            raise TransientFailure("server", f"unreadable answer: {_short(str(exc))}") from None
        latency = time.monotonic() - start
        choices = getattr(completion, "choices", None)
        if not choices:
            raise TransientFailure("server", "the answer has no choices")
        choice = choices[0]
        message = choice.message
        text = message.content or ""
        usage = completion.usage
        return LLMResponse(
            text=text,
            parsed=None,
            refusal=getattr(message, "refusal", None) or None,
            finish_reason=str(choice.finish_reason or ""),
            input_tokens=int(getattr(usage, "prompt_tokens", 0) or 0) if usage else 0,
            output_tokens=int(getattr(usage, "completion_tokens", 0) or 0) if usage else 0,
            latency=latency,
            model=str(completion.model or self.model),
        )


    # ---- PMI scoring through the completions endpoint -----------------------------------
    def score(self, request: ScoreRequest) -> ScoreResponse:
        """Log-probabilities of each candidate after both scoring prompts, one request per
        (prompt, candidate): ``/v1/completions`` with ``echo=True, logprobs=1, max_tokens=1``
        returns the prompt's own tokens with their log-probabilities (llama.cpp's server
        with ``logits_all``, vLLM). A server that refuses these parameters or returns no
        log-probabilities (OpenAI's current models) raises :class:`ScoringUnsupported`;
        the server's own prefix cache is what saves the shared prompt's evaluation."""
        start = time.monotonic()
        given: list[tuple[float, int]] = []
        alone: list[tuple[float, int]] = []
        total = 0
        for prefix, out in ((request.conditional, given), (request.unconditional, alone)):
            for sentence in request.candidates:
                logprob, n_sentence, n_prompt = self._sentence_logprob(prefix, sentence)
                out.append((logprob, n_sentence))
                total += n_prompt
        scores = tuple(CandidateScore(sentence=text, conditional=c[0], unconditional=u[0], tokens=c[1])
                       for text, c, u in zip(request.candidates, given, alone, strict=True))
        return ScoreResponse(scores=scores, input_tokens=total, evaluated_tokens=total,
                             latency=time.monotonic() - start, model=self.model)

    def _echo(self, text: str) -> Any:
        try:
            return self._client.completions.create(model=self.model, prompt=text, echo=True, logprobs=1,
                                                   max_tokens=1, temperature=0.0, seed=0)
        except openai.APITimeoutError as exc:
            raise TransientFailure("timeout", f"no answer within the time-out ({exc.__class__.__name__})") from None
        except openai.APIConnectionError as exc:
            raise TransientFailure("connection", f"cannot reach {self.name}: {exc.message}") from None
        except openai.APIStatusError as exc:
            message = f"HTTP {exc.status_code}: {_short(exc.message)}"
            if exc.status_code in _NO_SCORING_STATUS or "logprobs" in exc.message.lower():
                raise ScoringUnsupported(f"the completions endpoint refused echo/logprobs ({message})") from None
            raise status_failure(exc.status_code, message,
                                 parse_retry_after(exc.response.headers.get("retry-after"))) from None
        except (openai.OpenAIError, ValueError) as exc:
            raise TransientFailure("server", f"unreadable answer: {_short(str(exc))}") from None

    def _sentence_logprob(self, prefix: str, sentence: str) -> tuple[float, int, int]:
        """log P(sentence | prefix), the sentence's tokens and the prompt's tokens, from the
        echoed prompt's tokens whose character offset falls inside the sentence.

        Offsets count from the end of the prompt: llama.cpp's server leaves the special
        tokens' text out of its offsets (while ``text`` has it), so the prompt ends at the
        offset of the one generated token, and the sentence is the last ``len(sentence)``
        characters before it."""
        completion = self._echo(prefix + sentence)
        choices = getattr(completion, "choices", None)
        logprobs = getattr(choices[0], "logprobs", None) if choices else None
        tokens = getattr(logprobs, "tokens", None)
        offsets = getattr(logprobs, "text_offset", None)
        values = getattr(logprobs, "token_logprobs", None)
        if not tokens or not offsets or not values or not len(tokens) == len(offsets) == len(values):
            raise ScoringUnsupported("the completions endpoint returned no prompt log-probabilities for echo=True")
        usage = getattr(completion, "usage", None)
        generated = int(getattr(usage, "completion_tokens", 0) or 0) if usage else 0
        if 0 < generated < len(offsets):
            end = int(offsets[len(offsets) - generated])
            prompt_part = range(len(offsets) - generated)
        else:  # nothing generated (an end-of-text at once): the prompt is all there is
            end = int(offsets[-1]) + len(str(tokens[-1]))
            prompt_part = range(len(offsets))
        begin = end - len(sentence)
        picked = [values[i] for i in prompt_part if begin <= offsets[i] < end]
        if not picked or any(v is None for v in picked):
            raise TransientFailure("server", "the echoed prompt has no log-probabilities for the sentence")
        prompt_tokens = int(getattr(usage, "prompt_tokens", 0) or 0) if usage else 0
        return float(sum(picked)), len(picked), prompt_tokens


#: statuses by which a server says it does not do echo/logprobs on completions (OpenAI
#: proper answers 400 for current chat models; a chat-only server 404 or 405)
_NO_SCORING_STATUS = frozenset({400, 404, 405, 422, 501})


def _short(text: str, limit: int = 300) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit] + "..."

