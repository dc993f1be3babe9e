"""LLM-written per-robot action lists, without PDDL: the front end of the No-PFG&HP
ablation and of the SMART-LLM baseline.

The schema has one property per team member, each a list of actions whose ``skill`` is
an enum of THAT robot's skills, ``target`` an enum of the scene's object ids (slice
pieces included, so "pick up a slice" is expressible) and ``receptacle`` an enum of its
receptacles or null. A robot therefore cannot be given a skill it lacks, nor an object
the scene does not have; whether the actions succeed is left to execution, which is what
these modes measure.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from emboteam.llm.client import LLMClient
from emboteam.llm.messages import LLMRequest, Message
from emboteam.llm.structured import Rejected, ask_structured
from emboteam.pfg.llm_frontend import InstructionError, quote_instruction
from emboteam.pfg.prompts import load_prompt, render, render_scene, render_team
from emboteam.sim.rules import piece_ids
from emboteam.world.actions import Action, Skill
from emboteam.world.catalogue import load_catalogue
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState


def action_targets(state: WorldState) -> tuple[list[str], list[str]]:
    """(target ids, receptacle ids): live objects plus the pieces sliceable ones become."""
    cat = load_catalogue()
    targets: list[str] = []
    for o in state.objects.values():
        if o.gone:
            continue
        targets.append(o.id)
        product = cat.slice_product(o.type)
        if product is not None and o.source is None and not o.is_sliced:
            targets += [p for p in piece_ids(o.id, product[1]) if p not in state.objects]
    receptacles = sorted(o.id for o in state.objects.values() if not o.gone and o.has("receptacle"))
    return sorted(set(targets)), receptacles


def action_lists_schema(state: WorldState, team: Sequence[RobotProfile], *, max_actions: int = 40) -> dict[str, Any]:
    targets, receptacles = action_targets(state)
    robots: dict[str, Any] = {}
    for p in team:
        robots[p.name] = {
            "type": "array", "maxItems": max_actions,
            "description": f"{p.name}'s actions in order, at most {max_actions}",
            "items": {
                "type": "object", "additionalProperties": False, "required": ["skill", "target", "receptacle"],
                "properties": {
                    "skill": {"type": "string", "enum": [s.value for s in Skill if s in p.skills]},
                    "target": {"type": "string", "enum": targets},
                    "receptacle": {"anyOf": [{"type": "string", "enum": receptacles}, {"type": "null"}],
                                   "description": "the receptacle for PutObject; null for every other skill"},
                },
            },
        }
    return {"type": "object", "additionalProperties": False, "required": [p.name for p in team],
            "properties": robots}


def actions_from_answer(answer: dict[str, Any], team: Sequence[RobotProfile]) -> dict[str, list[Action]]:
    """A schema-valid answer -> actions per robot; Rejected if PutObject lacks a receptacle
    or another skill has one (the two ways the schema cannot rule out)."""
    problems: list[str] = []
    plans: dict[str, list[Action]] = {}
    for p in team:
        actions: list[Action] = []
        for i, raw in enumerate(answer[p.name]):
            skill = Skill(raw["skill"])
            receptacle = raw["receptacle"]
            if skill is Skill.PutObject and receptacle is None:
                problems.append(f"{p.name}[{i}]: PutObject({raw['target']}) needs a receptacle")
                continue
            if skill is not Skill.PutObject and receptacle is not None:
                problems.append(f"{p.name}[{i}]: {skill.value} takes no receptacle (set it to null)")
                continue
            actions.append(Action(skill=skill, target=raw["target"], receptacle=receptacle))
        plans[p.name] = actions
    if problems:
        raise Rejected("; ".join(problems))
    if not any(plans.values()):
        raise Rejected("every robot's list is empty: give the actions that carry out the instruction")
    return plans


class LLMActionListFrontend:
    """``generate(instruction, scene, state, team) -> {robot: [Action, ...]}`` in one call."""

    name = "llm-actions"
    stage = "action_lists"

    def __init__(self, client: LLMClient, *, repair_rounds: int = 2, max_actions: int = 40, max_tokens: int = 4096,
                 seed: int = 0) -> None:
        self.client = client
        self.repair_rounds = repair_rounds
        self.max_actions = max_actions
        self.max_tokens = max_tokens
        self.seed = seed

    def request(self, instruction: str, scene: Scene, state: WorldState, team: Sequence[RobotProfile]) -> LLMRequest:
        if not team:
            raise InstructionError("the team is empty")
        user = render("action_lists_user", instruction=quote_instruction(instruction), floor_plan=scene.floor_plan,
                      scene=render_scene(state), team=render_team(team))
        return LLMRequest(stage=self.stage,
                          messages=(Message(role="system", content=load_prompt("action_lists_system").strip()),
                                    Message(role="user", content=user)),
                          json_schema=action_lists_schema(state, team, max_actions=self.max_actions),
                          schema_name="action_lists", max_tokens=self.max_tokens, seed=self.seed)

    def generate(self, instruction: str, scene: Scene, state: WorldState,
                 team: Sequence[RobotProfile]) -> dict[str, list[Action]]:
        request = self.request(instruction, scene, state, team)
        return ask_structured(self.client, request, lambda answer: actions_from_answer(answer, team),
                              repair_rounds=self.repair_rounds, feedback=load_prompt("feedback"))
