"""The Environment protocol: what the executor needs from a world, simulated or real.

The symbolic simulator (:class:`emboteam.sim.Simulator`) implements it; an adapter for a
real AI2-THOR controller or a ROS 2 action server implements the same five methods and
slots in without touching the planner or the behavior-tree compiler.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

from emboteam.world.actions import Action, ActionOutcome
from emboteam.world.robots import RobotProfile
from emboteam.world.state import WorldState


@runtime_checkable
class Environment(Protocol):
    @property
    def now(self) -> float:
        """Current (simulated or wall-clock) time, seconds since the episode began."""

    def observe(self) -> WorldState:
        """The current symbolic state. Callers must not mutate it."""

    def start(self, robot: str, action: Action) -> None:
        """Begin an action; its outcome arrives from :meth:`advance`."""

    def busy(self, robot: str) -> bool:
        """Is the robot executing an action?"""

    def advance(self, until: float) -> list[ActionOutcome]:
        """Let time pass up to ``until``; return the actions that ended meanwhile."""

    def next_event_time(self) -> float | None:
        """When the next action ends or scheduled event happens (None: nothing pending)."""

    def add_robot(self, profile: RobotProfile) -> None:
        """A robot joins the team now."""
