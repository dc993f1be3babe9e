"""The OpenAI-compatible backend against a real HTTP server on loopback: the wire
format of strict structured output, and every fault ending in a typed error in bounded
time (retries with backoff, Retry-After, time-outs, garbage, refusals)."""

from __future__ import annotations

import time
from typing import Any

import pytest

from emboteam.llm import (
    LLMClient,
    LLMConfigError,
    LLMMalformedOutput,
    LLMRateLimited,
    LLMRefusal,
    LLMRequest,
    LLMServerError,
    LLMTimeout,
    LLMUnreachable,
    Message,
    RetryPolicy,
    ask_structured,
    make_client,
)
from llm_servers import Reply, ScriptedServer, free_port

FAST = RetryPolicy(max_attempts=3, base_delay=0.01, max_delay=0.05)

SCHEMA: dict[str, Any] = {
    "type": "object", "additionalProperties": False, "required": ["colour", "note"],
    "properties": {"colour": {"type": "string", "enum": ["red", "green"]},
                   "note": {"anyOf": [{"type": "string", "maxLength": 20}, {"type": "null"}]}},
}


def ask(stage: str = "t") -> LLMRequest:
    return LLMRequest(stage=stage, messages=(Message(role="system", content="be brief"),
                                             Message(role="user", content="pick a colour")),
                      json_schema=SCHEMA, schema_name="pick", max_tokens=50, seed=7)


def client(server: ScriptedServer, *, timeout: float = 5.0, retry: RetryPolicy = FAST) -> LLMClient:
    return make_client(server.spec("gpt-test"), timeout=timeout, retry=retry)


@pytest.fixture(autouse=True)
def _key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", "sk-test-openai-key")


def test_structured_request_uses_strict_json_schema_and_returns_parsed_json() -> None:
    with ScriptedServer("openai", [Reply.answer({"colour": "red", "note": None}, input_tokens=11,
                                                output_tokens=5)]) as srv:
        c = client(srv)
        response = c.complete(ask())
    body = srv.requests[0]
    assert body["model"] == "gpt-test"
    assert body["temperature"] == 0 and body["seed"] == 7 and body["max_tokens"] == 50
    assert body["messages"][0] == {"role": "system", "content": "be brief"}
    rf = body["response_format"]
    assert rf["type"] == "json_schema"
    assert rf["json_schema"]["name"] == "pick" and rf["json_schema"]["strict"] is True
    # strict mode's portable subset: the length bound stays on our side only
    assert rf["json_schema"]["schema"]["properties"]["note"]["anyOf"][0] == {"type": "string"}
    assert srv.headers[0]["authorization"] == "Bearer sk-test-openai-key"
    assert response.parsed == {"colour": "red", "note": None}
    assert (response.input_tokens, response.output_tokens, response.model) == (11, 5, "scripted-model")
    assert c.usage.by_stage()["t"].calls == 1


def test_429_is_retried_after_the_servers_retry_after() -> None:
    with ScriptedServer("openai", [Reply.error(429, retry_after="0.3"), Reply.answer({"colour": "green",
                                                                                      "note": "x"})]) as srv:
        c = client(srv)
        start = time.monotonic()
        response = c.complete(ask())
        elapsed = time.monotonic() - start
    assert response.parsed == {"colour": "green", "note": "x"}
    assert elapsed >= 0.3
    assert len(srv.requests) == 2
    usage = c.usage.by_stage()["t"]
    assert (usage.calls, usage.attempts) == (1, 2)


def test_5xx_is_retried_then_succeeds() -> None:
    with ScriptedServer("openai", [Reply.error(500), Reply.error(503), Reply.answer({"colour": "red",
                                                                                     "note": None})]) as srv:
        assert client(srv).complete(ask()).parsed == {"colour": "red", "note": None}
    assert len(srv.requests) == 3


def test_persistent_5xx_ends_in_server_error_after_max_attempts() -> None:
    with (ScriptedServer("openai", default=Reply.error(502)) as srv,
          pytest.raises(LLMServerError, match="after 3 attempt") as info):
        client(srv).complete(ask("pfg"))
    assert len(srv.requests) == 3
    assert info.value.stage == "pfg" and info.value.status == 502


def test_persistent_429_ends_in_rate_limited() -> None:
    with (ScriptedServer("openai", default=Reply.error(429, retry_after="0")) as srv,
          pytest.raises(LLMRateLimited, match="rate limiting")):
        client(srv).complete(ask())
    assert len(srv.requests) == 3


def test_retry_after_beyond_the_cap_fails_at_once() -> None:
    with ScriptedServer("openai", default=Reply.error(429, retry_after="3600")) as srv:
        start = time.monotonic()
        with pytest.raises(LLMRateLimited, match="3600"):
            client(srv).complete(ask())
        assert time.monotonic() - start < 2
    assert len(srv.requests) == 1


def test_hanging_server_ends_in_timeout_in_bounded_time() -> None:
    retry = RetryPolicy(max_attempts=2, base_delay=0.01, max_delay=0.01)
    with ScriptedServer("openai", default=Reply.hang(3.0)) as srv:
        start = time.monotonic()
        with pytest.raises(LLMTimeout, match="2 attempt"):
            client(srv, timeout=0.4, retry=retry).complete(ask())
        elapsed = time.monotonic() - start
    assert 0.8 <= elapsed < 2.5  # two attempts of 0.4 s, not the server's 3 s


def test_undecodable_http_body_is_a_server_error() -> None:
    with ScriptedServer("openai", default=Reply.garbage()) as srv, pytest.raises(LLMServerError):
        client(srv).complete(ask())
    assert len(srv.requests) == 3


def test_refusal_is_typed_and_not_retried() -> None:
    with (ScriptedServer("openai", [Reply.refuse("I will not do that.")]) as srv,
          pytest.raises(LLMRefusal, match="I will not do that")):
        client(srv).complete(ask())
    assert len(srv.requests) == 1


def test_unreachable_server() -> None:
    c = make_client(f"openai:m@http://127.0.0.1:{free_port()}/v1", timeout=1, retry=FAST)
    with pytest.raises(LLMUnreachable, match="unreachable"):
        c.complete(ask())


def test_401_is_a_config_error_and_403_too_without_retry() -> None:
    for status in (401, 403):
        with (ScriptedServer("openai", default=Reply.error(status)) as srv,
              pytest.raises(LLMConfigError, match="credentials")):
            client(srv).complete(ask())
        assert len(srv.requests) == 1


def test_400_is_not_retried() -> None:
    with (ScriptedServer("openai", default=Reply.error(400, message="bad schema")) as srv,
          pytest.raises(LLMServerError, match="bad schema") as info):
        client(srv).complete(ask())
    assert info.value.status == 400 and len(srv.requests) == 1


def test_malformed_answers_get_feedback_then_a_typed_error() -> None:
    script = [Reply.answer("not json at all"), Reply.answer({"colour": "blue", "note": None}),
              Reply.answer({"colour": "red"})]
    with ScriptedServer("openai", script) as srv:
        c = client(srv)
        with pytest.raises(LLMMalformedOutput, match="after 3 call") as info:
            ask_structured(c, ask("pfg"), lambda obj: obj, repair_rounds=2)
    assert info.value.stage == "pfg"
    assert len(srv.requests) == 3
    second, third = srv.requests[1]["messages"], srv.requests[2]["messages"]
    assert second[-2] == {"role": "assistant", "content": "not json at all"}
    assert "not a JSON object" in second[-1]["content"]
    assert "'blue' is not an allowed value" in third[-1]["content"]
    assert "'note' is a required property" in str(info.value)
    assert c.usage.by_stage()["pfg"].calls == 1 and c.usage.by_stage()["pfg.repair"].calls == 2


def test_json_in_a_markdown_fence_is_accepted() -> None:
    with ScriptedServer("openai", [Reply.answer('Sure:\n```json\n{"colour": "red", "note": null}\n```')]) as srv:
        assert client(srv).complete(ask()).parsed == {"colour": "red", "note": None}


def test_plain_text_request_sends_no_response_format() -> None:
    request = LLMRequest(stage="chat", messages=(Message(role="user", content="hi"),))
    with ScriptedServer("openai", [Reply.answer("hello")]) as srv:
        response = client(srv).complete(request)
    assert "response_format" not in srv.requests[0]
    assert response.text == "hello" and response.parsed is None
