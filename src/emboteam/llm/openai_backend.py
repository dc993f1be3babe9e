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

from emboteam.llm.backend import TransientFailure, api_key, parse_retry_after, status_failure
from emboteam.llm.messages import LLMRequest, LLMResponse
from emboteam.llm.spec import LLMSpec

#: keywords OpenAI's strict mode rejects or ignores; dropped from the wire schema only
_UNPORTABLE = frozenset({"minLength", "maxLength", "minimum", "maximum", "exclusiveMinimum",
                         "exclusiveMaximum", "minItems", "maxItems", "pattern", "format", "default"})

#: what local servers get when no key is set: they ignore it, but the client insists on one


def strict_subset(schema: Any) -> Any:
    """The schema without keywords outside OpenAI strict mode's portable subset. The
    schemas state every such bound in the node's ``description`` too (the model reads it
    on every backend; tests/test_llm_schema_limits.py checks this), and the full schema is
    checked on our side."""
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


def _short(text: str, limit: int = 300) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit] + "..."

