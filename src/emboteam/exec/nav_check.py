"""An independent check of an episode's motion: did two robots ever share a cell, or swap
cells in one step?

It replays the timed cell sequence the environment recorded (every robot's start cell and
every MoveAhead it executed, from the trace's ``nav`` event) with its own, plainer model,
and shares no code with the reservation table that planned the motion
(:mod:`emboteam.sim.traffic`), so a bug there cannot hide here:

- a robot is *in* a cell from the middle of the move that enters it to the middle of the
  move that leaves it (from its start, or to the end of the episode, if none);
- a **vertex conflict** is two robots in the same cell over a common stretch of time;
- an **edge conflict** is two robots crossing one edge in opposite directions at
  overlapping times (a swap, which the vertex rule alone would miss).

The planner's own rule is stricter (a move holds both cells for its whole duration), so an
episode planned with avoidance on must check clean; with the ``no-avoidance`` ablation the
checker is what counts the collisions.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

#: shortest overlap (s) that counts: timestamps are rounded to microseconds
TOLERANCE = 1e-4

GridCell = tuple[int, int]


@dataclass(frozen=True)
class Stay:
    robot: str
    cell: GridCell
    since: float
    until: float


@dataclass(frozen=True)
class Crossing:
    robot: str
    start: float
    end: float
    a: GridCell
    b: GridCell


@dataclass(frozen=True)
class NavCheck:
    """Conflicts found: (robot, robot, cell or edge, time) per conflict."""

    vertex: tuple[tuple[str, str, str, float], ...]
    edge: tuple[tuple[str, str, str, float], ...]

    @property
    def collisions(self) -> int:
        return len(self.vertex) + len(self.edge)


def _stays(starts: Mapping[str, Sequence[Any]], moves: Iterable[Sequence[Any]]) -> list[Stay]:
    by_robot: dict[str, list[tuple[float, float, GridCell, GridCell]]] = {}
    for robot, start, end, ai, aj, bi, bj in moves:
        by_robot.setdefault(str(robot), []).append((float(start), float(end), (int(ai), int(aj)),
                                                    (int(bi), int(bj))))
    out: list[Stay] = []
    for robot, (t0, i, j) in starts.items():
        cell: GridCell = (int(i), int(j))
        since = float(t0)
        for start, end, a, b in sorted(by_robot.get(robot, [])):
            mid = (start + end) / 2
            out.append(Stay(robot, a if a == cell else cell, since, mid))
            cell, since = b, mid
        out.append(Stay(robot, cell, since, float("inf")))
    return out


def check_motion(record: Mapping[str, Any]) -> NavCheck:
    """Conflicts in a recorded motion: ``record`` has ``starts`` (robot -> [t, i, j]) and
    ``moves`` ([robot, start, end, i_from, j_from, i_to, j_to] per MoveAhead)."""
    starts = record.get("starts", {})
    moves = record.get("moves", [])
    by_cell: dict[GridCell, list[Stay]] = {}
    for s in _stays(starts, moves):
        by_cell.setdefault(s.cell, []).append(s)
    vertex: list[tuple[str, str, str, float]] = []
    for cell, stays in by_cell.items():
        stays.sort(key=lambda s: s.since)
        for k, a in enumerate(stays):
            for b in stays[k + 1:]:
                if b.since >= a.until - TOLERANCE:
                    break
                if a.robot != b.robot and min(a.until, b.until) - max(a.since, b.since) > TOLERANCE:
                    first, second = sorted((a.robot, b.robot))
                    vertex.append((first, second, f"{cell}", round(max(a.since, b.since), 4)))
    crossings = [Crossing(str(r), float(s), float(e), (int(ai), int(aj)), (int(bi), int(bj)))
                 for r, s, e, ai, aj, bi, bj in moves]
    by_edge: dict[tuple[GridCell, GridCell], list[Crossing]] = {}
    for c in crossings:
        by_edge.setdefault((c.a, c.b), []).append(c)
    edge: list[tuple[str, str, str, float]] = []
    for c in crossings:
        for d in by_edge.get((c.b, c.a), ()):
            if c.robot < d.robot and min(c.end, d.end) - max(c.start, d.start) > TOLERANCE:
                edge.append((c.robot, d.robot, f"{c.a}-{c.b}", round(max(c.start, d.start), 4)))
    return NavCheck(tuple(sorted(vertex)), tuple(sorted(edge)))
