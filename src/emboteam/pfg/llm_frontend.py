"""The PFG with an LLM: instruction -> TaskSpec in ONE call, decomposition and
allocation together (the paper's PFG).

The prompt holds the rules it is held to (every limit and check, :meth:`system_text`),
the instruction (delimited, as data), the scene summary (in full, with ids and relevant
state, the types the instruction names or implies, :mod:`emboteam.pfg.focus`; the rest by
name), the team (skills, mass capacity) and the most similar worked example from the
development corpus (never of the task's floor plan or set); the answer is constrained by a
schema built from the scene and team (:mod:`emboteam.pfg.schema`), then converted and
validated, or is a clarification (:mod:`emboteam.pfg.clarification`). Problems are
rendered later by the planner from the state and these goals: the LLM never writes the
initial state or object lists.

Feedback: a rejected answer (schema, unknown object, impossible goal, cycle, a repeated
subtask, a condition copied from the worked example, or an error of the caller's
``validate``, e.g. the planner's) goes back to the model with the
message, for a bounded number of rounds. :meth:`LLMFrontend.repair` does the same for an
error found later (the planner failing on an accepted spec).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Collection, Sequence
from typing import Any

from emboteam.errors import EmboTeamError
from emboteam.llm.client import LLMClient
from emboteam.llm.messages import LLMRequest, Message
from emboteam.llm.structured import Rejected, ask_structured
from emboteam.pfg.answer_checks import copied_problems, repetition_problems
from emboteam.pfg.clarification import Clarification, ClarificationNeeded, ClarifyHook
from emboteam.pfg.fewshot import FewShotExample, example_messages, example_subject_types, select_examples
from emboteam.pfg.focus import focus_types, named_types
from emboteam.pfg.prompts import GOAL_SKILLS, load_prompt, render, render_scene, render_team
from emboteam.pfg.schema import (
    COUNT_MAX,
    DESCRIPTION_MAX,
    MAX_SUBTASKS,
    SUBJECT_TYPES_MAX,
    SceneVocabulary,
    clarification_from_answer,
    taskspec_from_answer,
    taskspec_schema,
    taskspec_to_answer,
)
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.catalogue import load_catalogue
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

#: longer instructions are refused before any call: a household instruction is short, and
#: a prompt-stuffing attack is not
MAX_INSTRUCTION_CHARS = 2000

Validator = Callable[[TaskSpec], None]

#: completion tokens of the answer form, measured with Qwen2.5's tokenizer: the frame
#: ``{"subtasks":[]}`` and one subtask with one condition, an 80-character description
#: and two dependencies (75, plus the whitespace the grammar lets a model put in)
FRAME_TOKENS, SUBTASK_TOKENS = 8, 80
#: subtasks a valid answer needs at most: the MACE-THOR goals have 1-5 conditions, and a
#: valid answer states each once; one more for a commonsense step
NEEDED_SUBTASKS = 6


def answer_token_cap(subtasks: int = NEEDED_SUBTASKS) -> int:
    """Completion tokens a valid answer of ``subtasks`` one-condition subtasks needs.

    The schema allows more (:data:`~emboteam.pfg.schema.MAX_SUBTASKS` subtasks of up to 6
    conditions): only a model that loops,
    repeating a subtask until the schema's limit, comes near it. On a 2-core CPU every
    token costs 0.1-1 s, so the cap, not the schema, bounds a looping answer (the
    recorded 531-token loop took 43 min); the cut-off answer is fed back like any other.
    """
    return FRAME_TOKENS + subtasks * SUBTASK_TOKENS


class InstructionError(EmboTeamError):
    """An instruction or team the front end cannot work with (empty, absurdly long)."""


def offline_draft(instruction: str, scene: Scene, state: WorldState,
                  team: Sequence[RobotProfile]) -> TaskSpec | None:
    """The offline parser's reading of the instruction, or None when it cannot read it: a
    hint of what the instruction is about ("make coffee" names the mug without saying it),
    used to list those types in detail and never sent as an answer."""
    from emboteam.pfg.parser import offline_frontend

    try:
        return offline_frontend().decompose(instruction, scene, state, team)
    except EmboTeamError:
        return None


def mentioned_types(instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
                    draft: TaskSpec | None = None) -> set[str]:
    """Types the instruction names or implies: its nouns and sound-alikes, what its named
    places hold, what its intent touches, and the types the offline parser's reading
    (``draft``, or one made here) names. A condition on one of these is never "copied
    from the worked example"."""
    if draft is None:
        draft = offline_draft(instruction, scene, state, team)
    return named_types(instruction, state, draft)


def quote_instruction(instruction: str) -> str:
    """The instruction as prompt data: stripped, and unable to close its delimiters."""
    text = instruction.strip()
    if not text:
        raise InstructionError("the instruction is empty")
    if len(text) > MAX_INSTRUCTION_CHARS:
        raise InstructionError(f"the instruction has {len(text)} characters; at most {MAX_INSTRUCTION_CHARS}")
    return text.replace("<<<", "«").replace(">>>", "»")


class LLMFrontend:
    """``decompose(instruction, scene, state, team) -> TaskSpec`` through one LLM call
    (more only when an answer is rejected); :class:`ClarificationNeeded` when the model
    says it cannot tell and no ``clarify`` hook settles it."""

    name = "llm"
    stage = "pfg"

    def __init__(self, client: LLMClient, *, fewshot: int = 1, repair_rounds: int = 2, max_subtasks: int = MAX_SUBTASKS,
                 max_conditions: int = 6, max_tokens: int | None = None, seed: int = 0, focus: bool = True,
                 clarify: bool = True, avoid_set: str = "") -> None:
        self.client = client
        self.fewshot = fewshot
        #: list in full only the types the instruction names or implies (False: the whole
        #: scene, as before the prompts were cut; benchmarks/prompt_tokens.py compares the two)
        self.focus = focus
        #: the answer may be a clarification instead of a guess (:mod:`emboteam.pfg.clarification`)
        self.clarify = clarify
        #: the set the task comes from: no worked example is taken from it
        self.avoid_set = avoid_set
        self.repair_rounds = repair_rounds
        self.max_subtasks = max_subtasks
        self.max_conditions = max_conditions
        #: the completion cap: ``max_tokens`` as given, else what NEEDED_SUBTASKS need,
        #: raised for an instruction the offline reading finds longer (:meth:`answer_cap`)
        self.max_tokens = max_tokens if max_tokens is not None else answer_token_cap(min(max_subtasks,
                                                                                           NEEDED_SUBTASKS))
        self._cap_given = max_tokens is not None
        self.seed = seed
        self._draft_memo: tuple[str, WorldState, TaskSpec | None] | None = None
        #: an answer that leaves out the null clarification is read as having it
        self.defaults: dict[str, Any] = {"clarification": None} if clarify else {}

    # ---- what the prompt shows ---------------------------------------------------------
    def draft(self, instruction: str, scene: Scene, state: WorldState,
              team: Sequence[RobotProfile]) -> TaskSpec | None:
        """The offline reading (memoised for the last instruction and state: the prompt and
        the checks of one call share it)."""
        memo = self._draft_memo
        if memo is not None and memo[0] == instruction and memo[1] is state:
            return memo[2]
        draft = offline_draft(instruction, scene, state, team)
        self._draft_memo = (instruction, state, draft)
        return draft

    def listed_types(self, instruction: str, scene: Scene, state: WorldState,
                     team: Sequence[RobotProfile]) -> set[str] | None:
        """The types the task's scene listing shows in detail (None: the whole scene)."""
        if not self.focus:
            return None
        return focus_types(instruction, state, self.draft(instruction, scene, state, team))

    def answer_cap(self, draft: TaskSpec | None) -> int:
        """The completion cap of this task's answer: :attr:`max_tokens`, or, when the
        offline reading (``draft``) has more conditions than that allows, one subtask per
        condition and one more (at most ``max_subtasks``), so a long right answer is not
        cut off; a given ``max_tokens`` is kept as it is."""
        if self._cap_given or draft is None:
            return self.max_tokens
        needed = min(self.max_subtasks, len(draft.goal().conditions) + 1)
        return max(self.max_tokens, answer_token_cap(needed))

    def system_text(self) -> str:
        """The system prompt, its limits filled in from this front end's schema."""
        return render("pfg_system", max_subtasks=str(self.max_subtasks), max_conditions=str(self.max_conditions),
                      subject_max=str(SUBJECT_TYPES_MAX), count_max=str(COUNT_MAX),
                      description_max=str(DESCRIPTION_MAX))

    def schema(self, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
               extra_ids: Sequence[str] = (), listed: Collection[str] | None = None) -> dict[str, Any]:
        vocab = SceneVocabulary.build(scene, state, team, listed)
        return taskspec_schema(vocab, max_subtasks=self.max_subtasks, max_conditions=self.max_conditions,
                               extra_ids=extra_ids, clarify=self.clarify)

    def examples(self, scene: Scene, instruction: str | None = None) -> list[FewShotExample]:
        return select_examples(scene.floor_plan, self.fewshot, instruction=instruction, avoid_set=self.avoid_set)

    def task_message(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile], *,
                     hint: str | None = None) -> Message:
        """The task's user turn: the instruction, the scene (in full only the types the
        instruction names or implies, :mod:`emboteam.pfg.focus`) and the team."""
        detail = self.listed_types(instruction, scene, state, team)
        text = render("pfg_user", instruction=quote_instruction(instruction), floor_plan=scene.floor_plan,
                      scene=render_scene(state, detail=detail), team=render_team(team, GOAL_SKILLS))
        if hint:
            text += "\n\n" + hint.strip()
        return Message(role="user", content=text)

    def messages(self, instruction: str, scene: Scene, state: WorldState,
                 team: Sequence[RobotProfile], *, hint: str | None = None) -> list[Message]:
        if not team:
            raise InstructionError("the team is empty")
        messages = [Message(role="system", content=self.system_text())]
        for example in self.examples(scene, instruction):
            messages += example_messages(example, clarify=self.clarify)
        messages.append(self.task_message(instruction, scene, state, team, hint=hint))
        return messages

    def request(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
                *, stage: str | None = None, extra: Sequence[Message] = (),
                extra_ids: Sequence[str] = (), hint: str | None = None) -> LLMRequest:
        listed = self.listed_types(instruction, scene, state, team)
        return LLMRequest(stage=stage or self.stage,
                          messages=tuple(self.messages(instruction, scene, state, team, hint=hint)) + tuple(extra),
                          json_schema=self.schema(scene, state, team, extra_ids, listed), schema_name="taskspec",
                          max_tokens=self.answer_cap(self.draft(instruction, scene, state, team)),
                          temperature=0.0, seed=self.seed)

    # ---- calls -----------------------------------------------------------------------
    def converter(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
                  validate: Validator | None, *, draft: TaskSpec | None = None,
                  ) -> Callable[[dict[str, Any]], TaskSpec | Clarification]:
        """Answer -> validated TaskSpec (or the clarification it asks for): the schema's
        rules, then the checks stated in the system prompt (repeated subtasks, conditions
        copied from the worked example), then ``validate``."""
        allowed = checked_types(self, instruction, scene, state, team, draft)
        example_types = example_subject_types(self.examples(scene, instruction))

        def convert(answer: dict[str, Any]) -> TaskSpec | Clarification:
            if self.clarify and (clarification := clarification_from_answer(answer)) is not None:
                return clarification
            spec = taskspec_from_answer(answer, instruction.strip(), scene)
            problems = repetition_problems(spec)
            if allowed is not None:
                problems += copied_problems(spec, state, allowed, example_types)
            if problems:
                raise Rejected("; ".join(problems))
            if validate is not None:
                validate(spec)
            return spec
        return convert

    def decompose(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile], *,
                  validate: Validator | None = None, hint: str | None = None,
                  clarify: ClarifyHook | None = None) -> TaskSpec:
        """One call on the happy path. ``validate`` (e.g. "can the planner solve it?") may
        raise any :class:`EmboTeamError`; its message goes back to the model as feedback.
        ``hint`` is appended to the task (the hybrid front end's parser error). When the
        model answers a clarification, ``clarify`` (the ``--clarify`` hook) may settle it:
        the chosen reading is asked once more as the user's words; otherwise
        :class:`ClarificationNeeded` is raised (``--json`` prints it)."""
        request = self.request(instruction, scene, state, team, hint=hint)
        result = ask_structured(self.client, request, self.converter(instruction, scene, state, team, validate),
                                repair_rounds=self.repair_rounds, feedback=load_prompt("feedback"),
                                defaults=self.defaults)
        if isinstance(result, TaskSpec):
            return result
        chosen = clarify(result) if clarify is not None else None
        if not chosen:
            raise ClarificationNeeded(result)
        settled = "\n\n".join(x for x in (hint, f"Asked \"{result.question}\", the user answered: {chosen}") if x)
        request = self.request(instruction, scene, state, team, stage=f"{self.stage}.clarified", hint=settled)
        final = ask_structured(self.client, request, self.converter(instruction, scene, state, team, validate),
                               repair_rounds=self.repair_rounds, feedback=load_prompt("feedback"),
                                defaults=self.defaults)
        if isinstance(final, Clarification):
            raise ClarificationNeeded(final)
        return final

    def repair(self, spec: TaskSpec, error_message: str, scene: Scene, state: WorldState,
               team: Sequence[RobotProfile], *, validate: Validator | None = None) -> TaskSpec:
        """A corrected spec after a later stage rejected ``spec`` with ``error_message``:
        the original prompt, the spec as the model's answer, the error as feedback."""
        shown = taskspec_to_answer(spec)
        if self.clarify:
            shown["clarification"] = None
        answer = json.dumps(shown, separators=(",", ":"), ensure_ascii=False)
        feedback = render("feedback", errors=f"- {error_message.strip()}")
        request = self.request(spec.instruction, scene, state, team, stage=f"{self.stage}.repair",
                               extra=(Message(role="assistant", content=answer),
                                      Message(role="user", content=feedback)),
                               extra_ids=[s.id for s in spec.subtasks])
        result = ask_structured(self.client, request,
                                self.converter(spec.instruction, scene, state, team, validate),
                                repair_rounds=max(0, self.repair_rounds - 1), feedback=load_prompt("feedback"),
                                defaults=self.defaults)
        if isinstance(result, Clarification):
            raise ClarificationNeeded(result)
        return result


def checked_types(frontend: LLMFrontend, instruction: str, scene: Scene, state: WorldState,
                  team: Sequence[RobotProfile], draft: TaskSpec | None = None) -> set[str] | None:
    """The types a condition may be about without being "copied from the worked example":
    those the instruction names or implies and those its listing shows in detail. None
    when the whole scene is listed (nothing is then certainly copied)."""
    listed = frontend.listed_types(instruction, scene, state, team)
    if listed is None and frontend.focus:
        return None
    draft = draft if draft is not None else frontend.draft(instruction, scene, state, team)
    allowed = named_types(instruction, state, draft) | (listed or set())
    cat = load_catalogue()  # what slicing an allowed type makes is allowed too (TomatoSliced)
    return allowed | {p[0] for t in allowed if (p := cat.slice_product(t)) is not None}
