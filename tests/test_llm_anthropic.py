"""The Anthropic backend against a loopback /v1/messages server: structured output as a
forced tool call, the system prompt as a parameter, faults as typed errors."""

from __future__ import annotations

import time
from typing import Any

import pytest

from emboteam.llm import (
    LLMClient,
    LLMRefusal,
    LLMRequest,
    LLMServerError,
    LLMTimeout,
    Message,
    RetryPolicy,
    make_client,
)
from llm_servers import Reply, ScriptedServer

FAST = RetryPolicy(max_attempts=3, base_delay=0.01, max_delay=0.05)
SCHEMA: dict[str, Any] = {
    "type": "object", "additionalProperties": False, "required": ["colour"],
    "properties": {"colour": {"type": "string", "enum": ["red", "green"], "maxLength": 5}},
}


def ask(schema: dict[str, Any] | None = SCHEMA) -> LLMRequest:
    return LLMRequest(stage="t", messages=(Message(role="system", content="be brief"),
                                           Message(role="user", content="pick a colour")),
                      json_schema=schema, schema_name="pick", max_tokens=64)


def client(server: ScriptedServer, *, timeout: float = 5.0) -> LLMClient:
    return make_client(server.spec("claude-test"), timeout=timeout, retry=FAST)


@pytest.fixture(autouse=True)
def _key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ANTHROPIC_API_KEY", "sk-ant-test-key")


def test_structured_request_is_a_forced_tool_call() -> None:
    with ScriptedServer("anthropic", [Reply.answer({"colour": "green"}, input_tokens=20, output_tokens=4)]) as srv:
        response = client(srv).complete(ask())
    body = srv.requests[0]
    assert body["model"] == "claude-test" and body["max_tokens"] == 64
    assert body["system"] == "be brief"
    assert body["messages"] == [{"role": "user", "content": "pick a colour"}]
    assert body["tools"][0]["name"] == "pick"
    assert body["tools"][0]["input_schema"] == SCHEMA  # the full schema: Anthropic takes it as is
    assert body["tool_choice"]["type"] == "tool" and body["tool_choice"]["name"] == "pick"
    # the key from ANTHROPIC_API_KEY (sent as x-api-key or, by anthropic 2.x, as a bearer token)
    sent = srv.headers[0]
    assert "sk-ant-test-key" in (sent.get("x-api-key"), sent.get("authorization", "").removeprefix("Bearer "))
    assert response.parsed == {"colour": "green"}
    assert (response.input_tokens, response.output_tokens) == (20, 4)
    assert response.finish_reason == "tool_use"


def test_plain_text_request_has_no_tools() -> None:
    with ScriptedServer("anthropic", [Reply.answer("hello")]) as srv:
        response = client(srv).complete(ask(None))
    assert "tools" not in srv.requests[0] and "tool_choice" not in srv.requests[0]
    assert response.text == "hello" and response.parsed is None


def test_overloaded_529_is_retried() -> None:
    with ScriptedServer("anthropic", [Reply.error(529), Reply.answer({"colour": "red"})]) as srv:
        assert client(srv).complete(ask()).parsed == {"colour": "red"}
    assert len(srv.requests) == 2


def test_persistent_500_is_a_server_error() -> None:
    with (ScriptedServer("anthropic", default=Reply.error(500)) as srv,
          pytest.raises(LLMServerError, match="after 3 attempt")):
        client(srv).complete(ask())


def test_refusal_stop_reason_is_typed() -> None:
    with (ScriptedServer("anthropic", [Reply.refuse("No.")]) as srv,
          pytest.raises(LLMRefusal, match=r"No\.")):
        client(srv).complete(ask())
    assert len(srv.requests) == 1


def test_hanging_server_times_out() -> None:
    with ScriptedServer("anthropic", default=Reply.hang(3.0)) as srv:
        start = time.monotonic()
        with pytest.raises(LLMTimeout):
            make_client(srv.spec(), timeout=0.3,
                        retry=RetryPolicy(max_attempts=2, base_delay=0.01, max_delay=0.01)).complete(ask())
        assert time.monotonic() - start < 2.5
