"""Seeded fault injection.

Every random decision is drawn from its own generator seeded by ``(seed, kind, robot,
counter)``, so one robot's faults do not depend on what other robots did or on the order
the executor ticks them: the same seed and the same per-robot action sequence give the
same faults.
"""

from __future__ import annotations

import random

from pydantic import BaseModel, ConfigDict, Field


class Breakdown(BaseModel):
    """A robot stops for good at a simulated time (it drops what it holds)."""

    model_config = ConfigDict(frozen=True)

    robot: str
    at: float = Field(ge=0)


class ObjectMove(BaseModel):
    """Someone else moves an object at a simulated time (``to`` None: a random valid place)."""

    model_config = ConfigDict(frozen=True)

    object: str
    at: float = Field(ge=0)
    to: str | None = None


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

    @classmethod
    def level(cls, p: float) -> FaultConfig:
        """The ``--faults P`` setting: actions fail with probability P, and targets are
        occluded on arrival with probability P/2."""
        return cls(action_failure=p, occlusion=p / 2)

    @property
    def any(self) -> bool:
        return bool(self.action_failure or self.occlusion or self.breakdowns or self.moves)


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
