"""The PFG with an LLM: instruction -> TaskSpec in ONE call, decomposition and
allocation together (the paper's PFG).

The prompt holds the instruction (delimited, as data), the scene summary (objects by
type with ids and relevant state), the team (skills, mass capacity) and a few worked
examples from other floor plans; the answer is constrained by a schema built from the
scene and team (:mod:`emboteam.pfg.schema`), then converted and validated. Problems are
rendered later by the planner from the state and these goals: the LLM never writes the
initial state or object lists.

Feedback: a rejected answer (schema, unknown object, impossible goal, cycle, or an error
of the caller's ``validate``, e.g. the planner's) goes back to the model with the
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
from emboteam.llm.structured import ask_structured
from emboteam.pfg.fewshot import example_messages, select_examples
from emboteam.pfg.prompts import load_prompt, render, render_scene, render_team
from emboteam.pfg.schema import SceneVocabulary, taskspec_from_answer, taskspec_schema, taskspec_to_answer
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

#: longer instructions are refused before any call: a household instruction is short, and
#: a prompt-stuffing attack is not
MAX_INSTRUCTION_CHARS = 2000

Validator = Callable[[TaskSpec], None]


class InstructionError(EmboTeamError):
    """An instruction or team the front end cannot work with (empty, absurdly long)."""


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

    def __init__(self, client: LLMClient, *, fewshot: int = 3, repair_rounds: int = 2, max_subtasks: int = 12,
                 max_conditions: int = 6, max_tokens: int = 2048, seed: int = 0) -> None:
        self.client = client
        self.fewshot = fewshot
        self.repair_rounds = repair_rounds
        self.max_subtasks = max_subtasks
        self.max_conditions = max_conditions
        self.max_tokens = max_tokens
        self.seed = seed

    # ---- prompt ----------------------------------------------------------------------
    def schema(self, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
               extra_ids: Sequence[str] = ()) -> dict[str, Any]:
        vocab = SceneVocabulary.build(scene, state, team)
        return taskspec_schema(vocab, max_subtasks=self.max_subtasks, max_conditions=self.max_conditions,
                               extra_ids=extra_ids)

    def messages(self, instruction: str, scene: Scene, state: WorldState,
                 team: Sequence[RobotProfile]) -> list[Message]:
        if not team:
            raise InstructionError("the team is empty")
        messages = [Message(role="system", content=load_prompt("pfg_system").strip())]
        for example in select_examples(scene.floor_plan, self.fewshot):
            messages += example_messages(example)
        messages.append(Message(role="user", content=render(
            "pfg_user", instruction=quote_instruction(instruction), floor_plan=scene.floor_plan,
            scene=render_scene(state), team=render_team(team))))
        return messages

    def request(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
                *, stage: str | None = None, extra: Sequence[Message] = (),
                extra_ids: Sequence[str] = ()) -> LLMRequest:
        return LLMRequest(stage=stage or self.stage,
                          messages=tuple(self.messages(instruction, scene, state, team)) + tuple(extra),
                          json_schema=self.schema(scene, state, team, extra_ids), schema_name="taskspec",
                          max_tokens=self.max_tokens, temperature=0.0, seed=self.seed)

    # ---- calls -----------------------------------------------------------------------
    @staticmethod
    def _converter(instruction: str, scene: Scene, validate: Validator | None) -> Callable[[dict[str, Any]], TaskSpec]:
        def convert(answer: dict[str, Any]) -> TaskSpec:
            spec = taskspec_from_answer(answer, instruction.strip(), scene)
            if validate is not None:
                validate(spec)
            return spec
        return convert

    def decompose(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile], *,
                  validate: Validator | None = None) -> TaskSpec:
        """One call on the happy path. ``validate`` (e.g. "can the planner solve it?") may
        raise any :class:`EmboTeamError`; its message goes back to the model as feedback."""
        request = self.request(instruction, scene, state, team)
        return ask_structured(self.client, request, self._converter(instruction, scene, validate),
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
        return ask_structured(self.client, request, self._converter(spec.instruction, scene, validate),
                              repair_rounds=max(0, self.repair_rounds - 1), feedback=load_prompt("feedback"))
