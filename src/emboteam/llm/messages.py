"""Provider-independent requests and responses, and the canonical request key.

A request is what a pipeline stage asks (messages, an optional JSON schema, sampling
parameters); each backend translates it into its provider's wire format. The *key* of a
request is a SHA-256 over a canonical JSON form of exactly these fields, so a recording
made with one provider replays for the same request whatever the provider, and any
change to a prompt, the schema or a parameter is a different key (a replay miss, not a
silently wrong answer).
"""

from __future__ import annotations

import hashlib
import json
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

Role = Literal["system", "user", "assistant"]

#: bumped when the canonical form changes, so old cassettes miss instead of mismatching
KEY_VERSION = 1


class Message(BaseModel):
    model_config = ConfigDict(frozen=True)

    role: Role
    content: str


class LLMRequest(BaseModel):
    """One call a stage makes. ``schema`` (a JSON schema) asks for structured output."""

    model_config = ConfigDict(frozen=True)

    stage: str = Field(description="pipeline stage, e.g. pfg, hp.validate; the usage ledger key")
    messages: tuple[Message, ...] = Field(min_length=1)
    json_schema: dict[str, Any] | None = Field(None, description="the answer must be a JSON object of this schema")
    schema_name: str = Field("answer", pattern=r"^[A-Za-z0-9_-]{1,64}$",
                             description="the schema's name (OpenAI json_schema name, Anthropic tool name)")
    max_tokens: int = Field(2048, ge=1)
    temperature: float = Field(0.0, ge=0.0, le=2.0)
    seed: int = 0

    def canonical(self) -> dict[str, Any]:
        """The fields that define the request, in a provider-independent form."""
        return {
            "v": KEY_VERSION,
            "stage": self.stage,
            "messages": [{"role": m.role, "content": m.content} for m in self.messages],
            "schema": self.json_schema,
            "schema_name": self.schema_name if self.json_schema is not None else None,
            "max_tokens": self.max_tokens,
            "temperature": self.temperature,
            "seed": self.seed,
        }

    def key(self) -> str:
        """SHA-256 (hex) of the canonical form with sorted keys and no whitespace."""
        blob = json.dumps(self.canonical(), sort_keys=True, separators=(",", ":"), ensure_ascii=False)
        return hashlib.sha256(blob.encode("utf-8")).hexdigest()

    def system_text(self) -> str:
        return "\n\n".join(m.content for m in self.messages if m.role == "system")

    def dialogue(self) -> list[Message]:
        """The non-system messages (Anthropic takes the system prompt separately)."""
        return [m for m in self.messages if m.role != "system"]


class LLMResponse(BaseModel):
    """What came back. ``parsed`` is the JSON object for a structured request, else None;
    ``refusal`` is the provider's refusal text when the model declined."""

    model_config = ConfigDict(frozen=True)

    text: str
    parsed: dict[str, Any] | None = None
    refusal: str | None = None
    finish_reason: str = ""
    input_tokens: int = 0
    output_tokens: int = 0
    latency: float = Field(0.0, description="wall-clock seconds of the successful attempt")
    model: str = ""
    replayed: bool = False

    @property
    def tokens(self) -> int:
        return self.input_tokens + self.output_tokens
