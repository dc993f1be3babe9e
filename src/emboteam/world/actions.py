"""Skills, actions and typed action outcomes: the vocabulary shared by the planner, the
behavior-tree compiler, the executor and every Environment implementation."""

from __future__ import annotations

from enum import Enum

from pydantic import BaseModel, ConfigDict, Field


class Skill(str, Enum):
    """The THOR skill names used by SMART-LLM and LaMMA-P robot definitions."""

    GoToObject = "GoToObject"
    PickupObject = "PickupObject"
    PutObject = "PutObject"
    OpenObject = "OpenObject"
    CloseObject = "CloseObject"
    SwitchOn = "SwitchOn"
    SwitchOff = "SwitchOff"
    SliceObject = "SliceObject"
    BreakObject = "BreakObject"
    CleanObject = "CleanObject"
    ThrowObject = "ThrowObject"
    DropHandObject = "DropHandObject"
    PushObject = "PushObject"
    PullObject = "PullObject"

    def __str__(self) -> str:
        return self.value


class Action(BaseModel):
    """One skill applied to objects of the scene.

    ``target`` is the object acted on (for PutObject, ThrowObject and DropHandObject: the
    held object); ``receptacle`` is where PutObject puts it.
    """

    model_config = ConfigDict(frozen=True)

    skill: Skill
    target: str
    receptacle: str | None = None

    def __str__(self) -> str:
        args = self.target if self.receptacle is None else f"{self.target}, {self.receptacle}"
        return f"{self.skill.value}({args})"


class FailureReason(str, Enum):
    """Why an action failed. Every failure leaves the world state unchanged."""

    UNKNOWN_OBJECT = "unknown_object"
    MISSING_SKILL = "missing_skill"
    ROBOT_DOWN = "robot_down"
    ROBOT_BUSY = "robot_busy"
    NOT_REACHABLE = "not_reachable"
    NOT_VISIBLE = "not_visible"
    SPOT_BUSY = "spot_busy"
    HAND_FULL = "hand_full"
    HAND_EMPTY = "hand_empty"
    NOT_HOLDING_TARGET = "not_holding_target"
    TOO_HEAVY = "too_heavy"
    NOT_PICKUPABLE = "not_pickupable"
    HELD_BY_OTHER = "held_by_other"
    NOT_A_RECEPTACLE = "not_a_receptacle"
    RECEPTACLE_CLOSED = "receptacle_closed"
    NOT_ALLOWED_HERE = "not_allowed_here"
    NOT_OPENABLE = "not_openable"
    ALREADY_OPEN = "already_open"
    ALREADY_CLOSED = "already_closed"
    NOT_TOGGLEABLE = "not_toggleable"
    ALREADY_ON = "already_on"
    ALREADY_OFF = "already_off"
    NOT_SLICEABLE = "not_sliceable"
    ALREADY_SLICED = "already_sliced"
    NO_KNIFE = "no_knife"
    NOT_BREAKABLE = "not_breakable"
    ALREADY_BROKEN = "already_broken"
    NOT_DIRTYABLE = "not_dirtyable"
    ALREADY_CLEAN = "already_clean"
    NO_GARBAGE_CAN = "no_garbage_can"
    NOT_MOVEABLE = "not_moveable"
    ACTUATION_FAULT = "actuation_fault"

    def __str__(self) -> str:
        return self.value


#: Failures that a retry or a re-approach can clear without changing the plan.
TRANSIENT_FAILURES: frozenset[FailureReason] = frozenset({
    FailureReason.ACTUATION_FAULT,
    FailureReason.NOT_VISIBLE,
    FailureReason.SPOT_BUSY,
    FailureReason.NOT_REACHABLE,
    FailureReason.ROBOT_BUSY,
})


class ActionOutcome(BaseModel):
    """What became of one action: success, or a typed failure with a message."""

    model_config = ConfigDict(frozen=True)

    robot: str
    action: Action
    start: float = Field(description="simulated seconds")
    end: float = Field(description="simulated seconds")
    success: bool
    reason: FailureReason | None = None
    message: str = ""

    def __str__(self) -> str:
        verdict = "ok" if self.success else f"FAILED {self.reason}: {self.message}"
        return f"[{self.start:7.2f}-{self.end:7.2f}] {self.robot}: {self.action} {verdict}"
