"""A drive on the navigation grid as AI2-THOR agent actions.

The simulator's drives (:mod:`emboteam.sim.traffic`) are timed sequences of states
(cell, heading); consecutive states differ by one agent action. This module names those
actions the way AI2-THOR does, so the behavior-tree export and the AI2-THOR environment
replay the very path the simulator drove: ``MoveAhead`` (0.25 m along the heading),
``RotateRight`` (+90° yaw: heading 0 faces +z, 1 faces +x), ``RotateLeft`` (-90°), and
``Wait`` for the time a robot stands still because another robot holds the way (AI2-THOR
needs no action for it). Turns that line the robot up with the drive's first heading take
no time: in the simulator's model they overlap the end of the robot's previous action.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from emboteam.sim.traffic import Step
from emboteam.world.navgrid import STEPS, Cell, NavGrid

EPS = 1e-6
MOVE = "MoveAhead"
RIGHT = "RotateRight"
LEFT = "RotateLeft"
WAIT = "Wait"


@dataclass(frozen=True, slots=True)
class DriveStep:
    """One agent action of a drive, and the state it leaves the robot in."""

    action: str
    start: float
    end: float
    cell: Cell
    heading: int

    @property
    def yaw(self) -> int:
        """AI2-THOR ``rotation.y`` after the step (degrees)."""
        return 90 * self.heading


class NotOneActionError(ValueError):
    """Two consecutive states of a path are not one agent action apart (a caller bug)."""


def action_between(a: tuple[Cell, int], b: tuple[Cell, int]) -> str:
    """The agent action from state ``a`` to state ``b`` (``Wait`` when they are equal)."""
    (ca, ha), (cb, hb) = a, b
    turn = (hb - ha) % 4
    if ca == cb and turn != 2:
        return {0: WAIT, 1: RIGHT, 3: LEFT}[turn]
    if ha == hb and (cb[0] - ca[0], cb[1] - ca[1]) == STEPS[ha]:
        return MOVE
    raise NotOneActionError(f"{a} -> {b} is not one MoveAhead, RotateLeft or RotateRight")


def _align(start: float, cell: Cell, heading: int, target: int) -> list[DriveStep]:
    """Zero-time turns from ``heading`` to ``target`` (shortest way round)."""
    turn = (target - heading) % 4
    name, count = (RIGHT, turn) if turn <= 2 else (LEFT, 4 - turn)
    out = []
    for _ in range(count):
        heading = (heading + (1 if name == RIGHT else 3)) % 4
        out.append(DriveStep(name, start, start, cell, heading))
    return out


def _wait(out: list[DriveStep], at: Step, until: float) -> None:
    """Stand still at ``at`` until ``until`` (one ``Wait`` per stretch)."""
    if out and out[-1].action == WAIT and abs(out[-1].end - at.t) < EPS:
        out[-1] = DriveStep(WAIT, out[-1].start, until, at.cell, at.heading)
    else:
        out.append(DriveStep(WAIT, at.t, until, at.cell, at.heading))


def drive_steps(states: Sequence[Step], *, start: float | None = None, end: float | None = None,
                heading_before: int | None = None) -> list[DriveStep]:
    """The agent actions of a timed path; standing still (the robot waiting for the way
    to clear, before or during the drive) becomes one ``Wait`` per stretch. ``start`` /
    ``end``: the drive's own start and end when they lie before / after its path (a
    drive that waited before it found a way, a drive padded to its minimum time);
    ``heading_before``: where the robot faced before (zero-time turns line it up)."""
    if not states:
        return []
    first = states[0]
    out: list[DriveStep] = []
    if start is not None and first.t > start + EPS:
        out.append(DriveStep(WAIT, start, first.t, first.cell, first.heading if heading_before is None
                             else heading_before))
    if heading_before is not None:
        out.extend(_align(first.t, first.cell, heading_before, first.heading))
    for a, b in itertools.pairwise(states):
        if a.cell == b.cell and (abs(b.t - a.t) < EPS or (b.heading - a.heading) % 4 == 2):
            # a new plan (a re-plan after waiting, or from the same instant): wait, line up
            if b.t > a.t + EPS:
                _wait(out, a, b.t)
            out.extend(_align(b.t, a.cell, a.heading, b.heading))
            continue
        if a.cell != b.cell and b.heading != a.heading:
            # a move, then a new plan from the cell it entered: the move, then line up
            action_between((a.cell, a.heading), (b.cell, a.heading))
            out.append(DriveStep(MOVE, a.t, b.t, b.cell, a.heading))
            out.extend(_align(b.t, b.cell, a.heading, b.heading))
            continue
        name = action_between((a.cell, a.heading), (b.cell, b.heading))
        if name == WAIT:
            _wait(out, a, b.t)
        else:
            out.append(DriveStep(name, a.t, b.t, b.cell, b.heading))
    last = states[-1]
    if end is not None and end > last.t + EPS:
        out.append(DriveStep(WAIT, last.t, end, last.cell, last.heading))
    return out


def cells_text(states: Iterable[Step]) -> str:
    """The cells of a path as ``x,z,yaw`` in metres and degrees, ``;``-separated: each cell
    once, with the heading the robot leaves it with (the last: the heading it ends with)."""
    cells: list[tuple[Cell, int]] = []
    for s in states:
        if cells and cells[-1][0] == s.cell:
            cells[-1] = (s.cell, s.heading)
        else:
            cells.append((s.cell, s.heading))
    return ";".join("{:g},{:g},{}".format(*NavGrid.point(c), 90 * h) for c, h in cells)


def steps_text(steps: Iterable[DriveStep]) -> str:
    """The actions, space-separated; a wait as ``Wait:SECONDS``."""
    return " ".join(f"{WAIT}:{s.end - s.start:.2f}" if s.action == WAIT else s.action for s in steps)
