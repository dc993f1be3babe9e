"""Worked decomposition examples shown to the LLM before the task (few-shot prompting).

The examples are package data (``prompts/fewshot.json``), written for EmboTeam over
several floor plans. A task never sees an example of its own floor plan (that would leak
object ids and layout into the prompt and flatter the benchmark); among the rest,
examples of the same room type come first, then the others, in file order, so the
selection is deterministic.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from functools import cache
from importlib import resources
from typing import Any

from pydantic import BaseModel, ConfigDict

from emboteam.llm.messages import Message
from emboteam.pfg.prompts import GOAL_SKILLS, render, render_scene, render_team
from emboteam.world.catalogue import load_catalogue
from emboteam.world.robots import parse_team
from emboteam.world.scene import is_object_id, load_scene
from emboteam.world.state import WorldState


class FewShotExample(BaseModel):
    model_config = ConfigDict(frozen=True)

    floor_plan: str
    robots: str
    instruction: str
    answer: dict[str, Any]


@cache
def load_examples() -> tuple[FewShotExample, ...]:
    raw = json.loads(resources.files("emboteam.pfg.prompts").joinpath("fewshot.json").read_text(encoding="utf-8"))
    return tuple(FewShotExample.model_validate(e) for e in raw["examples"])


def select_examples(floor_plan: str, k: int, examples: Sequence[FewShotExample] | None = None) -> list[FewShotExample]:
    """Up to ``k`` examples not of ``floor_plan``: same room type first, then the others."""
    pool = [e for e in (examples if examples is not None else load_examples()) if e.floor_plan != floor_plan]
    room = load_scene(floor_plan).room
    same = [e for e in pool if load_scene(e.floor_plan).room == room]
    other = [e for e in pool if load_scene(e.floor_plan).room != room]
    return (same + other)[:max(0, k)]


def _mentioned(example: FewShotExample, state: WorldState) -> list[str]:
    """The object ids an example's answer is about (types expand to their instances and,
    for slice types, to the objects they are cut from): the scene excerpt it shows."""
    cat = load_catalogue()
    names: set[str] = set()
    for sub in example.answer["subtasks"]:
        for cond in sub["goal"]:
            names.update(cond["subject"])
            if cond["receptacle"] is not None:
                names.add(cond["receptacle"])
    ids = {n for n in names if is_object_id(n)}
    types = {n for n in names if not is_object_id(n)}
    types |= {src for t in types if (src := cat.source_type(t)) is not None}
    ids |= {o.id for o in state.objects.values() if o.type in types}
    return sorted(ids)


def example_subject_types(examples: Sequence[FewShotExample]) -> set[str]:
    """The object types the examples' goals are about (what a weak model copies)."""
    types: set[str] = set()
    for example in examples:
        state = WorldState.from_scene(load_scene(example.floor_plan), parse_team(example.robots))
        for sub in example.answer["subtasks"]:
            for cond in sub["goal"]:
                for name in cond["subject"]:
                    obj = state.objects.get(name)
                    types.add(obj.type if obj is not None else name)
    return types


def example_messages(example: FewShotExample) -> list[Message]:
    """The example as a user turn (instruction, scene excerpt, team) and the answer turn."""
    scene = load_scene(example.floor_plan)
    team = parse_team(example.robots)
    state = WorldState.from_scene(scene, team)
    user = render("pfg_user", instruction=example.instruction, floor_plan=f"{scene.floor_plan} (excerpt)",
                  scene=render_scene(state, _mentioned(example, state)), team=render_team(team, GOAL_SKILLS))
    answer = json.dumps(example.answer, separators=(",", ":"), ensure_ascii=False)
    return [Message(role="user", content=user), Message(role="assistant", content=answer)]
