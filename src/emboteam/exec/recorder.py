"""The executor's trace recorder: turns what happens during a run into
:class:`~emboteam.exec.trace.TraceEvent` records (see ``trace.py`` for the kinds).

It is the :class:`~emboteam.btc.runtime.TraceSink` of compiled trees and is shared by the
reactive executor and the linear baselines, so every mode writes the same trace format.
"""

from __future__ import annotations

import time
from typing import Any

import py_trees

from emboteam.exec.trace import TraceEvent
from emboteam.world.environment import Environment

#: simulator events that disturb the run from outside (not the seeded action faults)
DISTURBANCE_KINDS = frozenset({"breakdown", "join", "moved"})


class TraceRecorder:
    def __init__(self, env: Environment, *, nodes: bool = True) -> None:
        self.env = env
        self.events: list[TraceEvent] = []
        self.record_nodes = nodes
        self._sim_seen = 0
        self._poses: dict[str, tuple[float, float, str | None]] = {}
        self._status: dict[object, str] = {}
        self._disturbed_wall: float | None = None

    @property
    def disturbed(self) -> bool:
        """Has a robot broken down, joined, or an object been moved so far?"""
        return self._disturbed_wall is not None

    def wall_since_disturbance(self) -> float | None:
        """Wall-clock seconds since the first disturbance was seen (None: there was none)."""
        if self._disturbed_wall is None:
            return None
        return round(time.perf_counter() - self._disturbed_wall, 4)

    def emit(self, kind: str, robot: str | None, **data: Any) -> None:
        self.events.append(TraceEvent.model_validate(
            {"t": round(self.env.now, 6), "kind": kind, "robot": robot, "data": data}))
        if robot is not None and kind in ("action_start", "action_end"):
            self.pose(robot, force=True)

    # ---- poses -----------------------------------------------------------------------
    def _pose_of(self, robot: str) -> tuple[float, float, str | None]:
        state = self.env.observe()
        r = state.robots[robot]
        pose_fn = getattr(self.env, "pose", None)
        x, z = pose_fn(robot) if callable(pose_fn) else r.position
        return (round(float(x), 4), round(float(z), 4), r.holding)

    def pose(self, robot: str, *, force: bool = False) -> None:
        """Record where the robot is (``force``: even if it has not moved)."""
        if robot not in self.env.observe().robots:
            return
        p = self._pose_of(robot)
        if force or self._poses.get(robot) != p:
            self._poses[robot] = p
            self.events.append(TraceEvent(t=round(self.env.now, 6), kind="pose", robot=robot,
                                          data={"x": p[0], "z": p[1], "holding": p[2]}))

    def sample_poses(self) -> None:
        """The periodic sample: robots that moved since their last recorded pose."""
        for robot in self.env.observe().robots:
            self.pose(robot)

    # ---- environment events ----------------------------------------------------------
    def pull_sim_events(self) -> None:
        """Copy the environment's own events (faults, breakdowns, joins, moved objects)
        when it keeps them (the simulator does: ``Simulator.events``)."""
        events = getattr(self.env, "events", None)
        if not isinstance(events, list):
            return
        for ev in events[self._sim_seen:]:
            kind, detail = getattr(ev, "kind", "event"), getattr(ev, "detail", str(ev))
            if kind in DISTURBANCE_KINDS and self._disturbed_wall is None:
                self._disturbed_wall = time.perf_counter()
            robot = detail if kind in ("breakdown", "join") else None
            self.events.append(TraceEvent(t=round(float(getattr(ev, "t", self.env.now)), 6), kind="sim",
                                          robot=robot, data={"kind": kind, "detail": detail}))
        self._sim_seen = len(events)

    # ---- behavior-tree node statuses -------------------------------------------------
    def node_visitor(self, paths: dict[Any, str], robots: dict[Any, str]) -> Any:
        """A callback for ``CompiledTree.tick`` recording node status changes."""
        def visit(node: py_trees.behaviour.Behaviour) -> None:
            if not self.record_nodes:
                return
            status = node.status.value
            if self._status.get(node.id) == status:
                return
            self._status[node.id] = status
            self.events.append(TraceEvent(t=round(self.env.now, 6), kind="node",
                                          robot=robots.get(node.id),
                                          data={"node": node.name, "path": paths.get(node.id, node.name),
                                                "type": type(node).__name__, "status": status}))
        return visit
