"""The hybrid planner's LLM stages (the paper's mode): a semantic review of the TaskSpec
against the instruction, and an LLM proposal of orderings between subtasks.

Both are schema-constrained and advisory. The review returns a corrected TaskSpec or
"ok"; a correction that stays invalid after the repair rounds is dropped (the original
spec is kept and the reason recorded) because the review refines a spec that already
passed validation. Proposed orderings are checked by :func:`apply_orderings`, which adds
them as ``depends_on`` edges and rejects, with a recorded reason, any that names an
unknown subtask, orders a subtask after itself or would close a cycle. The formal merge
(the planner's) stays the default and checks whatever the LLM proposes.

Call budget: the review is one call on the happy path (PFG 1 + review 1 = 2 per task);
the ordering proposal is made only in the paper's mode or on request.
"""

from __future__ import annotations

import json
import logging
from collections.abc import Iterable, Sequence
from typing import Any, NamedTuple

from pydantic import BaseModel, ConfigDict

from emboteam.llm.client import LLMClient
from emboteam.llm.errors import LLMMalformedOutput
from emboteam.llm.messages import LLMRequest, Message
from emboteam.llm.structured import Rejected, ask_structured
from emboteam.pfg.answer_checks import copied_problems, repetition_problems
from emboteam.pfg.fewshot import example_subject_types
from emboteam.pfg.focus import focus_types, spec_types
from emboteam.pfg.llm_frontend import LLMFrontend, answer_token_cap, checked_types, quote_instruction
from emboteam.pfg.prompts import GOAL_SKILLS, load_prompt, render, render_scene, render_team
from emboteam.pfg.schema import (
    MAX_SUBTASKS,
    SceneVocabulary,
    taskspec_from_answer,
    taskspec_schema,
    taskspec_to_answer,
)
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

log = logging.getLogger(__name__)

REVIEW_STAGE = "hp.validate"
MERGE_STAGE = "hp.merge"
REASON_MAX = 300


def _subtasks_json(spec: TaskSpec) -> str:
    """One JSON subtask per line: compact for the prompt, and the form a correction uses."""
    return "\n".join(json.dumps(s, separators=(",", ":"), ensure_ascii=False)
                     for s in taskspec_to_answer(spec)["subtasks"])


# ---- semantic review --------------------------------------------------------------------
class SpecReview(BaseModel):
    """The review's outcome: the spec to plan, whether the LLM changed it, and why."""

    model_config = ConfigDict(frozen=True)

    spec: TaskSpec
    changed: bool
    reason: str = ""
    rejected: str | None = None


def review_schema(vocab: SceneVocabulary, spec: TaskSpec, *, max_subtasks: int = MAX_SUBTASKS) -> dict[str, Any]:
    subtasks = taskspec_schema(vocab, max_subtasks=max_subtasks,
                               extra_ids=[s.id for s in spec.subtasks])["properties"]["subtasks"]
    return {
        "type": "object",
        "additionalProperties": False,
        "required": ["verdict", "reason", "subtasks"],
        "properties": {
            "verdict": {"type": "string", "enum": ["ok", "corrected"]},
            "reason": {"type": "string", "maxLength": REASON_MAX,
                       "description": f"what was changed and why, at most {REASON_MAX} characters"},
            "subtasks": {**subtasks, "minItems": 0,
                         "description": f"the complete corrected subtasks, at most {max_subtasks}; empty when "
                                        "the verdict is ok"},
        },
    }


#: completion tokens of the review's verdict and reason (300 characters, about 80 tokens)
REVIEW_FRAME_TOKENS = 100


def review_token_cap(spec: TaskSpec) -> int:
    """Completion tokens a review needs: its verdict and reason, and at most the spec's
    subtasks once more with one to spare (a corrected list). A looping model is cut off
    here, not at the schema's limit (see :func:`emboteam.pfg.llm_frontend.answer_token_cap`)."""
    return REVIEW_FRAME_TOKENS + answer_token_cap(len(spec.subtasks) + 1)


def review_spec(client: LLMClient, spec: TaskSpec, instruction: str, scene: Scene, state: WorldState,
                team: Sequence[RobotProfile], *, repair_rounds: int = 1, max_tokens: int | None = None,
                seed: int = 0, avoid_set: str = "") -> SpecReview:
    """Ask the LLM whether ``spec`` does what ``instruction`` says; one call when it does.
    The scene lists in full only the types the instruction and the spec touch (and what
    the instruction implies). A correction is held to the decomposition's own checks
    (repeated subtasks, conditions copied from the PFG's worked example), so the review
    never puts back what those checks rejected, nor rejects what they accept."""
    detail = focus_types(instruction, state, spec)
    vocab = SceneVocabulary.build(scene, state, team, detail)
    pfg = LLMFrontend(client, avoid_set=avoid_set)
    allowed = checked_types(pfg, instruction, scene, state, team, spec)
    example_types = example_subject_types(pfg.examples(scene, instruction))
    request = LLMRequest(
        stage=REVIEW_STAGE,
        messages=(Message(role="system", content=load_prompt("hp_validate_system").strip()),
                  Message(role="user", content=render(
                      "hp_validate_user", instruction=quote_instruction(instruction), floor_plan=scene.floor_plan,
                      scene=render_scene(state, detail=detail), team=render_team(team, GOAL_SKILLS),
                      subtasks=_subtasks_json(spec)))),
        json_schema=review_schema(vocab, spec), schema_name="review",
        max_tokens=max_tokens if max_tokens is not None else review_token_cap(spec), seed=seed)

    def convert(answer: dict[str, Any]) -> SpecReview:
        reason = str(answer["reason"]).strip()
        if answer["verdict"] == "ok":
            return SpecReview(spec=spec, changed=False, reason=reason)
        if not answer["subtasks"]:
            raise Rejected("verdict 'corrected' needs the complete corrected list of subtasks")
        corrected = taskspec_from_answer({"subtasks": answer["subtasks"]}, spec.instruction, scene)
        problems = repetition_problems(corrected)
        if allowed is not None:
            problems += copied_problems(corrected, state, allowed | spec_types(spec, state), example_types)
        if problems:
            raise Rejected("; ".join(problems))
        return SpecReview(spec=corrected, changed=corrected != spec, reason=reason)

    try:
        return ask_structured(client, request, convert, repair_rounds=repair_rounds,
                              feedback=load_prompt("feedback"))
    except LLMMalformedOutput as exc:
        log.warning("hp.validate: correction dropped, keeping the original spec: %s", exc)
        return SpecReview(spec=spec, changed=False, rejected=str(exc))


# ---- orderings ---------------------------------------------------------------------------
class Ordering(NamedTuple):
    """``before`` must finish before ``after`` starts."""

    before: str
    after: str
    reason: str


class RejectedOrdering(NamedTuple):
    ordering: Ordering
    why: str


class OrderingReport(BaseModel):
    model_config = ConfigDict(frozen=True)

    spec: TaskSpec
    accepted: tuple[Ordering, ...] = ()
    rejected: tuple[RejectedOrdering, ...] = ()


def orderings_schema(spec: TaskSpec) -> dict[str, Any]:
    ids = [s.id for s in spec.subtasks]
    n = len(ids)
    return {
        "type": "object",
        "additionalProperties": False,
        "required": ["orderings"],
        "properties": {"orderings": {
            "type": "array", "maxItems": max(1, n * (n - 1) // 2),
            "description": f"at most {max(1, n * (n - 1) // 2)} orderings",
            "items": {
                "type": "object", "additionalProperties": False, "required": ["before", "after", "reason"],
                "properties": {"before": {"type": "string", "enum": ids}, "after": {"type": "string", "enum": ids},
                               "reason": {"type": "string", "maxLength": 200,
                                          "description": "why, at most 200 characters"}},
            },
        }},
    }


def propose_orderings(client: LLMClient, spec: TaskSpec, instruction: str, plan_summary: str, *,
                      repair_rounds: int = 1, max_tokens: int = 1024, seed: int = 0) -> list[tuple[str, str, str]]:
    """The LLM's proposed (before, after, reason) orderings between subtasks of ``spec``.

    Only schema-valid pairs over the spec's ids come back; whether they are acceptable
    (no self-loop, no cycle) is :func:`apply_orderings`' decision.
    """
    request = LLMRequest(
        stage=MERGE_STAGE,
        messages=(Message(role="system", content=load_prompt("hp_merge_system").strip()),
                  Message(role="user", content=render(
                      "hp_merge_user", instruction=quote_instruction(instruction), subtasks=_subtasks_json(spec),
                      plan=plan_summary.strip() or "(no summary)"))),
        json_schema=orderings_schema(spec), schema_name="orderings", max_tokens=max_tokens, seed=seed)

    def convert(answer: dict[str, Any]) -> list[tuple[str, str, str]]:
        return [(o["before"], o["after"], str(o["reason"]).strip()) for o in answer["orderings"]]

    return ask_structured(client, request, convert, repair_rounds=repair_rounds, feedback=load_prompt("feedback"))


def _reaches(deps: dict[str, set[str]], start: str, goal: str) -> bool:
    """Does ``start`` (transitively) depend on ``goal``?"""
    stack, seen = [start], set()
    while stack:
        node = stack.pop()
        if node == goal:
            return True
        if node in seen:
            continue
        seen.add(node)
        stack.extend(deps[node])
    return False


def apply_orderings_report(spec: TaskSpec, orderings: Iterable[tuple[str, str, str]]) -> OrderingReport:
    """Add each ordering as a ``depends_on`` edge, in the given order, unless it names an
    unknown subtask, orders a subtask after itself, or would close a cycle with the
    edges already present; every rejection is kept with its reason."""
    deps: dict[str, set[str]] = {s.id: set(s.depends_on) for s in spec.subtasks}
    accepted: list[Ordering] = []
    rejected: list[RejectedOrdering] = []
    for before, after, reason in orderings:
        o = Ordering(before, after, reason)
        unknown = [x for x in (before, after) if x not in deps]
        if unknown:
            rejected.append(RejectedOrdering(o, f"unknown subtask {', '.join(unknown)}"))
        elif before == after:
            rejected.append(RejectedOrdering(o, "a subtask cannot come after itself"))
        elif before in deps[after]:
            rejected.append(RejectedOrdering(o, "already ordered"))
        elif _reaches(deps, before, after):
            rejected.append(RejectedOrdering(o, f"cycle: {before} already depends on {after}"))
        else:
            deps[after].add(before)
            accepted.append(o)
    for r in rejected:
        log.info("ordering %s -> %s rejected: %s", r.ordering.before, r.ordering.after, r.why)
    subtasks = tuple(
        s.model_copy(update={"depends_on": s.depends_on + tuple(
            o.before for o in accepted if o.after == s.id)})
        for s in spec.subtasks)
    return OrderingReport(spec=TaskSpec(instruction=spec.instruction, subtasks=subtasks),
                          accepted=tuple(accepted), rejected=tuple(rejected))


def apply_orderings(spec: TaskSpec, orderings: Iterable[tuple[str, str, str]]) -> TaskSpec:
    """``spec`` with the acceptable orderings added as dependencies (see
    :func:`apply_orderings_report` for what was rejected and why)."""
    return apply_orderings_report(spec, orderings).spec
