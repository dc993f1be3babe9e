"""The ``--llm`` spec string: ``PROVIDER:MODEL[@BASE_URL]``.

Examples::

    openai:gpt-4o-mini                              OpenAI itself (OPENAI_API_KEY)
    openai:qwen2.5-7b@http://127.0.0.1:8000/v1      any OpenAI-compatible server (vLLM,
                                                    Ollama, llama.cpp's server)
    anthropic:claude-sonnet-4-5                     Anthropic (ANTHROPIC_API_KEY)
    llamacpp:/models/qwen2.5-1.5b-q4.gguf           a local GGUF file, in process
    replay:runs/cassettes/gpt-4o                    recorded answers, no model needed

The base URL is split off at the ``@`` that starts an ``http://`` or ``https://`` URL,
so model names with ``:`` (Ollama's ``llama3.1:8b``) and paths with ``@`` work. API keys
come from the environment only; a URL with credentials in it is refused.
"""

from __future__ import annotations

import re
from typing import Literal
from urllib.parse import urlsplit

from pydantic import BaseModel, ConfigDict

from emboteam.llm.errors import LLMConfigError

Provider = Literal["openai", "anthropic", "llamacpp", "replay"]
PROVIDERS: tuple[Provider, ...] = ("openai", "anthropic", "llamacpp", "replay")

_BASE_URL = re.compile(r"@(https?://\S*)$", re.IGNORECASE)


class LLMSpec(BaseModel):
    """Which backend, which model, and (for HTTP backends) which server."""

    model_config = ConfigDict(frozen=True)

    provider: Provider
    model: str
    base_url: str | None = None

    def __str__(self) -> str:
        """The spec as typed; it holds no secret (URL credentials are refused)."""
        text = f"{self.provider}:{self.model}"
        return f"{text}@{self.base_url}" if self.base_url else text


def parse_llm_spec(text: str) -> LLMSpec:
    """Parse ``PROVIDER:MODEL[@BASE_URL]``; raise :class:`LLMConfigError` naming the problem."""
    raw = text.strip()
    provider, sep, rest = raw.partition(":")
    provider = provider.strip().lower()
    if not sep or provider not in PROVIDERS:
        raise LLMConfigError(
            f"bad LLM spec {raw!r}: expected PROVIDER:MODEL[@BASE_URL] with PROVIDER one of "
            f"{', '.join(PROVIDERS)} (e.g. openai:gpt-4o-mini@http://127.0.0.1:8080/v1)")
    base_url: str | None = None
    m = _BASE_URL.search(rest)
    if m:
        base_url = m.group(1)
        rest = rest[: m.start()]
    model = rest.strip()
    if not model:
        raise LLMConfigError(f"bad LLM spec {raw!r}: the model is missing after '{provider}:'")
    if base_url is None and provider in ("openai", "anthropic") and "@" in model:
        # their model names have no '@': this is a base URL without its scheme
        raise LLMConfigError(f"bad LLM spec {raw!r}: the base URL after '@' must start with http:// or "
                             f"https:// (e.g. {provider}:{model.rpartition('@')[0]}@http://127.0.0.1:8080/v1)")
    if base_url is not None:
        parts = urlsplit(base_url)
        if not parts.hostname:
            raise LLMConfigError(f"bad LLM spec {raw!r}: base URL {base_url!r} has no host")
        if parts.username is not None or parts.password is not None:
            # HTTP libraries log request URLs, and the clients would turn them into Basic
            # auth in place of the key: keys belong in the environment only.
            raise LLMConfigError("credentials in the LLM base URL are refused: put the key in "
                                 "OPENAI_API_KEY or ANTHROPIC_API_KEY")
        if provider in ("llamacpp", "replay"):
            raise LLMConfigError(f"bad LLM spec {raw!r}: {provider} takes no base URL "
                                 f"(its MODEL is a {'.gguf file' if provider == 'llamacpp' else 'folder'})")
    return LLMSpec(provider=provider, model=model, base_url=base_url)
