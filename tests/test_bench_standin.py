"""The perfect-model stand-in (emboteam.bench.standin): real HTTP on 127.0.0.1, the project's
own clients and front ends against it. It must answer decompositions with the ground
truth, "ok" to a right draft, the ground truth to a wrong one, in whatever schema the
request carries, and refuse what it cannot know."""

from __future__ import annotations

import json
import urllib.request
from collections.abc import Sequence

import pytest

from emboteam.bench.standin import (
    DISCLAIMER,
    KnownTask,
    PerfectModel,
    StandInError,
    StandInServer,
    fit,
    known_tasks,
)
from emboteam.hp.llm_stages import review_spec
from emboteam.llm import make_client
from emboteam.llm.errors import LLMServerError
from emboteam.pfg.hybrid import HybridFrontend
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.pfg.reading import Reading
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Condition, Goal
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

FRIDGE = "Put the apple and the tomato in the fridge."
TRUTH = Goal(conditions=(Condition.parse("inside(Apple, Fridge)"), Condition.parse("inside(Tomato, Fridge)")))
OTHER = "Turn off the light."
OTHER_TRUTH = Goal(conditions=(Condition.parse("switched_off(LightSwitch)"),))


def tasks() -> list[KnownTask]:
    return [KnownTask(FRIDGE, "FloorPlan1", TRUTH), KnownTask(OTHER, "FloorPlan1", OTHER_TRUTH)]


def spec_of(instruction: str, *conditions: str, unsure: bool = False) -> TaskSpec:
    return TaskSpec.model_validate({"instruction": instruction, "subtasks": [
        {"id": f"s{i}", "description": c, "goal": [Condition.parse(c)]} for i, c in enumerate(conditions, 1)]})


def goal_keys(spec: TaskSpec) -> set[str]:
    return {str(c) for c in spec.goal().conditions}


def test_decomposition_is_the_ground_truth(scene1: Scene, state1: WorldState,
                                           team12: Sequence[RobotProfile]) -> None:
    with StandInServer(tasks()) as server:
        client = make_client(server.spec)
        spec = LLMFrontend(client).decompose(FRIDGE, scene1, state1, team12)
        counts = dict(server.model.counts)
    assert goal_keys(spec) == {str(c) for c in TRUTH.conditions}
    assert client.usage.calls == 1 and counts == {"decompose": 1}


def test_hp_review_says_ok_to_the_truth_and_corrects_a_wrong_spec(scene1: Scene, state1: WorldState,
                                                                  team12: Sequence[RobotProfile]) -> None:
    right = spec_of(FRIDGE, "inside(Apple, Fridge)", "inside(Tomato, Fridge)")
    wrong = spec_of(FRIDGE, "inside(Apple, Fridge)")
    with StandInServer(tasks()) as server:
        client = make_client(server.spec)
        ok = review_spec(client, right, FRIDGE, scene1, state1, team12)
        fixed = review_spec(client, wrong, FRIDGE, scene1, state1, team12)
    assert not ok.changed and ok.spec == right
    assert fixed.changed and goal_keys(fixed.spec) == {str(c) for c in TRUTH.conditions}


def test_hybrid_review_ok_for_a_right_draft_correction_for_a_wrong_one(scene1: Scene, state1: WorldState,
                                                                       team12: Sequence[RobotProfile]) -> None:
    # the parser's draft missed the tomato and says so: the model may add it
    wrong = Reading(spec=spec_of(FRIDGE, "inside(Apple, Fridge)"), unsure=("inside(Apple, Fridge)",))
    right = Reading(spec=spec_of(OTHER, "switched_off(LightSwitch_1)"), unsure=("switched_off(LightSwitch_1)",))
    drafts = {FRIDGE: wrong, OTHER: right}
    with StandInServer(tasks()) as server:
        client = make_client(server.spec)
        hybrid = HybridFrontend(client, lambda text, *_: drafts[text], when="always")
        corrected = hybrid.decompose(FRIDGE, scene1, state1, team12)
        kept = hybrid.decompose(OTHER, scene1, state1, team12)
        counts = dict(server.model.counts)
    assert goal_keys(corrected) == {str(c) for c in TRUTH.conditions}
    assert kept == right.spec  # an id where the truth names the type is still right
    assert counts == {"review: corrected": 1, "review: ok": 1}


def test_accepted_wording_is_answered_ok() -> None:
    model = PerfectModel(tasks())
    other_wording = [Condition.parse("inside(Apple_1, Fridge_1)")]
    task = tasks()[0]
    assert not model.is_right(task, other_wording)
    model.accept(FRIDGE, "FloorPlan1", other_wording)
    assert model.is_right(task, other_wording)


def _post(server: StandInServer, body: dict[str, object]) -> tuple[int, dict[str, object]]:
    req = urllib.request.Request(server.base_url + "/chat/completions", data=json.dumps(body).encode(),
                                 headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=10) as resp:
            return resp.status, json.loads(resp.read())
    except urllib.error.HTTPError as exc:
        return exc.code, json.loads(exc.read())


def test_answer_follows_a_changed_schema() -> None:
    """A schema with a field the stand-in never heard of, and without one it would send."""
    condition = {"type": "object", "additionalProperties": False, "required": ["predicate", "subject", "receptacle"],
                 "properties": {"predicate": {"type": "string"}, "subject": {"type": "array"},
                                "receptacle": {"anyOf": [{"type": "string"}, {"type": "null"}]}}}
    schema = {"type": "object", "required": ["subtasks", "confidence"], "additionalProperties": False,
              "properties": {"confidence": {"type": "number"}, "subtasks": {"type": "array", "items": {
                  "type": "object", "required": ["id", "goal", "why"], "additionalProperties": False,
                  "properties": {"id": {"type": "string"}, "why": {"anyOf": [{"type": "string"}, {"type": "null"}]},
                                 "goal": {"type": "array", "items": condition}}}}}}
    body = {"model": "m", "messages": [{"role": "system", "content": "You decompose."},
                                       {"role": "user", "content": f"Task for FloorPlan1:\n  {OTHER}  "}],
            "response_format": {"type": "json_schema", "json_schema": {"name": "x", "schema": schema}}}
    with StandInServer(tasks()) as server:
        status, reply = _post(server, body)
    assert status == 200
    answer = json.loads(reply["choices"][0]["message"]["content"])  # type: ignore[index]
    assert answer == {"subtasks": [{"id": "s1", "goal": [{"predicate": "switched_off", "subject": ["LightSwitch"],
                                                          "receptacle": None}], "why": None}], "confidence": 0}


def test_unknown_task_and_non_pfg_requests_are_refused(scene1: Scene, state1: WorldState,
                                                      team12: Sequence[RobotProfile]) -> None:
    with StandInServer(tasks()) as server:
        client = make_client(server.spec)
        with pytest.raises(LLMServerError, match="no registered instruction"):
            LLMFrontend(client).decompose("Wash the mug.", scene1, state1, team12)
        status, reply = _post(server, {"messages": [{"role": "user", "content": FRIDGE}]})
    assert status == 400 and "PFG requests only" in json.dumps(reply)


def test_floor_plan_picks_among_tasks_with_the_same_text() -> None:
    one = KnownTask(OTHER, "FloorPlan1", OTHER_TRUTH)
    two = KnownTask(OTHER, "FloorPlan12", Goal(conditions=(Condition.parse("switched_off(DeskLamp)"),)))
    model = PerfectModel([one, two])
    body = {"messages": [{"role": "user", "content": f"{OTHER}\nScene FloorPlan12, objects"}]}
    assert model.find_task(body)[0] == two  # type: ignore[index]
    assert "share this instruction" in str(model.find_task({"messages": [{"role": "user", "content": OTHER}]}))


def test_loopback_only() -> None:
    with pytest.raises(StandInError, match="loopback"):
        StandInServer(tasks(), host="0.0.0.0")


def test_fit_drops_unknown_and_fills_required() -> None:
    schema = {"type": "object", "required": ["a", "b"], "properties": {
        "a": {"type": "string", "maxLength": 3}, "b": {"type": "string", "enum": ["x", "y"]}}}
    assert fit({"a": "abcdef", "c": 1}, schema) == {"a": "abc", "b": "x"}


def test_known_tasks_skip_tasks_without_a_goal() -> None:
    class T:
        instruction, floor_plan, ground_truth = "x", "FloorPlan1", None
    assert known_tasks([T()]) == [] and "never model quality" in DISCLAIMER
