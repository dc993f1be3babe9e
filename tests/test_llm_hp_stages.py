"""The hybrid planner's LLM stages: the semantic review of a TaskSpec and the proposed
orderings, checked by apply_orderings (cycles, unknown ids, self-loops rejected with a
reason). Also the call budget of the paper's pipeline: PFG 1 + review 1 = 2 calls."""

from __future__ import annotations

from collections.abc import Sequence

import pytest

from emboteam.hp.llm_stages import (
    apply_orderings,
    apply_orderings_report,
    propose_orderings,
    review_spec,
    review_token_cap,
)
from emboteam.llm import LLMRefusal, RetryPolicy, make_client
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Condition
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState
from llm_servers import Reply, ScriptedServer, cond, subtask, taskspec_answer

FAST = RetryPolicy(max_attempts=2, base_delay=0.01, max_delay=0.02)
INSTRUCTION = "Slice the tomato and put a slice on the plate, and turn off the light."
SPEC_ANSWER = taskspec_answer(
    subtask("s1", cond("sliced", "Tomato_1"), robot="robot1"),
    subtask("s2", cond("inside", "TomatoSliced", receptacle="Plate_1"), robot="robot2"),
    subtask("s3", cond("switched_off", "LightSwitch_1"), robot="robot2"),
)


@pytest.fixture(autouse=True)
def _key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", "sk-test")


def spec3() -> TaskSpec:
    return TaskSpec.model_validate({"instruction": INSTRUCTION, "subtasks": [
        {"id": "s1", "description": "slice", "robot": "robot1", "goal": [Condition.parse("sliced(Tomato_1)")]},
        {"id": "s2", "description": "plate", "robot": "robot2",
         "goal": [Condition.parse("inside(TomatoSliced, Plate_1)")]},
        {"id": "s3", "description": "light", "robot": "robot2", "goal": [Condition.parse("off(LightSwitch_1)")]},
    ]})


def test_pfg_plus_review_is_two_calls_on_the_happy_path(scene1: Scene, state1: WorldState,
                                                        team12: Sequence[RobotProfile]) -> None:
    with ScriptedServer("openai", [Reply.answer(SPEC_ANSWER),
                                   Reply.answer({"verdict": "ok", "reason": "matches", "subtasks": []})]) as srv:
        client = make_client(srv.spec(), retry=FAST)
        spec = LLMFrontend(client).decompose(INSTRUCTION, scene1, state1, team12)
        review = review_spec(client, spec, INSTRUCTION, scene1, state1, team12)
    assert review.spec == spec and not review.changed and review.reason == "matches"
    assert client.usage.calls == 2
    assert {k: v.calls for k, v in client.usage.by_stage().items()} == {"pfg": 1, "hp.validate": 1}
    review_prompt = srv.requests[1]["messages"][-1]["content"]
    assert '"id":"s2"' in review_prompt and "TomatoSliced" in review_prompt
    # only what the instruction and the spec touch is listed with ids; the answer is capped
    assert "Tomato_1" in review_prompt and "Toaster_1" not in review_prompt
    assert srv.requests[1]["max_tokens"] == review_token_cap(spec) < 2048


def test_review_correction_replaces_the_spec(scene1: Scene, state1: WorldState,
                                             team12: Sequence[RobotProfile]) -> None:
    corrected = [*SPEC_ANSWER["subtasks"][:1], subtask("s2", cond("inside", "TomatoSliced", receptacle="Plate_1"), robot="robot2", depends_on=("s1",)), SPEC_ANSWER["subtasks"][2]]
    with ScriptedServer("openai", [Reply.answer({"verdict": "corrected", "reason": "slice before plating",
                                                 "subtasks": corrected})]) as srv:
        review = review_spec(make_client(srv.spec(), retry=FAST), spec3(), INSTRUCTION, scene1, state1, team12)
    assert review.changed and review.reason == "slice before plating"
    assert review.spec.subtask("s2").depends_on == ("s1",)
    assert review.spec.instruction == INSTRUCTION


def test_invalid_correction_is_dropped_with_the_reason_recorded(scene1: Scene, state1: WorldState,
                                                                team12: Sequence[RobotProfile]) -> None:
    empty = {"verdict": "corrected", "reason": "?", "subtasks": []}
    cyclic = {"verdict": "corrected", "reason": "?", "subtasks": [
        subtask("s1", cond("sliced", "Tomato_1"), depends_on=("s2",)),
        subtask("s2", cond("sliced", "Apple"), depends_on=("s1",))]}
    with ScriptedServer("openai", [Reply.answer(empty), Reply.answer(cyclic)]) as srv:
        review = review_spec(make_client(srv.spec(), retry=FAST), spec3(), INSTRUCTION, scene1, state1, team12)
    assert review.spec == spec3() and not review.changed
    assert review.rejected is not None and "cycle" in review.rejected
    assert "complete corrected list" in srv.requests[1]["messages"][-1]["content"]


def test_review_failures_other_than_bad_output_propagate(scene1: Scene, state1: WorldState,
                                                         team12: Sequence[RobotProfile]) -> None:
    with ScriptedServer("openai", [Reply.refuse()]) as srv, pytest.raises(LLMRefusal):
        review_spec(make_client(srv.spec(), retry=FAST), spec3(), INSTRUCTION, scene1, state1, team12)


def test_propose_orderings_returns_schema_valid_pairs() -> None:
    answer = {"orderings": [{"before": "s1", "after": "s2", "reason": "the slice exists after slicing"}]}
    with ScriptedServer("openai", [Reply.answer({"orderings": [{"before": "s9", "after": "s2", "reason": "x"}]}),
                                   Reply.answer(answer)]) as srv:
        client = make_client(srv.spec(), retry=FAST)
        proposed = propose_orderings(client, spec3(), INSTRUCTION, "s1 robot1: GoToObject(Knife_1) ...")
    assert proposed == [("s1", "s2", "the slice exists after slicing")]
    assert "'s9' is not an allowed value" in srv.requests[1]["messages"][-1]["content"]
    assert "GoToObject(Knife_1)" in srv.requests[0]["messages"][-1]["content"]
    assert client.usage.by_stage()["hp.merge"].calls == 1


def test_apply_orderings_adds_edges_and_rejects_bad_ones_with_reasons() -> None:
    report = apply_orderings_report(spec3(), [
        ("s1", "s2", "slice first"),
        ("s2", "s1", "backwards"),          # closes a cycle with the edge just added
        ("s3", "s3", "self"),
        ("s1", "s7", "unknown"),
        ("s1", "s2", "again"),
        ("s2", "s3", "plate before light"),
        ("s3", "s1", "transitive cycle"),   # s3 -> s1 -> s2 -> s3
    ])
    assert [(o.before, o.after) for o in report.accepted] == [("s1", "s2"), ("s2", "s3")]
    whys = {(r.ordering.before, r.ordering.after, r.ordering.reason): r.why for r in report.rejected}
    assert whys[("s2", "s1", "backwards")].startswith("cycle")
    assert whys[("s3", "s3", "self")] == "a subtask cannot come after itself"
    assert whys[("s1", "s7", "unknown")] == "unknown subtask s7"
    assert whys[("s1", "s2", "again")] == "already ordered"
    assert whys[("s3", "s1", "transitive cycle")].startswith("cycle")
    assert report.spec.subtask("s2").depends_on == ("s1",)
    assert report.spec.subtask("s3").depends_on == ("s2",)
    assert apply_orderings(spec3(), [("s1", "s2", "r")]).subtask("s2").depends_on == ("s1",)
