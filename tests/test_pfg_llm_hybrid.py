"""The hybrid front end over a loopback OpenAI-compatible server: no call for a confident
reading, a review of a doubtful one ("ok" or a correction), the rule that a correction
keeps what the parser was sure of, the draft standing when a weak model never gives an
acceptable answer, and the LLM writing the spec when the parser fails."""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

import pytest

from emboteam.llm import LLMClient, RetryPolicy, make_client
from emboteam.pfg.hybrid import HybridFrontend, as_reading, review_schema
from emboteam.pfg.offline.errors import OfflineParseError
from emboteam.pfg.reading import Reading, ReadingNote
from emboteam.pfg.schema import SceneVocabulary, taskspec_from_answer, taskspec_schema
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState
from llm_servers import Reply, ScriptedServer, cond, subtask, taskspec_answer

FAST = RetryPolicy(max_attempts=1, base_delay=0.01, max_delay=0.02)
INSTRUCTION = "Put the apple in the fridge and turn off the light, then jiggle the blorp."
APPLE = cond("inside", "Apple_1", receptacle="Fridge_1")
LIGHT_OFF = cond("switched_off", "LightSwitch_1")
LIGHT_ON = cond("switched_on", "LightSwitch_1")
FRIDGE_CLOSED = cond("closed", "Fridge_1")


@pytest.fixture(autouse=True)
def _key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", "sk-test")


def llm(server: ScriptedServer) -> LLMClient:
    return make_client(server.spec(), timeout=5, retry=FAST)


def spec_of(scene: Scene, *subtasks: dict[str, Any]) -> TaskSpec:
    return taskspec_from_answer(taskspec_answer(*subtasks), INSTRUCTION, scene)


def fixed_parse(reading: Reading | Exception) -> Any:
    def parse(instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile]) -> Reading:
        if isinstance(reading, Exception):
            raise reading
        return reading
    return parse


def draft(scene: Scene, *, unsure: tuple[str, ...] = (), notes: tuple[ReadingNote, ...] = ()) -> Reading:
    spec = spec_of(scene, subtask("s1", APPLE, robot="robot1"), subtask("s2", LIGHT_OFF, robot="robot2"))
    return Reading(spec=spec, notes=notes, unsure=unsure)


UNREAD = (ReadingNote(span="jiggle the blorp", reason="unknown word 'blorp'"),)
# the review's own checks are tested with when="always": whether a reading is reviewed
# at all is the doubt detector's (tests/test_pfg_doubt.py)


def test_confident_reading_makes_no_call(scene1: Scene, state1: WorldState, team12: Sequence[RobotProfile]) -> None:
    reading = draft(scene1)
    with ScriptedServer("openai", []) as srv:
        client = llm(srv)
        got = HybridFrontend(client, fixed_parse(reading)).read(INSTRUCTION, scene1, state1, team12)
    assert got.spec == reading.spec and srv.requests == [] and client.usage.calls == 0


def test_always_asks_even_about_a_confident_reading(scene1: Scene, state1: WorldState,
                                                     team12: Sequence[RobotProfile]) -> None:
    reading = draft(scene1)
    with ScriptedServer("openai", [Reply.answer({"ok": True, "subtasks": []})]) as srv:
        got = HybridFrontend(llm(srv), fixed_parse(reading), when="always").read(INSTRUCTION, scene1, state1,
                                                                                 team12)
    assert got.spec == reading.spec and len(srv.requests) == 1


def test_doubtful_reading_is_sent_as_a_draft_with_its_notes(scene1: Scene, state1: WorldState,
                                                             team12: Sequence[RobotProfile]) -> None:
    reading = draft(scene1, notes=UNREAD, unsure=("switched_off(LightSwitch_1)",))
    with ScriptedServer("openai", [Reply.answer({"ok": True, "subtasks": []})]) as srv:
        client = llm(srv)
        got = HybridFrontend(client, fixed_parse(reading)).read(INSTRUCTION, scene1, state1, team12)
    assert got.spec == reading.spec and client.usage.calls == 1
    body = srv.requests[0]
    user = body["messages"][-1]["content"]
    assert '"subject":["Apple_1"]' in user                     # the draft, in the answer form
    assert "unread 'jiggle the blorp': unknown word 'blorp'" in user
    assert "unsure: switched_off(LightSwitch_1)" in user
    assert "Fridge (receptacle, openable): Fridge_1 [closed]" in user
    assert "Also here (not listed in detail):" in user         # the rest of the scene by name only
    assert "Toaster_1" not in user
    assert body["response_format"]["json_schema"]["schema"]["required"] == ["ok", "subtasks"]


def test_a_correction_may_fix_the_unsure_part(scene1: Scene, state1: WorldState,
                                              team12: Sequence[RobotProfile]) -> None:
    reading = draft(scene1, unsure=("switched_off(LightSwitch_1)",))
    fixed = {"ok": False, "subtasks": [subtask("s1", APPLE, robot="robot1"), subtask("s2", LIGHT_ON)]}
    with ScriptedServer("openai", [Reply.answer(fixed)]) as srv:
        got = HybridFrontend(llm(srv), fixed_parse(reading)).read(INSTRUCTION, scene1, state1, team12)
    assert str(got.spec.goal()) == "inside(Apple_1, Fridge_1) & switched_on(LightSwitch_1)"
    assert any(n.kind == "assumed" and "corrected" in n.reason for n in got.notes)


def test_dropping_or_contradicting_a_sure_condition_is_fed_back(scene1: Scene, state1: WorldState,
                                                                team12: Sequence[RobotProfile]) -> None:
    reading = draft(scene1, notes=UNREAD)   # nothing unsure: both conditions are sure
    dropped = {"ok": False, "subtasks": [subtask("s1", LIGHT_OFF)]}
    contradicted = {"ok": False, "subtasks": [subtask("s1", APPLE), subtask("s2", LIGHT_ON)]}
    added = {"ok": False, "subtasks": [subtask("s1", APPLE), subtask("s2", LIGHT_OFF), subtask("s3", FRIDGE_CLOSED)]}
    with ScriptedServer("openai", [Reply.answer(dropped), Reply.answer(contradicted), Reply.answer(added)]) as srv:
        got = HybridFrontend(llm(srv), fixed_parse(reading), when="always").read(INSTRUCTION, scene1, state1, team12)
    feedback = [r["messages"][-1]["content"] for r in srv.requests[1:]]
    assert "keep inside(Apple_1, Fridge_1)" in feedback[0]
    assert "switched_on(LightSwitch_1) contradicts switched_off(LightSwitch_1)" in feedback[1]
    assert "closed(Fridge_1)" in str(got.spec.goal())   # adding to a sure reading is allowed


def test_a_weak_model_never_replaces_the_draft_with_a_worse_one(scene1: Scene, state1: WorldState,
                                                                team12: Sequence[RobotProfile]) -> None:
    reading = draft(scene1, notes=UNREAD)
    worse = {"ok": False, "subtasks": [subtask("s1", LIGHT_ON)]}
    with ScriptedServer("openai", [Reply.answer(worse)] * 3) as srv:
        client = llm(srv)
        got = HybridFrontend(client, fixed_parse(reading), when="always").read(INSTRUCTION, scene1, state1, team12)
    assert got.spec == reading.spec
    assert client.usage.calls == 3                       # every call is still counted
    assert any("the offline reading stands" in n.reason for n in got.notes)


def test_an_added_condition_on_an_unmentioned_object_is_fed_back(scene1: Scene, state1: WorldState,
                                                                 team12: Sequence[RobotProfile]) -> None:
    reading = draft(scene1, notes=UNREAD)
    toaster = {"ok": False, "subtasks": [subtask("s1", APPLE), subtask("s2", LIGHT_OFF),
                                         subtask("s3", cond("switched_on", "Toaster_1"))]}
    with ScriptedServer("openai", [Reply.answer(toaster), Reply.answer({"ok": True, "subtasks": []})]) as srv:
        got = HybridFrontend(llm(srv), fixed_parse(reading), when="always").read(INSTRUCTION, scene1, state1, team12)
    assert "switched_on(Toaster_1) is about something the instruction does not mention" in \
        srv.requests[1]["messages"][-1]["content"]
    assert got.spec == reading.spec


def test_a_parser_error_lets_the_llm_write_the_spec_with_the_error_as_a_hint(
        scene1: Scene, state1: WorldState, team12: Sequence[RobotProfile]) -> None:
    answer = taskspec_answer(subtask("s1", APPLE, robot="robot1"))
    with ScriptedServer("openai", [Reply.answer(answer)]) as srv:
        front = HybridFrontend(llm(srv), fixed_parse(OfflineParseError("no verb in 'the apple, fridge-wards'")))
        got = front.read("The apple, fridge-wards!", scene1, state1, team12)
    assert str(got.spec.goal()) == "inside(Apple_1, Fridge_1)"
    assert "An offline parser could not read this instruction: no verb in 'the apple, fridge-wards'" in \
        srv.requests[0]["messages"][-1]["content"]


def test_review_schema_allows_ok_with_no_subtasks(scene1: Scene, state1: WorldState,
                                                  team12: Sequence[RobotProfile]) -> None:
    schema = review_schema(taskspec_schema(SceneVocabulary.build(scene1, state1, team12)))
    assert list(schema["properties"]) == ["ok", "subtasks"]
    assert schema["properties"]["subtasks"]["minItems"] == 0
    json.dumps(schema)


def test_as_reading_adapts_the_parsers_older_result(scene1: Scene) -> None:
    class Old:
        spec = spec_of(scene1, subtask("s1", APPLE))
        notes = ("skipped: 'tidy up' is too vague",)

    reading = as_reading(Old())
    assert reading.doubtful and reading.notes[0].span == "skipped: 'tidy up' is too vague"
