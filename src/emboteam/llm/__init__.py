"""LLM backends behind one interface: OpenAI-compatible, Anthropic, local llama.cpp,
record/replay; structured output, retries, budget and per-stage usage (docs/llm.md)."""

from emboteam.llm.cassette import Cassette, RecordingBackend, ReplayBackend
from emboteam.llm.client import DEFAULT_TIMEOUT, LLMClient, extract_json_object, make_backend, make_client
from emboteam.llm.errors import (
    LLMBudgetExceeded,
    LLMConfigError,
    LLMError,
    LLMMalformedOutput,
    LLMRateLimited,
    LLMRefusal,
    LLMReplayMiss,
    LLMServerError,
    LLMTimeout,
    LLMUnreachable,
)
from emboteam.llm.messages import LLMRequest, LLMResponse, Message
from emboteam.llm.retry import RetryPolicy
from emboteam.llm.spec import LLMSpec, parse_llm_spec
from emboteam.llm.structured import Rejected, ask_structured
from emboteam.llm.usage import Budget, StageUsage, Usage

__all__ = [
    "DEFAULT_TIMEOUT", "Budget", "Cassette", "LLMBudgetExceeded", "LLMClient", "LLMConfigError", "LLMError",
    "LLMMalformedOutput", "LLMRateLimited", "LLMRefusal", "LLMReplayMiss", "LLMRequest", "LLMResponse",
    "LLMServerError", "LLMSpec", "LLMTimeout", "LLMUnreachable", "Message", "RecordingBackend", "Rejected",
    "ReplayBackend", "RetryPolicy", "StageUsage", "Usage", "ask_structured", "extract_json_object",
    "make_backend", "make_client", "parse_llm_spec",
]
