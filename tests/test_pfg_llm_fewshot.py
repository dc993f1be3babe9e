"""The few-shot examples shipped as package data: each is a valid decomposition of its
scene for its team, they span room types, and a task never sees its own floor plan."""

from __future__ import annotations

import jsonschema
import pytest

from emboteam.pfg.fewshot import FewShotExample, example_messages, load_examples, select_examples
from emboteam.pfg.prompts import load_prompt
from emboteam.pfg.schema import SceneVocabulary, taskspec_from_answer, taskspec_schema, taskspec_to_answer
from emboteam.world.actions import Skill
from emboteam.world.goals import Predicate
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

#: the skill a robot needs for each predicate an example assigns it (a sanity check of the
#: examples' allocation, which teaches the model to allocate by skills)
NEEDS = {Predicate.inside: Skill.PutObject, Predicate.sliced: Skill.SliceObject,
         Predicate.switched_on: Skill.SwitchOn, Predicate.switched_off: Skill.SwitchOff,
         Predicate.filled: Skill.PutObject, Predicate.cold: Skill.PutObject}


@pytest.mark.parametrize("example", load_examples(), ids=lambda e: f"{e.floor_plan}:{e.instruction[:30]}")
def test_example_is_a_valid_decomposition_for_its_scene_and_team(example: FewShotExample) -> None:
    scene = load_scene(example.floor_plan)
    team = parse_team(example.robots)
    state = WorldState.from_scene(scene, team)
    jsonschema.validate(example.answer, taskspec_schema(SceneVocabulary.build(scene, state, team)))
    spec = taskspec_from_answer(example.answer, example.instruction, scene)  # validate_goal inside
    assert taskspec_to_answer(spec) == example.answer  # the answer form round-trips
    by_name = {p.name: p for p in team}
    for s in spec.subtasks:
        assert s.robot in by_name
        for c in s.goal:
            assert NEEDS[c.predicate] in by_name[s.robot].skills, (s.id, c, s.robot)


def test_examples_span_room_types_and_floor_plans() -> None:
    examples = load_examples()
    assert len({e.floor_plan for e in examples}) >= 5
    assert {load_scene(e.floor_plan).room for e in examples} == {"kitchen", "living_room", "bedroom", "bathroom"}
    assert any(not s["final"] for e in examples for s in e.answer["subtasks"])  # shows an intermediate step
    assert any(c["count"] > 1 for e in examples for s in e.answer["subtasks"] for c in s["goal"])


@pytest.mark.parametrize("floor_plan", ["FloorPlan3", "FloorPlan11", "FloorPlan212", "FloorPlan420", "FloorPlan6"])
def test_selection_never_uses_the_tasks_floor_plan_and_prefers_its_room(floor_plan: str) -> None:
    chosen = select_examples(floor_plan, 3)
    assert len(chosen) == 3
    assert all(e.floor_plan != floor_plan for e in chosen)
    room = load_scene(floor_plan).room
    same_room = [e for e in load_examples() if e.floor_plan != floor_plan and load_scene(e.floor_plan).room == room]
    assert chosen[:len(same_room)] == same_room[:3]
    assert select_examples(floor_plan, 0) == []


def test_example_prompt_shows_only_the_objects_it_is_about() -> None:
    example = next(e for e in load_examples() if e.floor_plan == "FloorPlan11" and "tomato" in e.instruction)
    user, answer = example_messages(example)
    assert user.role == "user" and answer.role == "assistant"
    assert "Tomato_1" in user.content and "Bowl_1" in user.content
    assert "Fridge_1" not in user.content  # an excerpt, not the whole kitchen
    assert "robot25: lifts up to 100 kg; skills: PickupObject, PutObject" in user.content


def test_system_prompt_documents_every_predicate() -> None:
    text = load_prompt("pfg_system")
    missing = [p.value for p in Predicate if f"{p.value}(" not in text]
    assert missing == []
