"""The per-run budget of calls and tokens, and the per-stage usage ledger."""

from __future__ import annotations

from collections.abc import Sequence

import pytest

from emboteam.llm import Budget, LLMBudgetExceeded, LLMRequest, Message, RetryPolicy, make_client
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState
from llm_servers import Reply, ScriptedServer, cond, subtask, taskspec_answer

FAST = RetryPolicy(max_attempts=2, base_delay=0.01, max_delay=0.02)


def req(stage: str) -> LLMRequest:
    return LLMRequest(stage=stage, messages=(Message(role="user", content="hi"),))


@pytest.fixture(autouse=True)
def _key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", "sk-test")


def test_call_budget_stops_before_sending() -> None:
    with ScriptedServer("openai", default=Reply.answer("ok")) as srv:
        client = make_client(srv.spec(), retry=FAST, budget=Budget(max_calls=2))
        client.complete(req("pfg"))
        client.complete(req("hp.validate"))
        with pytest.raises(LLMBudgetExceeded, match="2 of 2 calls") as info:
            client.complete(req("hp.merge"))
    assert info.value.stage == "hp.merge"
    assert len(srv.requests) == 2  # the third call never left the process


def test_token_budget_is_enforced_on_the_call_that_exceeds_it() -> None:
    with ScriptedServer("openai", default=Reply.answer("ok", input_tokens=60, output_tokens=10)) as srv:
        client = make_client(srv.spec(), retry=FAST, budget=Budget(max_tokens=100))
        client.complete(req("pfg"))  # 70 tokens
        with pytest.raises(LLMBudgetExceeded, match="140 of 100 tokens"):
            client.complete(req("pfg"))
        with pytest.raises(LLMBudgetExceeded, match="spent"):
            client.complete(req("pfg"))
    assert len(srv.requests) == 2
    assert client.usage.tokens == 140  # what was spent stays on the ledger


def test_usage_ledger_counts_calls_attempts_and_tokens_per_stage() -> None:
    script = [Reply.answer("a", input_tokens=100, output_tokens=20), Reply.error(500),
              Reply.answer("b", input_tokens=50, output_tokens=5)]
    with ScriptedServer("openai", script) as srv:
        client = make_client(srv.spec(), retry=FAST)
        client.complete(req("pfg"))
        client.complete(req("hp.validate"))
    stages = client.usage.by_stage()
    assert (stages["pfg"].calls, stages["pfg"].attempts, stages["pfg"].tokens) == (1, 1, 120)
    assert (stages["hp.validate"].calls, stages["hp.validate"].attempts) == (1, 2)
    assert client.usage.to_dict()["calls"] == 2 and client.usage.to_dict()["tokens"] == 175


def test_scoped_clients_count_per_task_and_share_the_run_budget() -> None:
    with ScriptedServer("openai", default=Reply.answer("ok", input_tokens=1, output_tokens=1)) as srv:
        run = make_client(srv.spec(), retry=FAST, budget=Budget(max_calls=3))
        task_a, task_b = run.scoped(), run.scoped(Budget(max_calls=1))
        task_a.complete(req("pfg"))
        task_a.complete(req("hp.validate"))
        task_b.complete(req("pfg"))
        with pytest.raises(LLMBudgetExceeded):  # task_b's own budget
            task_b.complete(req("hp.validate"))
        with pytest.raises(LLMBudgetExceeded):  # the run's budget, spent by both tasks
            task_a.complete(req("pfg"))
    assert (task_a.usage.calls, task_b.usage.calls, run.usage.calls) == (2, 1, 3)


def test_budget_bounds_a_model_that_never_answers_validly(scene1: Scene, state1: WorldState,
                                                          team12: Sequence[RobotProfile]) -> None:
    """Garbage forever plus many repair rounds still ends at the budget, typed."""
    with ScriptedServer("openai", default=Reply.answer("garbage")) as srv:
        client = make_client(srv.spec(), retry=FAST, budget=Budget(max_calls=3))
        with pytest.raises(LLMBudgetExceeded):
            LLMFrontend(client, repair_rounds=50).decompose("Put the apple in the fridge.", scene1, state1, team12)
    assert len(srv.requests) == 3


def test_happy_path_of_pfg_is_one_call_with_tokens_recorded(scene1: Scene, state1: WorldState,
                                                            team12: Sequence[RobotProfile]) -> None:
    answer = taskspec_answer(subtask("s1", cond("inside", "Apple_1", receptacle="Fridge_1")))
    with ScriptedServer("openai", [Reply.answer(answer, input_tokens=1500, output_tokens=80)]) as srv:
        client = make_client(srv.spec(), retry=FAST)
        LLMFrontend(client).decompose("Put the apple in the fridge.", scene1, state1, team12)
    assert client.usage.to_dict() == {
        "calls": 1, "input_tokens": 1500, "output_tokens": 80, "tokens": 1580,
        "stages": {"pfg": {"calls": 1, "attempts": 1, "input_tokens": 1500, "output_tokens": 80}}}
