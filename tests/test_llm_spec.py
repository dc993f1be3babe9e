"""The --llm spec string and the configuration errors of make_client."""

from __future__ import annotations

from pathlib import Path

import pytest

from emboteam.errors import EmboTeamError
from emboteam.llm import LLMConfigError, LLMSpec, make_client, parse_llm_spec


@pytest.mark.parametrize(("text", "expected"), [
    ("openai:gpt-4o-mini", LLMSpec(provider="openai", model="gpt-4o-mini")),
    ("openai:qwen2.5-7b@http://127.0.0.1:8000/v1",
     LLMSpec(provider="openai", model="qwen2.5-7b", base_url="http://127.0.0.1:8000/v1")),
    # Ollama model tags contain ':'
    ("openai:llama3.1:8b@http://localhost:11434/v1",
     LLMSpec(provider="openai", model="llama3.1:8b", base_url="http://localhost:11434/v1")),
    ("Anthropic:claude-sonnet-4-5", LLMSpec(provider="anthropic", model="claude-sonnet-4-5")),
    ("anthropic:claude-x@https://proxy.example.com",
     LLMSpec(provider="anthropic", model="claude-x", base_url="https://proxy.example.com")),
    # a path may contain '@' when no URL follows it
    ("llamacpp:/models/me@home/q.gguf", LLMSpec(provider="llamacpp", model="/models/me@home/q.gguf")),
    ("replay:runs/cassettes/gpt-4o", LLMSpec(provider="replay", model="runs/cassettes/gpt-4o")),
])
def test_parse_llm_spec_accepts_documented_forms(text: str, expected: LLMSpec) -> None:
    assert parse_llm_spec(text) == expected


@pytest.mark.parametrize(("text", "fragment"), [
    ("gpt-4o", "PROVIDER:MODEL"),
    ("mistral:large", "PROVIDER one of"),
    ("openai:", "model is missing"),
    ("openai:@http://127.0.0.1:8000/v1", "model is missing"),
    ("llamacpp:/m.gguf@http://127.0.0.1:8000", "takes no base URL"),
    ("replay:dir@http://127.0.0.1:1", "takes no base URL"),
    ("openai:m@http://", "has no host"),
])
def test_parse_llm_spec_rejects_bad_specs_with_a_typed_error(text: str, fragment: str) -> None:
    with pytest.raises(LLMConfigError, match=fragment) as info:
        parse_llm_spec(text)
    assert isinstance(info.value, EmboTeamError)


def test_credentials_in_the_base_url_are_refused() -> None:
    """HTTP libraries log URLs, and the clients would send them as Basic auth instead of the
    key: secrets go in the environment only."""
    with pytest.raises(LLMConfigError, match="credentials in the LLM base URL") as info:
        parse_llm_spec("openai:m@http://user:s3cret@127.0.0.1:8000/v1")
    assert "s3cret" not in str(info.value)


def test_openai_without_key_or_base_url_is_a_config_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    with pytest.raises(LLMConfigError, match="OPENAI_API_KEY"):
        make_client("openai:gpt-4o-mini")


def test_anthropic_without_key_or_base_url_is_a_config_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ANTHROPIC_API_KEY", raising=False)
    with pytest.raises(LLMConfigError, match="ANTHROPIC_API_KEY"):
        make_client("anthropic:claude-x")


def test_local_server_needs_no_key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    client = make_client("openai:m@http://127.0.0.1:9/v1", timeout=1)
    assert client.name == "openai:m@http://127.0.0.1:9/v1"


def test_missing_gguf_file_and_missing_cassette_are_config_errors(tmp_path: Path) -> None:
    with pytest.raises(LLMConfigError, match="no GGUF file"):
        make_client(f"llamacpp:{tmp_path / 'absent.gguf'}")
    with pytest.raises(LLMConfigError, match="no cassette"):
        make_client(f"replay:{tmp_path / 'absent'}")


def test_non_positive_timeout_and_recording_a_replay_are_config_errors(tmp_path: Path) -> None:
    with pytest.raises(LLMConfigError, match="time-out"):
        make_client("openai:m@http://127.0.0.1:9/v1", timeout=0)
    (tmp_path / "c").mkdir()
    (tmp_path / "c" / "cassette.json").write_text('{"format": "emboteam-llm-cassette", "version": 1}')
    with pytest.raises(LLMConfigError, match="pointless"):
        make_client(f"replay:{tmp_path / 'c'}", record_dir=tmp_path / "d")
