"""Record/replay: exact, provider-independent, loud on a miss, and free of secrets."""

from __future__ import annotations

import json
import logging
from collections.abc import Sequence
from pathlib import Path

import pytest

from emboteam.llm import LLMConfigError, LLMReplayMiss, LLMRequest, Message, RetryPolicy, make_client
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState
from llm_servers import Reply, ScriptedServer, cond, subtask, taskspec_answer

FAST = RetryPolicy(max_attempts=2, base_delay=0.01, max_delay=0.02)
ANSWER = taskspec_answer(
    subtask("s1", cond("sliced", "Tomato_1"), robot="robot1"),
    subtask("s2", cond("inside", "TomatoSliced", receptacle="Plate"), robot="robot2", depends_on=("s1",)),
)
OPENAI_SECRET = "sk-proj-SECRET-0123456789"
ANTHROPIC_SECRET = "sk-ant-SECRET-9876543210"


@pytest.fixture(autouse=True)
def _keys(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", OPENAI_SECRET)
    monkeypatch.setenv("ANTHROPIC_API_KEY", ANTHROPIC_SECRET)


def test_record_then_replay_gives_the_identical_taskspec(tmp_path: Path, scene1: Scene, state1: WorldState,
                                                         team12: Sequence[RobotProfile]) -> None:
    instruction = "Slice the tomato and put a slice on the plate."
    with ScriptedServer("openai", [Reply.answer(ANSWER, input_tokens=900, output_tokens=120)]) as srv:
        recorder = make_client(srv.spec(), timeout=5, retry=FAST, record_dir=tmp_path / "cas")
        recorded = LLMFrontend(recorder).decompose(instruction, scene1, state1, team12)
    replayer = make_client(f"replay:{tmp_path / 'cas'}")
    replayed = LLMFrontend(replayer).decompose(instruction, scene1, state1, team12)
    assert replayed == recorded
    assert len(srv.requests) == 1  # the replay never touched the server (it is closed anyway)
    # the ledger reproduces too: the same calls and tokens as the recorded run
    assert replayer.usage.to_dict() == recorder.usage.to_dict()
    assert replayer.usage.tokens == 1020


def test_a_request_the_cassette_lacks_fails_loudly_naming_stage_and_key(
        tmp_path: Path, scene1: Scene, state1: WorldState, team12: Sequence[RobotProfile]) -> None:
    with ScriptedServer("openai", [Reply.answer(ANSWER)]) as srv:
        LLMFrontend(make_client(srv.spec(), retry=FAST, record_dir=tmp_path)).decompose(
            "Slice the tomato.", scene1, state1, team12)
    frontend = LLMFrontend(make_client(f"replay:{tmp_path}"))
    with pytest.raises(LLMReplayMiss) as info:
        frontend.decompose("Slice the tomato, please.", scene1, state1, team12)
    expected_key = frontend.request("Slice the tomato, please.", scene1, state1, team12).key()
    assert info.value.stage == "pfg" and info.value.key == expected_key
    assert "[pfg]" in str(info.value) and expected_key in str(info.value)


def test_replay_is_provider_independent(tmp_path: Path, scene1: Scene, state1: WorldState,
                                        team12: Sequence[RobotProfile]) -> None:
    """Recorded through Anthropic's tool call, replayed without any provider."""
    with ScriptedServer("anthropic", [Reply.answer(ANSWER)]) as srv:
        recorded = LLMFrontend(make_client(srv.spec(), retry=FAST, record_dir=tmp_path)).decompose(
            "Slice the tomato.", scene1, state1, team12)
    assert LLMFrontend(make_client(f"replay:{tmp_path}")).decompose(
        "Slice the tomato.", scene1, state1, team12) == recorded
    meta = json.loads((tmp_path / "cassette.json").read_text())
    assert meta["recorded_with"] == [f"anthropic:test-model@{srv.base_url}"]


def test_request_key_is_canonical() -> None:
    base = LLMRequest(stage="pfg", messages=(Message(role="user", content="a"),), json_schema={"type": "object"})
    same = LLMRequest.model_validate(json.loads(base.model_dump_json()))
    assert same.key() == base.key()
    for change in ({"messages": (Message(role="user", content="b"),)}, {"json_schema": {"type": "array"}},
                   {"temperature": 0.5}, {"seed": 1}, {"max_tokens": 10}, {"stage": "hp.validate"}):
        assert base.model_copy(update=change).key() != base.key(), change


def test_keys_never_reach_cassettes_or_logs(tmp_path: Path, caplog: pytest.LogCaptureFixture, scene1: Scene,
                                            state1: WorldState, team12: Sequence[RobotProfile]) -> None:
    caplog.set_level(logging.DEBUG)
    with ScriptedServer("openai", [Reply.error(500), Reply.answer(ANSWER)]) as srv:
        client = make_client(srv.spec(), retry=FAST, record_dir=tmp_path / "o")
        LLMFrontend(client).decompose("Slice the tomato.", scene1, state1, team12)
    with ScriptedServer("anthropic", [Reply.answer(ANSWER)]) as srv2:
        LLMFrontend(make_client(srv2.spec(), retry=FAST, record_dir=tmp_path / "a")).decompose(
            "Slice the tomato.", scene1, state1, team12)
    assert srv.headers[-1]["authorization"] == f"Bearer {OPENAI_SECRET}"  # the key was really used
    assert ANTHROPIC_SECRET in srv2.headers[-1].get("authorization", "") + srv2.headers[-1].get("x-api-key", "")
    files = list(tmp_path.rglob("*"))
    assert len([f for f in files if f.suffix == ".json"]) == 4
    for f in files:
        if f.is_file():
            text = f.read_text()
            for secret in (OPENAI_SECRET, ANTHROPIC_SECRET):
                assert secret not in text, f"{secret} leaked into {f}"
    logged = "\n".join(r.getMessage() for r in caplog.records)
    assert "attempt 1/2 failed" in logged  # the retry was logged ...
    for secret in (OPENAI_SECRET, ANTHROPIC_SECRET):
        assert secret not in logged  # ... without any secret (third-party loggers included)


def test_corrupt_or_foreign_cassettes_are_typed_errors(tmp_path: Path) -> None:
    request = LLMRequest(stage="pfg", messages=(Message(role="user", content="a"),))
    (tmp_path / "cassette.json").write_text('{"format": "something-else"}')
    with pytest.raises(LLMConfigError, match="not an EmboTeam LLM cassette"):
        make_client(f"replay:{tmp_path}")
    (tmp_path / "cassette.json").write_text('{"format": "emboteam-llm-cassette", "version": 1}')
    (tmp_path / f"{request.key()}.json").write_text("{not json")
    with pytest.raises(LLMReplayMiss, match="unusable cassette entry"):
        make_client(f"replay:{tmp_path}").complete(request)
