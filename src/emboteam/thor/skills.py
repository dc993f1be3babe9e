"""Skills -> AI2-THOR controller actions, the way SMART-LLM and LaMMA-P drive AI2-THOR.

Navigation (GoToObject) drives the simulator's grid paths step by step
(:mod:`emboteam.thor.driving`); :func:`facing` gives the yaw and camera tilt that look at
the object at the end.

Interactions map one to one (SwitchOn -> ``ToggleObjectOn``, ...). ThrowObject puts the
held object into the GarbageCan within reach (our model's meaning of "throw it away";
AI2-THOR's own ``ThrowObject`` flings it along the camera wherever physics lands it).
CleanObject is AI2-THOR's ``CleanObject``; running water cleans and fills what stands in
the basin a faucet runs into (:meth:`ThorSkills.run_water`), as TEACh's wrapper does,
because AI2-THOR's water particles alone do not reliably change the metadata.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

from emboteam.thor.failures import failure_reason
from emboteam.thor.ids import ThorIds
from emboteam.world.actions import Action, FailureReason, Skill
from emboteam.world.catalogue import WATER_SOURCES
from emboteam.world.state import WorldState

#: the agent's eye height above its position (m): the iTHOR agent's camera
EYE_HEIGHT = 0.675
#: force (N) PushObject/PullObject apply: enough to slide furniture a little
PUSH_NEWTONS = 100.0

#: skill -> AI2-THOR action of the skills that take the target's objectId and nothing else
SIMPLE: dict[Skill, str] = {
    Skill.PickupObject: "PickupObject",
    Skill.OpenObject: "OpenObject",
    Skill.CloseObject: "CloseObject",
    Skill.SwitchOn: "ToggleObjectOn",
    Skill.SwitchOff: "ToggleObjectOff",
    Skill.SliceObject: "SliceObject",
    Skill.BreakObject: "BreakObject",
    Skill.CleanObject: "CleanObject",
}


class ThorEvent(Protocol):
    """What the adapter reads of an ``ai2thor.server.Event`` / ``MultiAgentEvent``."""

    metadata: Mapping[str, Any]
    events: Sequence[Any]


class ThorController(Protocol):
    """The part of ``ai2thor.controller.Controller`` the adapter uses."""

    last_event: Any

    def step(self, action: Any = None, **action_args: Any) -> Any: ...

    def stop(self) -> None: ...


@dataclass(frozen=True, slots=True)
class StepResult:
    """The outcome of one controller step (or a short sequence of them)."""

    success: bool
    reason: FailureReason | None = None
    message: str = ""


def _hdist(a: Mapping[str, float], b: Mapping[str, float]) -> float:
    return math.hypot(float(a["x"]) - float(b["x"]), float(a["z"]) - float(b["z"]))


def facing(agent: Mapping[str, float], target: Mapping[str, float]) -> tuple[float, float]:
    """(yaw, horizon) in degrees that point the agent's camera at ``target``. AI2-THOR's
    yaw 0 looks along +z and 90 along +x; a positive horizon looks down."""
    yaw = math.degrees(math.atan2(float(target["x"]) - float(agent["x"]), float(target["z"]) - float(agent["z"])))
    drop = float(agent["y"]) + EYE_HEIGHT - float(target["y"])
    horizon = math.degrees(math.atan2(drop, max(_hdist(agent, target), 1e-6)))
    return (round(yaw % 360.0, 1), round(max(-30.0, min(60.0, horizon)), 1))


class ThorSkills:
    """Runs our skills on an AI2-THOR controller, one agent at a time."""

    def __init__(self, controller: ThorController, ids: ThorIds, *, force_action: bool = True) -> None:
        self.controller = controller
        self.ids = ids
        #: ``forceAction`` on interactions, as SMART-LLM and LaMMA-P pass it: the agent stands
        #: near the object but its camera need not frame it exactly
        self.force_action = force_action

    # ---- low level --------------------------------------------------------------------
    def step(self, agent_id: int, action: str, skill: Skill | None = None, **args: Any) -> tuple[StepResult, Any]:
        """One controller step; AI2-THOR's ValueError for a malformed call is a failure too."""
        try:
            event = self.controller.step(dict(action=action, agentId=agent_id, **args))
        except ValueError as exc:  # AI2-THOR raises it for InvalidArgument/MissingArguments
            return StepResult(False, failure_reason(str(exc), skill), str(exc)), None
        meta = event.metadata
        if meta.get("lastActionSuccess"):
            return StepResult(True), event
        message = str(meta.get("errorMessage") or f"{action} failed")
        return StepResult(False, failure_reason(message, skill), message), event

    # ---- interactions -----------------------------------------------------------------
    def interact(self, agent_id: int, action: Action, state: WorldState, robot: str) -> StepResult:
        """Run one non-navigation skill; ``state`` is the state right before it."""
        skill = action.skill
        force = self.force_action
        if skill in SIMPLE:
            result, _ = self.step(agent_id, SIMPLE[skill], skill, objectId=self.ids.thor(action.target),
                                  forceAction=force)
        elif skill is Skill.PutObject:
            assert action.receptacle is not None
            result, _ = self.step(agent_id, "PutObject", skill, objectId=self.ids.thor(action.receptacle),
                                  forceAction=force, placeStationary=True)
        elif skill is Skill.ThrowObject:
            cans = sorted((state.distance(robot, g.id), g.id) for g in state.of_type("GarbageCan")
                          if state.in_reach(robot, g.id))
            if not cans:
                return StepResult(False, FailureReason.NO_GARBAGE_CAN, f"no GarbageCan within reach of {robot}")
            result, _ = self.step(agent_id, "PutObject", skill, objectId=self.ids.thor(cans[0][1]),
                                  forceAction=True, placeStationary=False)
        elif skill is Skill.DropHandObject:
            result, _ = self.step(agent_id, "DropHandObject", skill, forceAction=True)
        elif skill in (Skill.PushObject, Skill.PullObject):
            result, _ = self.step(agent_id, skill.value, skill, objectId=self.ids.thor(action.target),
                                  moveMagnitude=PUSH_NEWTONS, forceAction=force)
        else:
            raise AssertionError(f"unhandled skill {skill}")
        return result

    def run_water(self, agent_id: int, state: WorldState) -> None:
        """What running water does to the basins of running faucets: a dirty object in one
        is cleaned, an empty fillable one filled with water (AI2-THOR's ``CleanObject`` and
        ``FillObjectWithLiquid``; a failure leaves the object as it is)."""
        seen: set[str] = set()
        for src in state.objects.values():
            if src.type not in WATER_SOURCES or not src.is_on:
                continue
            for basin in src.controls:
                for o in state.descendants(basin):
                    if o.id in seen or o.id not in self.ids:
                        continue
                    seen.add(o.id)
                    if o.is_dirty:
                        self.step(agent_id, "CleanObject", objectId=self.ids.thor(o.id), forceAction=True)
                    if o.has("canFillWithLiquid") and o.liquid is None:
                        self.step(agent_id, "FillObjectWithLiquid", objectId=self.ids.thor(o.id),
                                  fillLiquid="water", forceAction=True)
