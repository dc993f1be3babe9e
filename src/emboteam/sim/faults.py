"""Seeded fault injection.

Every random decision is drawn from its own generator seeded by ``(seed, kind, robot,
counter)``, so one robot's faults do not depend on what other robots did or on the order
the executor ticks them: the same seed and the same per-robot action sequence give the
same faults.
"""

from __future__ import annotations

import random

from pydantic import BaseModel, ConfigDict, Field, model_validator


class Breakdown(BaseModel):
    """A robot stops for good at a simulated time (it drops what it holds)."""

    model_config = ConfigDict(frozen=True)

    robot: str
    at: float = Field(ge=0)


class ObjectMove(BaseModel):
    """Someone else moves an object at a simulated time (``to`` None: a random valid place).

    ``object`` None: the object is drawn when the move happens, among ``candidates`` that
    exist then and are not held (a benchmark's ``--moves random@…``). ``into_closed``: the
    random place may be inside a closed receptacle (the person opens it, puts the object
    in and shuts it again) when a working robot of the team can open it; a random place
    is always within reach of a cell no broken robot walls off. ``draw`` keys the random choices, so two moves at one time
    still draw independently."""

    model_config = ConfigDict(frozen=True)

    object: str | None = None
    at: float = Field(ge=0)
    to: str | None = None
    candidates: tuple[str, ...] = ()
    into_closed: bool = False
    draw: str = ""

    @model_validator(mode="after")
    def _something_to_move(self) -> ObjectMove:
        if self.object is None and not self.candidates:
            raise ValueError("a move needs an object or candidates to draw it from")
        return self


class MessageFaults(BaseModel):
    """The blackboard as a lossy network between robots (``--msg-loss``, ``--msg-delay``).

    - ``release_loss``: probability that a spot lock's release message is lost; the lock
      stays on the board until its lease expires (``BTConfig.lock_lease`` simulated seconds
      after its holder stopped renewing it) and a waiting robot takes it over;
    - ``flag_delay``: a done flag reaches each other robot up to this many simulated
      seconds late (drawn per flag and reader), so a consumer reads it late.
    """

    model_config = ConfigDict(frozen=True)

    release_loss: float = Field(0.0, ge=0, le=1)
    flag_delay: float = Field(0.0, ge=0)

    @property
    def any(self) -> bool:
        return bool(self.release_loss or self.flag_delay)


class FaultConfig(BaseModel):
    """What can go wrong during an episode."""

    model_config = ConfigDict(frozen=True)

    #: probability that an action (navigation included) fails at its end, state unchanged
    action_failure: float = Field(0.0, ge=0, le=1)
    #: probability that, on arrival, an interaction target is occluded until the robot
    #: re-approaches it (one draw per approach; a re-approach after an occlusion clears it)
    occlusion: float = Field(0.0, ge=0, le=1)
    breakdowns: tuple[Breakdown, ...] = ()
    moves: tuple[ObjectMove, ...] = ()
    messages: MessageFaults = MessageFaults()

    @classmethod
    def level(cls, p: float) -> FaultConfig:
        """The ``--faults P`` setting: actions fail with probability P, and targets are
        occluded on arrival with probability P/2."""
        return cls(action_failure=p, occlusion=p / 2)

    @property
    def any(self) -> bool:
        return bool(self.action_failure or self.occlusion or self.breakdowns or self.moves or self.messages.any)


class FaultInjector:
    """Answers "does this go wrong?" deterministically from the seed."""

    def __init__(self, config: FaultConfig, seed: int) -> None:
        self.config = config
        self.seed = seed

    def _draw(self, *key: object) -> float:
        return random.Random("|".join(map(str, (self.seed, *key)))).random()

    def action_fails(self, robot: str, action_index: int) -> bool:
        p = self.config.action_failure
        return p > 0 and self._draw("act", robot, action_index) < p

    def occluded(self, robot: str, approach: int, target: str) -> bool:
        p = self.config.occlusion
        return p > 0 and self._draw("occ", robot, approach, target) < p

    def choice(self, key: str, options: list[str]) -> str:
        return options[int(self._draw("choice", key) * len(options))]

    def release_lost(self, robot: str, spot: str, count: int) -> bool:
        """Is this robot's ``count``-th release of ``spot`` lost on the way?"""
        p = self.config.messages.release_loss
        return p > 0 and self._draw("release", robot, spot, count) < p

    def flag_delay(self, flag: str, reader: str) -> float:
        """How late ``reader`` sees ``flag`` (0 without ``flag_delay``)."""
        d = self.config.messages.flag_delay
        return round(d * self._draw("delay", flag, reader), 6) if d > 0 else 0.0
