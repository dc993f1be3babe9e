"""LLM-written per-robot action lists (No-PFG&HP ablation, SMART-LLM baseline)."""

from __future__ import annotations

from typing import Any

import pytest

from emboteam.llm import LLMMalformedOutput, RetryPolicy, make_client
from emboteam.pfg.action_lists import LLMActionListFrontend, action_lists_schema
from emboteam.world.actions import Action, Skill
from emboteam.world.robots import parse_team
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState
from llm_servers import Reply, ScriptedServer

FAST = RetryPolicy(max_attempts=2, base_delay=0.01, max_delay=0.02)
TEAM = parse_team("1,25")


def act(skill: str, target: str, receptacle: str | None = None) -> dict[str, Any]:
    return {"skill": skill, "target": target, "receptacle": receptacle}


GOOD = {
    "robot1": [act("GoToObject", "Fridge_1"), act("OpenObject", "Fridge_1")],
    "robot25": [act("GoToObject", "Apple_1"), act("PickupObject", "Apple_1"), act("GoToObject", "Fridge_1"),
                act("PutObject", "Apple_1", "Fridge_1")],
}


@pytest.fixture(autouse=True)
def _key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", "sk-test")


@pytest.fixture
def state(scene1: Scene) -> WorldState:
    return WorldState.from_scene(scene1, TEAM)


def test_generate_returns_typed_actions_per_robot(scene1: Scene, state: WorldState) -> None:
    with ScriptedServer("openai", [Reply.answer(GOOD)]) as srv:
        client = make_client(srv.spec(), retry=FAST)
        plans = LLMActionListFrontend(client).generate("Put the apple in the fridge.", scene1, state, TEAM)
    assert plans["robot25"][-1] == Action(skill=Skill.PutObject, target="Apple_1", receptacle="Fridge_1")
    assert [str(a) for a in plans["robot1"]] == ["GoToObject(Fridge_1)", "OpenObject(Fridge_1)"]
    assert client.usage.by_stage()["action_lists"].calls == 1
    assert "<<<INSTRUCTION\nPut the apple in the fridge.\nINSTRUCTION>>>" in srv.requests[0]["messages"][-1]["content"]


def test_schema_limits_each_robot_to_its_own_skills_and_the_scenes_objects(state: WorldState) -> None:
    schema = action_lists_schema(state, TEAM)
    assert schema["required"] == ["robot1", "robot25"]
    item = schema["properties"]["robot25"]["items"]["properties"]
    assert item["skill"]["enum"] == ["GoToObject", "PickupObject", "PutObject"]
    targets = set(item["target"]["enum"])
    assert {"Apple_1", "Apple_1_Slice_1", "Apple_1_Slice_3", "Fridge_1"} <= targets
    assert "Apple_1_Slice_4" not in targets and "Toilet_1" not in targets
    assert "Apple_1" not in item["receptacle"]["anyOf"][0]["enum"]


def test_skill_a_robot_lacks_and_missing_receptacle_are_fed_back(scene1: Scene, state: WorldState) -> None:
    lacks_skill = {"robot1": [], "robot25": [act("OpenObject", "Fridge_1")]}
    no_receptacle = {"robot1": [], "robot25": [act("PutObject", "Apple_1")]}
    with ScriptedServer("openai", [Reply.answer(lacks_skill), Reply.answer(no_receptacle),
                                   Reply.answer(GOOD)]) as srv:
        plans = LLMActionListFrontend(make_client(srv.spec(), retry=FAST)).generate(
            "Put the apple in the fridge.", scene1, state, TEAM)
    assert len(plans["robot25"]) == 4
    assert "robot25/0/skill: 'OpenObject' is not an allowed value" in srv.requests[1]["messages"][-1]["content"]
    assert "PutObject(Apple_1) needs a receptacle" in srv.requests[2]["messages"][-1]["content"]


def test_all_empty_lists_are_rejected(scene1: Scene, state: WorldState) -> None:
    with (ScriptedServer("openai", default=Reply.answer({"robot1": [], "robot25": []})) as srv,
          pytest.raises(LLMMalformedOutput, match="every robot's list is empty")):
        LLMActionListFrontend(make_client(srv.spec(), retry=FAST), repair_rounds=1).generate(
            "Put the apple in the fridge.", scene1, state, TEAM)
    assert len(srv.requests) == 2
