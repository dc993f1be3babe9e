""""I cannot tell" is an answer: the LLM front end takes a clarification instead of a
forced guess, raises it as a typed ClarificationNeeded (the ``clarification`` field of
``run --json`` / ``plan --json``), and a ``clarify`` hook can settle it with the
person's choice, asked once more as the user's words."""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path

import pytest

from emboteam.llm import LLMClient, LLMMalformedOutput, RetryPolicy, make_client
from emboteam.pfg.clarification import Clarification, ClarificationNeeded, ask_terminal
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState
from llm_servers import Reply, ScriptedServer, cond, subtask, taskspec_answer

FAST = RetryPolicy(max_attempts=1, base_delay=0.01, max_delay=0.02)
EMBOTEAM = str(Path(sys.executable).parent / "emboteam")
AMBIGUOUS = "Put it away."
ASK = {"subtasks": [], "clarification": {
    "question": "What should I put away, and where?",
    "readings": ["Put the apple in the fridge.", "Put the mug in the cabinet."]}}
APPLE_IN_FRIDGE = taskspec_answer(subtask("s1", cond("inside", "Apple", receptacle="Fridge")))


@pytest.fixture(autouse=True)
def _key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", "sk-test")


def llm(server: ScriptedServer) -> LLMClient:
    return make_client(server.spec(), timeout=5, retry=FAST)


def test_a_clarification_is_raised_typed_not_guessed(scene1: Scene, state1: WorldState,
                                                     team12: Sequence[RobotProfile]) -> None:
    with ScriptedServer("openai", [Reply.answer(ASK)]) as srv, pytest.raises(ClarificationNeeded) as info:
        LLMFrontend(llm(srv)).decompose(AMBIGUOUS, scene1, state1, team12)
    assert len(srv.requests) == 1  # no repair round: a clarification is an answer
    asked = info.value.clarification
    assert asked.question == "What should I put away, and where?" and len(asked.readings) == 2
    schema = srv.requests[0]["response_format"]["json_schema"]["schema"]
    assert schema["required"] == ["subtasks", "clarification"]  # strict mode: every property required


def test_a_hook_settles_it_with_the_persons_choice(scene1: Scene, state1: WorldState,
                                                   team12: Sequence[RobotProfile]) -> None:
    seen: list[Clarification] = []

    def choose(c: Clarification) -> str:
        seen.append(c)
        return c.readings[0]
    with ScriptedServer("openai", [Reply.answer(ASK), Reply.answer(APPLE_IN_FRIDGE)]) as srv:
        client = llm(srv)
        spec = LLMFrontend(client).decompose(AMBIGUOUS, scene1, state1, team12, clarify=choose)
    assert str(spec.goal()) == "inside(Apple, Fridge)" and len(seen) == 1
    second = srv.requests[1]["messages"][-1]["content"]
    assert "the user answered: Put the apple in the fridge." in second
    assert {k: v.calls for k, v in client.usage.by_stage().items()} == {"pfg": 1, "pfg.clarified": 1}


def test_an_empty_answer_without_a_clarification_is_fed_back_with_the_rule(
        scene1: Scene, state1: WorldState, team12: Sequence[RobotProfile]) -> None:
    empty = {"subtasks": [], "clarification": None}
    with ScriptedServer("openai", [Reply.answer(empty), Reply.answer(APPLE_IN_FRIDGE)]) as srv:
        spec = LLMFrontend(llm(srv)).decompose("Put the apple in the fridge.", scene1, state1, team12)
    assert str(spec.goal()) == "inside(Apple, Fridge)"
    assert "a clarification with the subtasks empty" in srv.requests[1]["messages"][-1]["content"]


def test_a_clarification_with_one_reading_breaks_the_schema_limit(scene1: Scene, state1: WorldState,
                                                                  team12: Sequence[RobotProfile]) -> None:
    one = {"subtasks": [], "clarification": {"question": "Which?", "readings": ["the apple"]}}
    with ScriptedServer("openai", [Reply.answer(one)] * 3) as srv, pytest.raises(LLMMalformedOutput) as info:
        LLMFrontend(llm(srv)).decompose(AMBIGUOUS, scene1, state1, team12)
    assert "readings" in str(info.value)


def test_the_terminal_hook_reads_a_number_and_needs_a_terminal() -> None:
    asked = Clarification(question="Which one?", readings=("the apple", "the mug"))

    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True
    out = io.StringIO()
    assert ask_terminal(asked, Tty("2\n"), out) == "the mug"
    assert "  1. the apple\n  2. the mug" in out.getvalue()
    assert ask_terminal(asked, Tty("the red one\n"), io.StringIO()) == "the red one"
    assert ask_terminal(asked, io.StringIO("1\n"), io.StringIO()) is None  # no terminal: nobody to ask


@pytest.mark.parametrize("command", ["run", "plan"])
def test_json_output_carries_the_clarification(command: str) -> None:
    env = {**os.environ, "OPENAI_API_KEY": "sk-loopback-test-key"}
    with ScriptedServer("openai", [Reply.answer(ASK)]) as srv:
        proc = subprocess.run([EMBOTEAM, command, AMBIGUOUS, "--scene", "FloorPlan1", "--robots", "1,2",
                               "--frontend", "llm", "--llm", srv.spec("gpt-test"), "--json"],
                              capture_output=True, text=True, timeout=300, env=env)
    assert proc.returncode == 2, proc.stderr  # the instruction needs the user: bad input, not a failure
    result = json.loads(proc.stdout)
    assert result["success"] is False and "needs a clarification" in str(result["error"])
    assert result["clarification"] == {"question": "What should I put away, and where?",
                                       "readings": ["Put the apple in the fridge.", "Put the mug in the cabinet."],
                                       "source": "llm"}
    assert len(proc.stderr.strip().splitlines()) == 1  # one line on stderr, no traceback
