"""Worked decomposition examples shown to the LLM before the task (few-shot prompting).

The pool is package data: ``prompts/fewshot.json`` (written by hand over several floor
plans, set ``fewshot``) and ``prompts/fewshot_corpus.json`` (the development tasks with
their ground-truth goals in the answer form, built by ``benchmarks/build_fewshot_corpus.py``
from ``tests/data``' development rounds, the offline development sets and MACE-THOR).

:func:`select_examples` picks, for an instruction, the examples whose instructions are
most similar to it (TF-IDF cosine over words, :mod:`emboteam.pfg.similarity`), never one
of the task's own floor plan or its own set (that would leak object ids, layout or the
answer itself into the prompt and flatter the benchmark) nor one with the same wording.
Ties keep the pool's order, so the selection is deterministic. Without an instruction,
examples of the same room type come first, then the others, in file order.
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
from emboteam.pfg.similarity import TfIdfIndex
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
    #: the set the example comes from (a task never sees an example of its own set)
    set: str = "fewshot"


def _load(name: str) -> tuple[FewShotExample, ...]:
    raw = json.loads(resources.files("emboteam.pfg.prompts").joinpath(name).read_text(encoding="utf-8"))
    return tuple(FewShotExample.model_validate(e) for e in raw["examples"])


@cache
def load_examples() -> tuple[FewShotExample, ...]:
    """The hand-written examples (``prompts/fewshot.json``)."""
    return _load("fewshot.json")


@cache
def load_pool() -> tuple[FewShotExample, ...]:
    """Every example a task may be shown: the hand-written ones, then the development corpus."""
    return load_examples() + _load("fewshot_corpus.json")


@cache
def _pool_index() -> TfIdfIndex:
    return TfIdfIndex([e.instruction for e in load_pool()])


def _same_words(a: str, b: str) -> bool:
    return " ".join(a.lower().split()) == " ".join(b.lower().split())


def select_examples(floor_plan: str, k: int, examples: Sequence[FewShotExample] | None = None, *,
                    instruction: str | None = None, avoid_set: str = "") -> list[FewShotExample]:
    """Up to ``k`` examples, never of ``floor_plan``, of the set ``avoid_set``, or with the
    same wording as ``instruction``. With an instruction: the most similar first (from
    the whole pool unless ``examples`` is given). Without: same room type first, then
    the others (the hand-written examples)."""
    if instruction is not None:
        pool = tuple(examples) if examples is not None else load_pool()
        index = _pool_index() if examples is None else TfIdfIndex([e.instruction for e in pool])
        scores = index.scores(instruction)
        order = sorted(range(len(pool)), key=lambda i: -scores[i])
        chosen = [pool[i] for i in order
                  if pool[i].floor_plan != floor_plan and (not avoid_set or pool[i].set != avoid_set)
                  and not _same_words(pool[i].instruction, instruction)]
        return chosen[:max(0, k)]
    rest = [e for e in (examples if examples is not None else load_examples()) if e.floor_plan != floor_plan]
    room = load_scene(floor_plan).room
    same = [e for e in rest if load_scene(e.floor_plan).room == room]
    other = [e for e in rest if load_scene(e.floor_plan).room != room]
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


def example_messages(example: FewShotExample, *, clarify: bool = False) -> list[Message]:
    """The example as a user turn (instruction, scene excerpt, team) and the answer turn
    (with ``"clarification": null`` when the schema has that field)."""
    scene = load_scene(example.floor_plan)
    team = parse_team(example.robots)
    state = WorldState.from_scene(scene, team)
    user = render("pfg_user", instruction=example.instruction, floor_plan=f"{scene.floor_plan} (excerpt)",
                  scene=render_scene(state, _mentioned(example, state)), team=render_team(team, GOAL_SKILLS))
    shown = {**example.answer, "clarification": None} if clarify else example.answer
    answer = json.dumps(shown, separators=(",", ":"), ensure_ascii=False)
    return [Message(role="user", content=user), Message(role="assistant", content=answer)]
