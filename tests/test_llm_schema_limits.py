"""Every limit an answer is held to is stated where the model reads it, on every API.

OpenAI's strict structured outputs take a subset of JSON Schema, so the wire schema
(``openai_backend.strict_subset``) drops length, range and item-count bounds; Anthropic's
tool ``input_schema`` and llama.cpp's grammar take the full schema. Whatever is dropped
must still be said: each bounded node's ``description`` names its bound, and the PFG's
system prompt names the same numbers. Both schemas keep strict mode's shape (every
property required, no additional properties) and are valid JSON Schema.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import Any, cast

import jsonschema
import pytest

from emboteam.hp.llm_stages import orderings_schema, review_schema
from emboteam.llm import LLMClient
from emboteam.llm.openai_backend import _UNPORTABLE, strict_subset
from emboteam.pfg.action_lists import action_lists_schema
from emboteam.pfg.hybrid import review_schema as hybrid_review_schema
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.pfg.schema import COUNT_MAX, DESCRIPTION_MAX, MAX_SUBTASKS, SUBJECT_TYPES_MAX, SceneVocabulary
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.goals import Condition
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

BOUNDS = ("minLength", "maxLength", "minimum", "maximum", "minItems", "maxItems")


def nodes(schema: Any, path: str = "", said: str = "") -> Iterator[tuple[str, dict[str, Any], str]]:
    """Every schema node, with what its own description and an array's (for its items) say."""
    if isinstance(schema, dict):
        here = str(schema.get("description", ""))
        yield path, schema, f"{said} {here}"
        for k, v in schema.items():
            yield from nodes(v, f"{path}/{k}", here if k == "items" else "")
    elif isinstance(schema, list):
        for i, v in enumerate(schema):
            yield from nodes(v, f"{path}/{i}")


def all_schemas(scene: Scene, state: WorldState, team: Sequence[RobotProfile]) -> dict[str, dict[str, Any]]:
    frontend = LLMFrontend(cast(LLMClient, None))
    spec = TaskSpec(instruction="x", subtasks=(
        Subtask(id="s1", description="d", goal=(Condition.parse("inside(Apple, Fridge)"),)),
        Subtask(id="s2", description="d", goal=(Condition.parse("switched_off(LightSwitch)"),))))
    task = frontend.schema(scene, state, team)
    return {"pfg": task, "pfg.review": hybrid_review_schema(task),
            "hp.validate": review_schema(SceneVocabulary.build(scene, state, team), spec),
            "hp.merge": orderings_schema(spec), "action_lists": action_lists_schema(state, team)}


def test_every_bound_is_stated_in_its_description(scene1: Scene, state1: WorldState,
                                                  team12: Sequence[RobotProfile]) -> None:
    unstated = []
    for name, schema in all_schemas(scene1, state1, team12).items():
        for path, node, said in nodes(schema):
            for key in BOUNDS:
                value = node.get(key)
                if value is None or (key == "minItems" and value == 0):
                    continue
                if str(value) not in said:
                    unstated.append(f"{name}{path}: {key}={value}")
    assert unstated == []


def test_the_system_prompt_states_the_answer_limits() -> None:
    text = LLMFrontend(cast(LLMClient, None)).system_text()
    assert f"over {MAX_SUBTASKS} subtasks, 6 conditions" in text  # the defaults, as the schema holds them
    for number in (MAX_SUBTASKS, 6, SUBJECT_TYPES_MAX, COUNT_MAX, DESCRIPTION_MAX):
        assert str(number) in text
    assert "$" not in text  # every placeholder filled
    assert "null: the planner chooses and may combine members" in text  # what robot: null means
    assert "knife" in text and "clarification" in text


@pytest.mark.parametrize("name", ["pfg", "pfg.review", "hp.validate", "hp.merge", "action_lists"])
def test_wire_schemas_keep_strict_modes_shape(name: str, scene1: Scene, state1: WorldState,
                                              team12: Sequence[RobotProfile]) -> None:
    full = all_schemas(scene1, state1, team12)[name]
    wire = strict_subset(full)
    jsonschema.Draft202012Validator.check_schema(full)   # Anthropic's input_schema, llama.cpp's grammar
    jsonschema.Draft202012Validator.check_schema(wire)
    for path, node, _ in nodes(wire):
        assert not set(node) & _UNPORTABLE or path.endswith("/properties"), path
        if node.get("type") == "object":
            assert node["additionalProperties"] is False, path
            assert sorted(node["required"]) == sorted(node["properties"]), path
