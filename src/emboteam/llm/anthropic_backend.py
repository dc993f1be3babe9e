"""Anthropic's Messages API through the official ``anthropic`` client.

Structured output is a forced tool call: the schema becomes the ``input_schema`` of one
tool and ``tool_choice={"type": "tool", "name": ...}`` makes the model answer by calling
it, so the answer arrives as the tool's JSON input rather than as prose. The system
prompt goes in the ``system`` parameter (the Messages API has no system role). The
client's own retries are off (``max_retries=0``): see :mod:`emboteam.llm.retry`.

The current Messages API (anthropic 2.x) takes no sampling parameters, so the request's
``temperature`` and ``seed`` are not sent: Anthropic runs are repeatable through
cassettes, not through seeds.
"""

from __future__ import annotations

import json
import time
from typing import Any

import anthropic

from emboteam.llm.backend import TransientFailure, api_key, parse_retry_after, status_failure
from emboteam.llm.messages import LLMRequest, LLMResponse
from emboteam.llm.spec import LLMSpec


class AnthropicBackend:
    """One Anthropic-compatible endpoint. The API key comes from ``ANTHROPIC_API_KEY`` only
    (passed explicitly, so the client never falls back to profiles on disk)."""

    def __init__(self, spec: LLMSpec, *, timeout: float) -> None:
        key = api_key("ANTHROPIC_API_KEY", spec)
        self.name = str(spec)
        self.model = spec.model
        self._client = anthropic.Anthropic(api_key=key, base_url=spec.base_url, timeout=timeout, max_retries=0)

    def _params(self, request: LLMRequest) -> dict[str, Any]:
        params: dict[str, Any] = {
            "model": self.model,
            "max_tokens": request.max_tokens,
            "messages": [{"role": m.role, "content": m.content} for m in request.dialogue()],
        }
        system = request.system_text()
        if system:
            params["system"] = system
        if request.json_schema is not None:
            params["tools"] = [{
                "name": request.schema_name,
                "description": "Give the answer by calling this tool; its input is the whole answer.",
                "input_schema": request.json_schema,
            }]
            params["tool_choice"] = {"type": "tool", "name": request.schema_name, "disable_parallel_tool_use": True}
        return params

    def send(self, request: LLMRequest) -> LLMResponse:
        start = time.monotonic()
        try:
            message = self._client.messages.create(**self._params(request))
        except anthropic.APITimeoutError:
            raise TransientFailure("timeout", "no answer within the time-out") from None
        except anthropic.APIConnectionError as exc:
            raise TransientFailure("connection", f"cannot reach {self.name}: {exc.message}") from None
        except anthropic.APIStatusError as exc:
            retry_after = parse_retry_after(exc.response.headers.get("retry-after"))
            raise status_failure(exc.status_code, f"HTTP {exc.status_code}: {_short(exc.message)}",
                                 retry_after) from None
        except (anthropic.AnthropicError, ValueError) as exc:
            raise TransientFailure("server", f"unreadable answer: {_short(str(exc))}") from None
        latency = time.monotonic() - start
        texts: list[str] = []
        tool_input: object = None
        for block in getattr(message, "content", None) or []:
            kind = getattr(block, "type", "")
            if kind == "text":
                texts.append(str(getattr(block, "text", "")))
            elif kind == "tool_use" and getattr(block, "name", "") == request.schema_name:
                tool_input = getattr(block, "input", None)
        stop = str(getattr(message, "stop_reason", "") or "")
        if request.json_schema is not None and tool_input is not None:
            text = json.dumps(tool_input, ensure_ascii=False)
        else:
            text = "".join(texts)
        refusal = ("".join(texts) or "the model refused") if stop == "refusal" else None
        usage = getattr(message, "usage", None)
        return LLMResponse(
            text=text,
            refusal=refusal,
            finish_reason=stop,
            input_tokens=int(getattr(usage, "input_tokens", 0) or 0),
            output_tokens=int(getattr(usage, "output_tokens", 0) or 0),
            latency=latency,
            model=str(getattr(message, "model", "") or self.model),
        )


def _short(text: str, limit: int = 300) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit] + "..."
