"""The PFG with an LLM: instruction -> TaskSpec in ONE call, decomposition and
allocation together (the paper's PFG).

The prompt holds the instruction (delimited, as data), the scene summary (in full, with
ids and relevant state, only the types the instruction touches; the rest by name), the
team (skills, mass capacity) and one worked example from another floor plan; the answer is constrained by a schema built from the
scene and team (:mod:`emboteam.pfg.schema`), then converted and validated. Problems are
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
from collections.abc import Callable, Sequence
from typing import Any

from emboteam.errors import EmboTeamError
from emboteam.llm.client import LLMClient
from emboteam.llm.messages import LLMRequest, Message
from emboteam.llm.structured import Rejected, ask_structured
from emboteam.pfg.answer_checks import copied_problems, repetition_problems
from emboteam.pfg.fewshot import FewShotExample, example_messages, example_subject_types, select_examples
from emboteam.pfg.focus import focus_types, instruction_types, spec_types
from emboteam.pfg.prompts import GOAL_SKILLS, load_prompt, render, render_scene, render_team
from emboteam.pfg.schema import SceneVocabulary, taskspec_from_answer, taskspec_schema, taskspec_to_answer
from emboteam.pfg.taskspec import TaskSpec
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

    The schema allows more (8 subtasks of up to 6 conditions): only a model that loops,
    repeating a subtask until the schema's limit, comes near it. On a 2-core CPU every
    token costs 0.1-1 s, so the cap, not the schema, bounds a looping answer (the
    recorded 531-token loop took 43 min); the cut-off answer is fed back like any other.
    """
    return FRAME_TOKENS + subtasks * SUBTASK_TOKENS


class InstructionError(EmboTeamError):
    """An instruction or team the front end cannot work with (empty, absurdly long)."""


def mentioned_types(instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
                    draft: TaskSpec | None = None) -> set[str]:
    """Types the instruction mentions: its nouns, and the types the offline parser's
    reading (``draft``, or one made here) names ("make coffee" names the mug without
    saying it). Used only to catch conditions copied from the worked examples."""
    types = instruction_types(instruction)
    if draft is None:
        from emboteam.pfg.parser import offline_frontend

        try:
            draft = offline_frontend().decompose(instruction, scene, state, team)
        except EmboTeamError:
            draft = None
    if draft is not None:
        types |= spec_types(draft, state)
    return types


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
    (more only when an answer is rejected)."""

    name = "llm"
    stage = "pfg"

    def __init__(self, client: LLMClient, *, fewshot: int = 1, repair_rounds: int = 2, max_subtasks: int = 8,
                 max_conditions: int = 6, max_tokens: int | None = None, seed: int = 0, focus: bool = True) -> None:
        self.client = client
        self.fewshot = fewshot
        #: list in full only the types the instruction touches (False: the whole scene, as
        #: before the prompts were cut; benchmarks/prompt_tokens.py compares the two)
        self.focus = focus
        self.repair_rounds = repair_rounds
        self.max_subtasks = max_subtasks
        self.max_conditions = max_conditions
        self.max_tokens = max_tokens if max_tokens is not None else answer_token_cap(min(max_subtasks,
                                                                                           NEEDED_SUBTASKS))
        self.seed = seed

    # ---- prompt ----------------------------------------------------------------------
    def schema(self, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
               extra_ids: Sequence[str] = ()) -> dict[str, Any]:
        vocab = SceneVocabulary.build(scene, state, team)
        return taskspec_schema(vocab, max_subtasks=self.max_subtasks, max_conditions=self.max_conditions,
                               extra_ids=extra_ids)

    def examples(self, scene: Scene) -> list[FewShotExample]:
        return select_examples(scene.floor_plan, self.fewshot)

    def task_message(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile], *,
                     hint: str | None = None) -> Message:
        """The task's user turn: the instruction, the scene (in full only the types the
        instruction touches, :mod:`emboteam.pfg.focus`) and the team."""
        text = render("pfg_user", instruction=quote_instruction(instruction), floor_plan=scene.floor_plan,
                      scene=render_scene(state, detail=focus_types(instruction, state) if self.focus else None),
                      team=render_team(team, GOAL_SKILLS))
        if hint:
            text += "\n\n" + hint.strip()
        return Message(role="user", content=text)

    def messages(self, instruction: str, scene: Scene, state: WorldState,
                 team: Sequence[RobotProfile], *, hint: str | None = None) -> list[Message]:
        if not team:
            raise InstructionError("the team is empty")
        messages = [Message(role="system", content=load_prompt("pfg_system").strip())]
        for example in self.examples(scene):
            messages += example_messages(example)
        messages.append(self.task_message(instruction, scene, state, team, hint=hint))
        return messages

    def request(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
                *, stage: str | None = None, extra: Sequence[Message] = (),
                extra_ids: Sequence[str] = (), hint: str | None = None) -> LLMRequest:
        return LLMRequest(stage=stage or self.stage,
                          messages=tuple(self.messages(instruction, scene, state, team, hint=hint)) + tuple(extra),
                          json_schema=self.schema(scene, state, team, extra_ids), schema_name="taskspec",
                          max_tokens=self.max_tokens, temperature=0.0, seed=self.seed)

    # ---- calls -----------------------------------------------------------------------
    def converter(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
                  validate: Validator | None, *, draft: TaskSpec | None = None,
                  ) -> Callable[[dict[str, Any]], TaskSpec]:
        """Answer -> validated TaskSpec: the schema's rules, then the weak-model checks
        (repeated subtasks, conditions copied from the worked examples), then ``validate``."""
        mentioned = mentioned_types(instruction, scene, state, team, draft)
        example_types = example_subject_types(self.examples(scene))

        def convert(answer: dict[str, Any]) -> TaskSpec:
            spec = taskspec_from_answer(answer, instruction.strip(), scene)
            problems = repetition_problems(spec) + copied_problems(spec, state, mentioned, example_types)
            if problems:
                raise Rejected("; ".join(problems))
            if validate is not None:
                validate(spec)
            return spec
        return convert

    def decompose(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile], *,
                  validate: Validator | None = None, hint: str | None = None) -> TaskSpec:
        """One call on the happy path. ``validate`` (e.g. "can the planner solve it?") may
        raise any :class:`EmboTeamError`; its message goes back to the model as feedback.
        ``hint`` is appended to the task (the hybrid front end's parser error)."""
        request = self.request(instruction, scene, state, team, hint=hint)
        return ask_structured(self.client, request, self.converter(instruction, scene, state, team, validate),
                              repair_rounds=self.repair_rounds, feedback=load_prompt("feedback"))

    def repair(self, spec: TaskSpec, error_message: str, scene: Scene, state: WorldState,
               team: Sequence[RobotProfile], *, validate: Validator | None = None) -> TaskSpec:
        """A corrected spec after a later stage rejected ``spec`` with ``error_message``:
        the original prompt, the spec as the model's answer, the error as feedback."""
        answer = json.dumps(taskspec_to_answer(spec), separators=(",", ":"), ensure_ascii=False)
        feedback = render("feedback", errors=f"- {error_message.strip()}")
        request = self.request(spec.instruction, scene, state, team, stage=f"{self.stage}.repair",
                               extra=(Message(role="assistant", content=answer),
                                      Message(role="user", content=feedback)),
                               extra_ids=[s.id for s in spec.subtasks])
        return ask_structured(self.client, request, self.converter(spec.instruction, scene, state, team, validate),
                              repair_rounds=max(0, self.repair_rounds - 1), feedback=load_prompt("feedback"))
