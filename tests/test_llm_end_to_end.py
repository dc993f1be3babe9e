"""The LLM front end through the whole system and the ``emboteam`` command, against a
real OpenAI-compatible HTTP server on loopback: happy path in two calls, a recorded
cassette replayed without the server, and a misbehaving server ending in a clear
``success: false`` within bounded time."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

from llm_servers import Reply, ScriptedServer, cond, subtask, taskspec_answer

EMBOTEAM = str(Path(sys.executable).parent / "emboteam")
INSTRUCTION = "Put the apple in the fridge and turn off the light."
SPEC = taskspec_answer(
    subtask("s1", cond("inside", "Apple_1", receptacle="Fridge_1"), robot="robot1"),
    subtask("s2", cond("switched_off", "LightSwitch_1"), robot="robot2"),
)
REVIEW_OK = {"verdict": "ok", "reason": "matches the instruction", "subtasks": []}


def run_cli(*args: str, code: int = 0) -> tuple[dict[str, object], subprocess.CompletedProcess[str]]:
    """``emboteam run INSTRUCTION ... --json``; ``--frontend llm`` unless ARGS choose one."""
    env = {**os.environ, "OPENAI_API_KEY": "sk-loopback-test-key"}
    if "--frontend" not in args:
        args = ("--frontend", "llm", *args)
    proc = subprocess.run([EMBOTEAM, "run", INSTRUCTION, "--scene", "FloorPlan1", "--robots", "1,2", *args,
                           "--json"], capture_output=True, text=True, timeout=300, env=env)
    assert proc.returncode == code, proc.stderr  # docs/cli.md: 0 goal reached, 1 failed, 3 LLM unusable
    return json.loads(proc.stdout), proc


def test_llm_happy_path_is_two_calls_then_replays_without_the_model(tmp_path: Path) -> None:
    cassette = tmp_path / "cassette"
    with ScriptedServer("openai", [Reply.answer(SPEC), Reply.answer(REVIEW_OK)]) as srv:
        live, proc = run_cli("--llm", srv.spec("gpt-test"), "--llm-record", str(cassette))
        assert len(srv.requests) == 2  # one PFG call, one HP validation call
    assert live["success"] is True and live["llm_calls"] == 2 and int(str(live["tokens"])) > 0
    assert "sk-loopback-test-key" not in proc.stderr
    for f in cassette.rglob("*"):
        if f.is_file():
            assert "sk-loopback-test-key" not in f.read_text()  # keys never reach cassettes
    replayed, _ = run_cli("--llm", f"replay:{cassette}")  # the server is gone now
    keep = ("success", "gcr", "exec", "makespan", "actions", "llm_calls", "tokens")
    assert {k: replayed[k] for k in keep} == {k: live[k] for k in keep}


def test_a_hanging_server_ends_in_a_failed_episode_within_bounded_time() -> None:
    with ScriptedServer("openai", default=Reply.hang(30)) as srv:
        start = time.monotonic()
        result, _ = run_cli("--llm", srv.spec("gpt-test"), "--llm-timeout", "0.5", code=3)
        elapsed = time.monotonic() - start
    assert result["success"] is False and result["error_type"] == "LLMTimeout" and result["exit_code"] == 3
    assert elapsed < 25, f"took {elapsed:.1f} s"


def test_garbage_from_the_server_is_a_clear_error_not_a_traceback() -> None:
    with ScriptedServer("openai", default=Reply.answer("I would rather write a poem about fridges.")) as srv:
        result, proc = run_cli("--llm", srv.spec("gpt-test"), code=1)  # the service answered, badly
    assert result["success"] is False and result["error"]
    assert "Traceback" not in proc.stderr


def test_llm_merge_ordering_is_in_the_plan(tmp_path: Path) -> None:
    """The paper's LLM merge: a third call proposes orderings; an acceptable one becomes a
    dependency the formal merge honours (the light goes off only after the apple is in)."""
    orderings = {"orderings": [{"before": "s1", "after": "s2", "reason": "light off last"}]}
    with ScriptedServer("openai", [Reply.answer(SPEC), Reply.answer(REVIEW_OK), Reply.answer(orderings)]) as srv:
        result, _ = run_cli("--llm", srv.spec("gpt-test"), "--llm-merge", "--out", str(tmp_path))
        assert len(srv.requests) == 3
    assert result["success"] is True and result["llm_calls"] == 3
    episode = json.loads((tmp_path / "episode.json").read_text())
    spec = {s["id"]: s for s in episode["taskspec"]["subtasks"]}
    assert spec["s2"]["depends_on"] == ["s1"]
    steps = episode["plan"]["steps"]  # the dependency is causal: the switch-off waits for the put
    put = next(s for s in steps if s["subtask"] == "s1" and s["action"]["skill"] == "PutObject")
    off = next(s for s in steps if s["subtask"] == "s2" and s["action"]["skill"] == "SwitchOff")
    assert off["est_start"] >= put["est_end"] - 1e-6
