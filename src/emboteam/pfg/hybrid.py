"""The hybrid front end: the offline parser reads, the LLM reviews only what is in doubt.

1. The offline parser reads the instruction (milliseconds, no call).
2. ``when="doubt"``: a reading the doubt detector does not flag
   (:func:`emboteam.pfg.doubt.needs_review`) is used as it is; ``when="always"`` asks
   the LLM every time; ``when="close"`` never reviews: the model only scores the close
   readings (below), and a parser error stands (for a small local model, whose review
   answers "ok" to everything and whose written specs are rarely right).
3. Review: the LLM sees the draft (in the answer form of :mod:`emboteam.pfg.schema`), the
   parser's notes and the conditions it was unsure of, and answers ``ok`` or the whole
   corrected decomposition, validated like the LLM front end's answers (schema, scene,
   repeated or copied subtasks, the planner), errors fed back.
4. A parser error (nothing read): the LLM writes the spec as the LLM front end does, with
   the parser's error as a hint.

The rule that keeps a weak model from making a confident reading worse: a correction must
keep every condition the parser was sure of (those not in ``Reading.unsure``) and add
none that contradicts one; it may change the unsure conditions and add what the notes
say was not read. Added conditions must be about types the instruction mentions, unless
the parser found a chore too vague to read ("get breakfast ready": commonsense may name
anything). A correction that breaks the rule is fed back; when the model never gives an
acceptable answer, the draft stands (the call is still counted).
"""

from __future__ import annotations

import json
import logging
from collections.abc import Callable, Sequence
from copy import deepcopy
from dataclasses import replace
from typing import Any, Literal

from emboteam.llm.client import LLMClient
from emboteam.llm.errors import (
    LLMMalformedOutput,
    LLMRateLimited,
    LLMScoringUnsupported,
    LLMServerError,
    LLMTimeout,
    LLMUnreachable,
)
from emboteam.llm.messages import LLMRequest, Message
from emboteam.llm.structured import Rejected, ask_structured
from emboteam.pfg.answer_checks import repetition_problems, sure_condition_problems
from emboteam.pfg.candidates import Candidate
from emboteam.pfg.clarification import ClarifyHook
from emboteam.pfg.doubt import needs_review
from emboteam.pfg.doubt_gate import doubt_signals, gate_candidates
from emboteam.pfg.focus import condition_types
from emboteam.pfg.llm_frontend import (
    LLMFrontend,
    Validator,
    answer_token_cap,
    mentioned_types,
    quote_instruction,
)
from emboteam.pfg.model_ranker import (
    Calibration,
    Reranking,
    differing_kinds,
    load_ranker_settings,
    objects_summary,
    rerank,
    rerank_in_scene,
)
from emboteam.pfg.prompts import GOAL_SKILLS, load_prompt, render, render_scene, render_team
from emboteam.pfg.reading import Reading, ReadingNote
from emboteam.pfg.schema import taskspec_from_answer, taskspec_to_answer
from emboteam.pfg.sentences import clause_sentences
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

log = logging.getLogger(__name__)
#: scoring failures the reading survives (configuration errors, replay misses and spent
#: budgets stay loud: they are the user's to fix)
SCORING_OUTAGES = (LLMTimeout, LLMUnreachable, LLMServerError, LLMRateLimited)

LLMWhen = Literal["doubt", "always", "close"]

#: what a parse function returns: a Reading, or the parser's older ParseResult (spec and
#: notes as strings), adapted by :func:`as_reading`
Parse = Callable[[str, Scene, WorldState, Sequence[RobotProfile]], Any]


def as_reading(result: Any) -> Reading:
    """A :class:`Reading` from what the offline parser returned."""
    if isinstance(result, Reading):
        return result
    if isinstance(result, TaskSpec):
        return Reading(spec=result)
    notes = tuple(n if isinstance(n, ReadingNote) else ReadingNote(span=str(n), reason=str(n))
                  for n in getattr(result, "notes", ()))
    return Reading(spec=result.spec, notes=notes, unsure=tuple(getattr(result, "unsure", ())))


def review_schema(task_schema: dict[str, Any]) -> dict[str, Any]:
    """The review answer: ``{"ok": true, "subtasks": []}`` or ``ok: false`` with the
    complete corrected subtasks ("ok" first, so a grammar makes the model decide first)."""
    subtasks = deepcopy(task_schema["properties"]["subtasks"])
    subtasks["minItems"] = 0
    subtasks["description"] = f"empty when ok; else all corrected subtasks, at most {subtasks['maxItems']}"
    return {"type": "object", "additionalProperties": False, "required": ["ok", "subtasks"],
            "properties": {"ok": {"type": "boolean", "description": "true if the draft is right as it is"},
                           "subtasks": subtasks}}


def render_notes(reading: Reading) -> str:
    lines = [f"- {n.kind} {n.span!r}: {n.reason}" for n in reading.notes]
    lines += [f"- unsure: {c}" for c in reading.unsure]
    return "\n".join(lines) or "- (none: the parser read every word)"


class HybridFrontend:
    """Offline reading first; the LLM reviews a doubtful draft or writes a missing one."""

    name = "hybrid"
    stage = "pfg.review"

    def __init__(self, client: LLMClient, parse: Parse, *, when: LLMWhen = "doubt",
                 llm: LLMFrontend | None = None, review_rounds: int = 2, max_tokens: int | None = None,
                 rank_margin: float | None = None, rank_weight: float | None = None,
                 rank_min_lead: float | None = None, rank_calibration: Calibration | None = None,
                 clarify: ClarifyHook | None = None) -> None:
        self.client = client
        self.parse = parse
        self.when = when
        self.llm = llm or LLMFrontend(client)
        #: feedback rounds of a review; the draft stands after them, so more rounds only
        #: cost calls when the model cannot correct itself
        self.review_rounds = review_rounds
        #: "ok" is a dozen tokens; by default a corrected spec as long as the answer form
        #: allows (the LLM front end's max_subtasks, one condition each) fits. Bounding the
        #: answer by tokens, not by a time-out, keeps a slow local model's runs reproducible
        #: (a cut-off answer is recorded and fed back; a timed-out call is not recorded)
        self.max_tokens = max_tokens if max_tokens is not None else answer_token_cap(self.llm.max_subtasks)
        #: the model ranker's margin, weight (0 turns it off) and PMI lead, by default the
        #: fitted ones (pfg/model_ranker.json); the last ranking, for views
        settings = load_ranker_settings()
        self.rank_margin = settings.margin if rank_margin is None else rank_margin
        self.rank_weight = settings.weight if rank_weight is None else rank_weight
        self.rank_min_lead = settings.min_lead if rank_min_lead is None else rank_min_lead
        #: which kinds of doubt the model may judge and the lead each needs
        #: (RankerSettings.lead_for; a ``rank_min_lead`` given stands for the file's)
        self.rank_kinds = settings.model_copy(update={"min_lead": self.rank_min_lead})
        #: the model's lead from whole sentences or from the clauses they do not share
        self.rank_calibration = settings.calibration if rank_calibration is None else rank_calibration
        #: the reading's own doubt signals that let the model score a sure prior
        self.doubt_gate = settings.doubt_gate
        self.last_ranking: Reranking[Candidate] | None = None
        #: settles a clarification the LLM asks for when it writes a spec the parser could not
        self.clarify = clarify

    def decompose(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile], *,
                  validate: Validator | None = None) -> TaskSpec:
        return self.read(instruction, scene, state, team, validate=validate).spec

    def read(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile], *,
             validate: Validator | None = None) -> Reading:
        from emboteam.pfg.offline.errors import OfflineParseError

        try:
            draft = as_reading(self.parse(instruction, scene, state, team))
        except OfflineParseError as exc:
            if self.when == "close":
                raise       # the model only scores readings: nothing to score
            hint = (f"An offline parser could not read this instruction: {exc}. "
                    "Decompose what the user asks for.")
            spec = self.llm.decompose(instruction, scene, state, team, validate=validate, hint=hint,
                                      clarify=self.clarify)
            return Reading(spec=spec, notes=(ReadingNote(span=instruction.strip(), reason=f"the offline parser "
                                             f"failed ({exc}); the LLM wrote the goals", kind="assumed"),))
        draft = self.rank_close_candidates(draft, instruction, scene, state)
        if self.when == "close" or (self.when == "doubt" and not needs_review(draft, instruction, state)):
            return draft
        return self.review(draft, instruction, scene, state, team, validate=validate)

    # ---- the local model as a scorer of close readings (issue 25) --------------------
    def rank_close_candidates(self, draft: Reading, instruction: str, scene: Scene,
                              state: WorldState | None = None) -> Reading:
        """The reader's candidates re-ranked by the model where their priors are close
        (:mod:`emboteam.pfg.model_ranker`: PMI of each end-state sentence, one call, none
        when the prior is sure) or, given the ``state``, where the reading's own doubt
        signals open the gate (:mod:`emboteam.pfg.doubt_gate`). A backend without
        log-probabilities (Anthropic) leaves the draft as read: the review below is its
        way to decide."""
        if len(draft.candidates) < 2 or self.rank_weight <= 0:
            return draft
        try:
            ranking = rerank_in_scene(draft.candidates, client=self.client, scene=scene, instruction=instruction,
                                      margin=self.rank_margin, weight=self.rank_weight,
                                      min_lead=self.rank_min_lead, lead_needed=self.lead_needed,
                                      clauses_of=_clauses if self.rank_calibration == "clauses" else None)
            opened: tuple[str, ...] = ()
            if not ranking.scored and state is not None and self.doubt_gate.rules:
                opened = self.doubt_gate.opened_by(doubt_signals(draft, instruction, state))
                if opened:
                    ranking = self.rank_doubtful(draft, instruction, scene) or ranking
        except LLMScoringUnsupported:
            return draft
        except SCORING_OUTAGES as exc:
            # the model only settles close calls: when it cannot answer (a time-out on a
            # loaded machine, a server down), the prior's order is still a complete reading,
            # so the task goes on with it and the reading says why the model was not heard
            log.warning("scoring skipped: %s", exc)
            unheard = ReadingNote(span="(model ranking)", kind="unsure",
                                  reason=f"the local model could not score the close readings "
                                         f"({type(exc).__name__}); the prior's order stands")
            return replace(draft, notes=(*draft.notes, unheard))
        self.last_ranking = ranking
        if not ranking.overturned:
            return draft
        best = ranking.candidates[0]
        why = f"the reading's doubt ({', '.join(opened)})" if opened else "a close reading"
        chosen = ReadingNote(span="(model ranking)", kind="assumed",
                             reason=f"the local model preferred {why}: {best.sentence}")
        return replace(draft, spec=best.spec, candidates=ranking.candidates, notes=(*draft.notes, chosen))

    def rank_doubtful(self, draft: Reading, instruction: str, scene: Scene) -> Reranking[Candidate] | None:
        """The top candidates (``doubt_gate.top_k``, within ``max_gap``), scored in one call
        whatever their priors, where a doubt signal opened the gate: the prior's first
        stands unless another leads its PMI by more than the gate's ``min_lead`` (and its
        prior plus weighted PMI too). None, and no call, when fewer than two differ."""
        gate = self.doubt_gate
        chosen = gate_candidates(draft.candidates, gate.top_k, gate.max_gap, gate.judge_drops)
        if not chosen:
            return None
        picked = {id(c) for c in chosen}
        rest = [c for c in draft.candidates if id(c) not in picked]
        objects = objects_summary(scene, (instruction, *(c.sentence for c in draft.candidates)))
        return rerank(chosen, client=self.client, objects=objects, instruction=instruction, margin=float("inf"),
                      weight=gate.weight, min_lead=gate.min_lead, tail=rest)

    def lead_needed(self, first: Candidate, other: Candidate) -> float | None:
        """The PMI lead ``other`` needs to overturn ``first``, by the kinds of doubt the two
        settle differently (pfg/model_ranker.json ``kinds``); None: the prior decides."""
        return self.rank_kinds.lead_for(differing_kinds(_resolutions(first), _resolutions(other)))

    # ---- the review call ---------------------------------------------------------------
    def request(self, draft: Reading, instruction: str, scene: Scene, state: WorldState,
                team: Sequence[RobotProfile]) -> LLMRequest:
        from emboteam.pfg.focus import focus_types

        detail = focus_types(instruction, state, draft.spec)
        system = self.llm.system_text() + "\n\n" + load_prompt("pfg_review_system").strip()
        answer = json.dumps(taskspec_to_answer(draft.spec), separators=(",", ":"), ensure_ascii=False)
        user = render("pfg_review_user", instruction=quote_instruction(instruction), floor_plan=scene.floor_plan,
                      scene=render_scene(state, detail=detail),
                      team=render_team(team, GOAL_SKILLS), draft=answer, notes=render_notes(draft))
        schema = review_schema(self.llm.schema(scene, state, team, extra_ids=[s.id for s in draft.spec.subtasks],
                                               listed=detail))
        return LLMRequest(stage=self.stage, messages=(Message(role="system", content=system),
                                                      Message(role="user", content=user)),
                          json_schema=schema, schema_name="review", max_tokens=self.max_tokens,
                          temperature=0.0, seed=self.llm.seed)

    def converter(self, draft: Reading, instruction: str, scene: Scene, state: WorldState,
                  team: Sequence[RobotProfile], validate: Validator | None) -> Callable[[dict[str, Any]], TaskSpec]:
        from emboteam.pfg.focus import focus_types

        # the same rule as the LLM front end's "copied" check, stated in the review prompt:
        # an added condition must be about a type the instruction names or implies, or the
        # listing shows in detail (the whole scene, when it is listed whole)
        listed = focus_types(instruction, state, draft.spec)
        mentioned = None if listed is None else mentioned_types(instruction, scene, state, team, draft.spec) | listed
        free = any(n.kind == "vague" for n in draft.notes) or mentioned is None
        known = {str(c) for c in draft.spec.goal().conditions}

        def convert(answer: dict[str, Any]) -> TaskSpec:
            if answer["ok"]:
                return draft.spec
            if not answer["subtasks"]:
                raise Rejected('give the complete corrected subtasks, or "ok": true if the draft is right')
            spec = taskspec_from_answer({"subtasks": answer["subtasks"]}, instruction.strip(), scene)
            problems = repetition_problems(spec) + sure_condition_problems(spec, draft.spec, draft.unsure)
            if not free:
                for s in spec.subtasks:
                    for c in s.goal:
                        if str(c) not in known and mentioned is not None \
                                and not condition_types(c, state) & mentioned:
                            problems.append(f"{s.id}: {c} is about something the instruction neither names "
                                            "nor implies and the listing does not show: remove it")
            if problems:
                raise Rejected("; ".join(problems))
            if spec == draft.spec:
                return draft.spec
            if validate is not None:
                validate(spec)
            return spec
        return convert

    def review(self, draft: Reading, instruction: str, scene: Scene, state: WorldState,
               team: Sequence[RobotProfile], *, validate: Validator | None = None) -> Reading:
        """The draft, or the LLM's accepted correction of it."""
        request = self.request(draft, instruction, scene, state, team)
        convert = self.converter(draft, instruction, scene, state, team, validate)
        try:
            spec = ask_structured(self.client, request, convert, repair_rounds=self.review_rounds,
                                  feedback=load_prompt("feedback"))
        except LLMMalformedOutput as exc:
            log.warning("hybrid front end: the LLM's corrections were rejected, the offline reading stands: %s", exc)
            stands = ReadingNote(span="(LLM review)", kind="assumed",
                                 reason=f"no acceptable correction, the offline reading stands: {exc}")
            return Reading(spec=draft.spec, unsure=draft.unsure, notes=(*draft.notes, stands))
        if spec is draft.spec:
            return draft
        corrected = ReadingNote(span="(LLM review)", reason="the LLM corrected the offline reading", kind="assumed")
        return Reading(spec=spec, notes=(*draft.notes, corrected))


def _clauses(candidate: Candidate) -> tuple[str, ...]:
    return clause_sentences(candidate.goals)


def _resolutions(candidate: Candidate) -> list[tuple[str, str, str]]:
    return [(r.kind, r.span, r.label) for r in candidate.resolves]
