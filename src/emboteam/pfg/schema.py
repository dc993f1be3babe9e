"""The JSON schema an LLM answers a decomposition in, built from the scene and the team,
and the conversion of an answer into a :class:`TaskSpec`.

The schema is the guard rail: object references are enums of the ids and types present
in the scene, receptacles an enum of the receptacles, robots an enum of the team,
predicates those of :class:`~emboteam.world.goals.Predicate`, subtask ids a fixed
``s1..sN``. Whatever the instruction says, a schema-valid answer can only talk about
this scene's objects and this team. The schema stays within OpenAI strict mode's rules
(every property required, ``additionalProperties: false``, nullable fields as an
``anyOf`` with ``null``) and carries length and item bounds that the llama.cpp grammar
enforces and that :mod:`emboteam.llm.structured` checks for every backend.

Conversion then applies what a schema cannot say (an id is one object, a count belongs
to a type, the goal must be achievable in this scene, dependencies form a DAG) and
raises :class:`~emboteam.llm.structured.Rejected` with a message for the model.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass
from typing import Any

from pydantic import ValidationError

from emboteam.llm.structured import Rejected
from emboteam.pfg.clarification import (
    MAX_READINGS,
    MIN_READINGS,
    QUESTION_MAX,
    READING_MAX,
    Clarification,
)
from emboteam.pfg.prompts import GOAL_PROPERTIES
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.catalogue import SAME_PLACE, load_catalogue
from emboteam.world.checker import GoalValidationError, validate_goal
from emboteam.world.goals import Condition, Goal, ObjectRef, Predicate
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene, is_object_id
from emboteam.world.state import WorldState

LIQUIDS = ("water", "coffee", "wine")

#: a description is one short sentence; a weak model copies the whole instruction into it,
#: and every character costs generation time on a local model
DESCRIPTION_MAX = 80
#: types one subject may list ("any of these": "the fruit" over Apple, Orange, ...)
SUBJECT_TYPES_MAX = 6
#: how many distinct objects one condition may ask for ("close all the cabinets": FloorPlan9 has 28)
COUNT_MAX = 30
#: subtasks one answer may hold: the longest right answer in the development corpus (one
#: condition a subtask, as the worked examples are written) has 15 (round 63's harder tasks
#: have 12-15; 12 refused nine of its forty right answers); the completion cap, not this
#: bound, stops a model that loops (:func:`emboteam.pfg.llm_frontend.answer_token_cap`)
MAX_SUBTASKS = 20


@dataclass(frozen=True)
class SceneVocabulary:
    """What an answer may name: the scene's objects and types, its receptacles, the team."""

    object_ids: tuple[str, ...]
    types: tuple[str, ...]
    receptacles: tuple[str, ...]
    robots: tuple[str, ...]

    @classmethod
    def build(cls, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
              listed: Collection[str] | None = None) -> SceneVocabulary:
        """``listed``: the types the prompt lists in detail; only their objects' ids are
        enumerated (an answer names the others by type, which are all enumerated), which
        keeps the schema, counted as input by the hosted APIs, small."""
        cat = load_catalogue()
        live = [o for o in state.objects.values() if not o.gone]
        ids = tuple(sorted(o.id for o in live if listed is None or o.type in listed))
        present = {o.type for o in live}
        # a goal may speak of what slicing produces (AppleSliced) before it exists
        products = {p[0] for t in present if (p := cat.slice_product(t)) is not None}
        # a subject type is one some goal can be about: a type with none of the goal
        # properties (Floor, Window, CounterTop) is only ever a receptacle
        subjects = {t for t in present | products if cat.type(t).properties & GOAL_PROPERTIES}
        types = tuple(sorted(subjects))
        rec_ids = sorted(o.id for o in live if o.has("receptacle") and (listed is None or o.type in listed))
        rec_types = {o.type for o in live if o.has("receptacle")}
        # "in the sink" may name the Sink or its basin (catalogue.SAME_PLACE)
        rec_types |= {alias for alias, group in SAME_PLACE.items() if alias in present and group & rec_types}
        return cls(object_ids=ids, types=types, receptacles=tuple(rec_ids + sorted(rec_types)),
                   robots=tuple(p.name for p in team))


def subtask_ids(max_subtasks: int) -> list[str]:
    return [f"s{i}" for i in range(1, max_subtasks + 1)]


def _nullable_enum(values: Sequence[str]) -> dict[str, Any]:
    return {"anyOf": [{"type": "string", "enum": list(values)}, {"type": "null"}]}


def condition_schema(vocab: SceneVocabulary) -> dict[str, Any]:
    return {
        "type": "object",
        "additionalProperties": False,
        "required": ["predicate", "subject", "receptacle", "count", "liquid"],
        "properties": {
            "predicate": {"type": "string", "enum": [p.value for p in Predicate]},
            "subject": {
                "type": "array", "minItems": 1, "maxItems": SUBJECT_TYPES_MAX,
                "description": f"one id, or 1-{SUBJECT_TYPES_MAX} types",
                "items": {"type": "string", "enum": [*vocab.object_ids, *vocab.types]},
            },
            "receptacle": _nullable_enum(vocab.receptacles),
            "count": {"type": "integer", "minimum": 1, "maximum": COUNT_MAX, "description": f"1-{COUNT_MAX}"},
            "liquid": _nullable_enum(LIQUIDS),
        },
    }


def clarification_schema() -> dict[str, Any]:
    """"I cannot tell": a question and the readings it chooses between (null otherwise)."""
    return {"anyOf": [{
        "type": "object",
        "additionalProperties": False,
        "required": ["question", "readings"],
        "properties": {
            "question": {"type": "string", "maxLength": QUESTION_MAX,
                         "description": f"at most {QUESTION_MAX} characters"},
            "readings": {"type": "array", "minItems": MIN_READINGS, "maxItems": MAX_READINGS,
                         "description": f"{MIN_READINGS}-{MAX_READINGS} end states, each at most {READING_MAX} "
                                        "characters",
                         "items": {"type": "string", "maxLength": READING_MAX}},
        },
    }, {"type": "null"}]}


def subtasks_schema(vocab: SceneVocabulary, *, max_subtasks: int = MAX_SUBTASKS, max_conditions: int = 6,
                    extra_ids: Sequence[str] = (), min_items: int = 1) -> dict[str, Any]:
    """The list of subtasks (shared by the decomposition and the review answers)."""
    ids = list(dict.fromkeys([*subtask_ids(max_subtasks), *extra_ids]))
    return {
        "type": "array", "minItems": min_items, "maxItems": max_subtasks,
        "description": f"1-{max_subtasks}" if min_items else f"at most {max_subtasks}",
        "items": {
            "type": "object",
            "additionalProperties": False,
            "required": ["id", "description", "robot", "goal", "depends_on", "final"],
            "properties": {
                "id": {"type": "string", "enum": ids},
                "description": {"type": "string", "maxLength": DESCRIPTION_MAX,
                                "description": f"at most {DESCRIPTION_MAX} characters"},
                "robot": _nullable_enum(vocab.robots),
                "goal": {"type": "array", "minItems": 1, "maxItems": max_conditions,
                         "description": f"1-{max_conditions} conditions", "items": condition_schema(vocab)},
                "depends_on": {"type": "array", "maxItems": max_subtasks,
                               "description": f"at most {max_subtasks}", "items": {"type": "string", "enum": ids}},
                "final": {"type": "boolean"},
            },
        },
    }


def taskspec_schema(vocab: SceneVocabulary, *, max_subtasks: int = MAX_SUBTASKS, max_conditions: int = 6,
                    extra_ids: Sequence[str] = (), clarify: bool = False) -> dict[str, Any]:
    """The answer schema of a decomposition over this scene and team. Subtask ids are
    ``s1..s<max_subtasks>`` plus ``extra_ids`` (those of a spec under review). With
    ``clarify`` the answer may instead be a clarification with no subtasks."""
    subtasks = subtasks_schema(vocab, max_subtasks=max_subtasks, max_conditions=max_conditions,
                               extra_ids=extra_ids, min_items=0 if clarify else 1)
    properties: dict[str, Any] = {"subtasks": subtasks}
    if clarify:
        subtasks["description"] = f"at most {max_subtasks}"
        properties["clarification"] = clarification_schema()
    return {"type": "object", "additionalProperties": False, "required": list(properties),
            "properties": properties}


def clarification_from_answer(answer: dict[str, Any]) -> Clarification | None:
    """The answer's clarification when it gives one instead of subtasks; Rejected for an
    answer with neither (an empty answer is not a reading)."""
    raw = answer.get("clarification")
    if answer["subtasks"]:
        return None
    if raw is None:
        raise Rejected("give the subtasks, or (only if the instruction has readings with different end "
                       "states that the scene does not settle) a clarification with the subtasks empty")
    try:
        return Clarification(question=str(raw["question"]).strip(),
                             readings=tuple(str(r).strip() for r in raw["readings"]))
    except ValidationError as exc:
        raise Rejected("clarification: " + "; ".join(str(e["msg"]) for e in exc.errors())) from None


def condition_from_answer(raw: dict[str, Any]) -> Condition:
    """One answer condition -> a :class:`Condition` (Rejected with the reason)."""
    subject_names: list[str] = list(raw["subject"])
    ids = [n for n in subject_names if is_object_id(n)]
    if ids and len(subject_names) > 1:
        raise Rejected(f"subject {subject_names}: give exactly one object id, or one or more types, not a mix")
    subject = ObjectRef(id=ids[0]) if ids else ObjectRef(types=tuple(dict.fromkeys(subject_names)))
    receptacle = None
    if raw["receptacle"] is not None:
        name = str(raw["receptacle"])
        receptacle = ObjectRef(id=name) if is_object_id(name) else ObjectRef(types=(name,))
    try:
        return Condition(predicate=Predicate(raw["predicate"]), subject=subject, receptacle=receptacle,
                         count=int(raw["count"]), liquid=raw["liquid"])
    except ValidationError as exc:
        reasons = "; ".join(str(e["msg"]).removeprefix("Value error, ") for e in exc.errors())
        raise Rejected(f"{raw['predicate']}({', '.join(subject_names)}"
                       f"{', ' + str(raw['receptacle']) if raw['receptacle'] else ''}): {reasons}") from None


def taskspec_from_answer(answer: dict[str, Any], instruction: str, scene: Scene) -> TaskSpec:
    """A schema-valid answer -> a validated :class:`TaskSpec`, or Rejected listing every
    problem (so one repair round can fix them all)."""
    problems: list[str] = []
    subtasks: list[Subtask] = []
    for raw in answer["subtasks"]:
        sid = raw["id"]
        conditions: list[Condition] = []
        for rc in raw["goal"]:
            try:
                conditions.append(condition_from_answer(rc))
            except Rejected as exc:
                problems.append(f"{sid}: {exc}")
        if len(conditions) != len(raw["goal"]):
            continue
        try:
            validate_goal(Goal(conditions=tuple(conditions)), scene)
        except GoalValidationError as exc:
            problems.append(f"{sid}: {exc}")
            continue
        subtasks.append(Subtask(id=sid, description=raw["description"], robot=raw["robot"],
                                goal=tuple(conditions), depends_on=tuple(dict.fromkeys(raw["depends_on"])),
                                final=bool(raw["final"])))
    if problems:
        raise Rejected("; ".join(problems))
    try:
        return TaskSpec(instruction=instruction, subtasks=tuple(subtasks))
    except ValidationError as exc:
        raise Rejected("; ".join(str(e["msg"]).removeprefix("Value error, ") for e in exc.errors())) from None


def condition_to_answer(cond: Condition) -> dict[str, Any]:
    subject = [cond.subject.id] if cond.subject.id is not None else list(cond.subject.types)
    receptacle = None
    if cond.receptacle is not None:
        receptacle = cond.receptacle.id if cond.receptacle.id is not None else cond.receptacle.types[0]
    return {"predicate": cond.predicate.value, "subject": subject, "receptacle": receptacle,
            "count": cond.count, "liquid": cond.liquid}


def taskspec_to_answer(spec: TaskSpec) -> dict[str, Any]:
    """The answer form of a spec: what few-shot examples show and repair rounds echo."""
    return {"subtasks": [
        {"id": s.id, "description": s.description, "robot": s.robot,
         "goal": [condition_to_answer(c) for c in s.goal], "depends_on": list(s.depends_on), "final": s.final}
        for s in spec.subtasks
    ]}
