"""An answer cut at the token limit (a weak model looping over one subtask) is rejected,
and the feedback names both the limit and what the checks find in its complete part,
so the model hears "s2 repeats s1", not only "not JSON"."""

from __future__ import annotations

import json
from collections.abc import Sequence

import pytest

from emboteam.llm import LLMMalformedOutput, RetryPolicy, make_client
from emboteam.llm.truncated import complete_prefix
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState
from llm_servers import APPLE, FRIDGE, TOMATO, Reply, ScriptedServer, subtask, taskspec_answer

FAST = RetryPolicy(max_attempts=1, base_delay=0.01, max_delay=0.02)


@pytest.fixture(autouse=True)
def _key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", "sk-test")


def looping_answer(cut_at: int) -> str:
    """What Qwen2.5-Coder-0.5B wrote: the same subtask again until the cap cut it."""
    text = json.dumps(taskspec_answer(subtask("s1", APPLE), *(subtask(f"s{i}", TOMATO) for i in range(2, 9))))
    return text[:cut_at]


def test_the_complete_part_of_a_cut_answer_is_closed_after_its_last_whole_element() -> None:
    text = looping_answer(700)
    partial = complete_prefix(text)
    assert partial is not None
    ids = [s["id"] for s in partial["subtasks"]]
    assert ids and ids == [f"s{i}" for i in range(1, len(ids) + 1)]
    assert all(set(s) == {"id", "description", "robot", "goal", "depends_on", "final"} for s in partial["subtasks"])
    assert complete_prefix(json.dumps({"subtasks": []})) is None       # complete: not a cut answer
    assert complete_prefix('{"subtasks": [{"id": "s1", "description": "a } in a string", "rob') is None
    assert complete_prefix("no JSON here") is None


def test_a_looping_answer_cut_at_the_cap_is_fed_back_with_its_repetitions(
        scene1: Scene, state1: WorldState, team12: Sequence[RobotProfile]) -> None:
    good = taskspec_answer(subtask("s1", APPLE), subtask("s2", TOMATO))
    with ScriptedServer("openai", [Reply.answer(looping_answer(700), finish_reason="length"),
                                   Reply.answer(good)]) as srv:
        client = make_client(srv.spec(), timeout=5, retry=FAST)
        spec = LLMFrontend(client).decompose(FRIDGE, scene1, state1, team12)
    feedback = srv.requests[1]["messages"][-1]["content"]
    assert "cut off at the 488-token limit" in feedback
    assert "in the part before the cut: s3 repeats s2" in feedback
    assert str(spec.goal()) == "inside(Apple_1, Fridge_1) & inside(Tomato_1, Fridge_1)"


def test_a_cut_answer_is_never_accepted_even_when_its_complete_part_is_valid(
        scene1: Scene, state1: WorldState, team12: Sequence[RobotProfile]) -> None:
    cut = json.dumps(taskspec_answer(subtask("s1", APPLE), subtask("s2", TOMATO)))[:-3]
    with ScriptedServer("openai", default=Reply.answer(cut, finish_reason="length")) as srv:
        client = make_client(srv.spec(), timeout=5, retry=FAST)
        with pytest.raises(LLMMalformedOutput, match="cut off at the 488-token limit"):
            LLMFrontend(client, repair_rounds=1).decompose(FRIDGE, scene1, state1, team12)
    assert len(srv.requests) == 2
    assert "in the part before the cut" not in srv.requests[1]["messages"][-1]["content"]
