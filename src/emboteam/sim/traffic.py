"""Robots on the navigation grid: one cell each, space-time reservations, prioritised
planning of drives, waiting, local re-planning and yielding.

Every robot holds the cells it stands on, as time intervals in a reservation table shared
by the whole team: a parked robot holds its cell until it sets off; a drive holds each cell
from the start of the action that enters it to the end of the action that leaves it (so
during a move both cells are held, which rules out swaps as well as two robots in one
cell). A drive is planned when it starts, by a space-time A* search over (cell, heading,
step) that avoids every interval already reserved (*prioritised planning*: earlier drives
have priority); the static distance table of :mod:`emboteam.world.navigation` is its
heuristic. Waiting on the spot is one of its actions.

When no path exists because robots stand in the way (a robot parked in a doorway), the
drive *waits* and re-plans shortly after; an idle robot in the way is asked to *yield*
(it moves to the nearest cell off the other's way), and when robots wait on each other
(a cycle of blocked drives) the later one yields, which breaks the deadlock. A robot that
breaks down keeps its cell for good; drives whose reserved path crossed it re-plan
locally from where they are.

The search is written here: it needs reservations in time, which no graph library's
shortest-path call takes.
"""

from __future__ import annotations

import heapq
import itertools
import math
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from emboteam.world.navgrid import GRID, STEPS, Cell, NavGrid
from emboteam.world.navigation import POSE_CHOICES, Navigator, cost_table
from emboteam.world.poses import REACH, Pose

INF = math.inf
EPS = 1e-6
#: A* expansions before a drive counts as blocked (a few thousand suffice on iTHOR grids)
MAX_EXPANSIONS = 4_000
#: steps a drive may spend waiting beyond its static length before it counts as blocked
MAX_EXTRA_STEPS = 60


@dataclass(frozen=True, slots=True)
class Step:
    """A robot's state at time ``t``: its cell and heading (0..3)."""

    t: float
    cell: Cell
    heading: int


@dataclass(frozen=True, slots=True)
class Move:
    """One executed MoveAhead: from ``a`` to ``b`` between ``start`` and ``end``."""

    robot: str
    start: float
    end: float
    a: Cell
    b: Cell


@dataclass
class _Interval:
    robot: str
    t0: float
    t1: float


class Reservations:
    """Cell -> time intervals held by robots."""

    def __init__(self) -> None:
        self._cells: dict[Cell, list[_Interval]] = {}

    def add(self, robot: str, cell: Cell, t0: float, t1: float) -> None:
        self._cells.setdefault(cell, []).append(_Interval(robot, t0, t1))

    def holders(self, cell: Cell, t0: float, t1: float, robot: str) -> list[str]:
        """Other robots holding ``cell`` at some time in the open interval (t0, t1)."""
        return [iv.robot for iv in self._cells.get(cell, ())
                if iv.robot != robot and iv.t0 < t1 - EPS and iv.t1 > t0 + EPS]

    def free(self, cell: Cell, t0: float, t1: float, robot: str) -> bool:
        return not any(iv.robot != robot and iv.t0 < t1 - EPS and iv.t1 > t0 + EPS
                       for iv in self._cells.get(cell, ()))

    def release_after(self, robot: str, t: float) -> None:
        """Forget what ``robot`` holds after time ``t`` (its plan from ``t`` on changed)."""
        for cell, ivs in self._cells.items():
            keep = []
            for iv in ivs:
                if iv.robot == robot and iv.t0 >= t - EPS:
                    continue
                if iv.robot == robot and iv.t1 > t:
                    iv.t1 = t
                keep.append(iv)
            self._cells[cell] = keep

    def parks(self, cell: Cell, robot: str) -> bool:
        """Whether another robot holds ``cell`` for good, now or from some time on."""
        return any(iv.t1 == INF and iv.robot != robot for iv in self._cells.get(cell, ()))

    def parked_at(self, cell: Cell, t: float) -> str | None:
        """The robot holding ``cell`` from before ``t`` for good, if any."""
        for iv in self._cells.get(cell, ()):
            if iv.t1 == INF and iv.t0 <= t + EPS:
                return iv.robot
        return None


def intervals(path: Sequence[Step]) -> list[tuple[Cell, float, float]]:
    """The (cell, from, to) a timed path holds; the last cell is held for good."""
    out: list[tuple[Cell, float, float]] = []
    cell, since = path[0].cell, path[0].t
    for prev, nxt in itertools.pairwise(path):
        if nxt.cell != prev.cell:
            out.append((cell, since, nxt.t))
            cell, since = nxt.cell, prev.t
    out.append((cell, since, INF))
    return out


def _within_reach(cell: Cell, point: tuple[float, float]) -> bool:
    x, z = NavGrid.point(cell)
    return math.hypot(x - point[0], z - point[1]) <= REACH


def wait_segments(path: Sequence[Step]) -> int:
    """Stretches of a path where the robot stays put (same cell and heading)."""
    waiting = [a.cell == b.cell and a.heading == b.heading for a, b in itertools.pairwise(path)]
    return sum(1 for i, w in enumerate(waiting) if w and (i == 0 or not waiting[i - 1]))


def _succ(grid: NavGrid, cell: Cell, h: int) -> Iterable[tuple[Cell, int]]:
    di, dj = STEPS[h]
    nxt = (cell[0] + di, cell[1] + dj)
    if nxt in grid.cells:
        yield nxt, h
    yield cell, (h + 1) % 4
    yield cell, (h + 3) % 4
    yield cell, h  # wait


def search(res: Reservations | None, nav: Navigator, robot: str, start: Cell, t0: float, dt: float,
           goals: Sequence[Pose], heading: int | None = None) -> list[Step] | None:
    """A shortest timed path from ``start`` at ``t0`` to one of ``goals`` avoiding ``res``
    (``None``: no other robot is considered). ``heading`` ``None``: the robot may set off
    in any direction (see :mod:`emboteam.world.navigation`)."""
    if res is not None:
        quick = _static_if_free(res, nav, robot, start, t0, dt, goals, heading)
        if quick is not None:
            return quick
        if not _open_way(res, nav.grid, robot, start, t0, {g.cell for g in goals}):
            return None  # parked robots wall every goal off: no search in time can help
    tables = [tab for g in goals if (tab := _table(nav, g))]
    if not tables:
        return None

    def h_of(cell: Cell, h: int) -> int | None:
        best = [d for tab in tables if (d := tab.get((cell, h))) is not None]
        return min(best) if best else None

    heads = range(4) if heading is None else (heading,)
    starts = [(cell_h, hv) for hv in heads if (cell_h := h_of(start, hv)) is not None]
    if not starts:
        return None
    limit = min(s for s, _ in starts) + (MAX_EXTRA_STEPS if res is not None else 0)
    goal_set = {(g.cell, g.heading) for g in goals}
    # entries: (f, -steps: deeper first among equals, insertion order, steps, cell, heading)
    frontier: list[tuple[int, int, int, int, Cell, int]] = []
    parent: dict[tuple[Cell, int, int], tuple[Cell, int, int] | None] = {}
    order = 0
    for est, hv in starts:
        heapq.heappush(frontier, (est, 0, order, 0, start, hv))
        order += 1
        parent[(start, hv, 0)] = None
    expansions = 0
    while frontier and expansions < MAX_EXPANSIONS:
        _, _, _, k, cell, hv = heapq.heappop(frontier)
        expansions += 1
        t = t0 + k * dt
        if (cell, hv) in goal_set and (res is None or res.free(cell, t, INF, robot)):
            return _unwind(parent, (cell, hv, k), t0, dt)
        if k >= limit:
            continue
        for ncell, nh in _succ(nav.grid, cell, hv):
            key = (ncell, nh, k + 1)
            if key in parent:
                continue
            if res is not None and not (res.free(ncell, t, t + dt, robot) and res.free(cell, t, t + dt, robot)):
                continue
            remaining = h_of(ncell, nh)
            if remaining is None:
                continue
            parent[key] = (cell, hv, k)
            heapq.heappush(frontier, (k + 1 + remaining, -(k + 1), order, k + 1, ncell, nh))
            order += 1
    return None


def _open_way(res: Reservations, grid: NavGrid, robot: str, start: Cell, t: float, goals: set[Cell]) -> bool:
    """Whether some goal cell can be reached past the cells other robots hold for good (now
    or once they arrive): when not, the drive waits for them to leave or yield rather than
    search in time for a way that mostly is not there."""
    seen = {start}
    stack = [start]
    while stack:
        cell = stack.pop()
        if cell in goals:
            return True
        for n in grid.neighbours(cell):
            if n not in seen and not res.parks(n, robot):
                seen.add(n)
                stack.append(n)
    return False


def _static(nav: Navigator, start: Cell, t0: float, dt: float, goals: Sequence[Pose]) -> list[Step] | None:
    """The shortest path (cached) to the nearest of ``goals``, timed from ``t0``, ignoring
    every other robot."""
    best = min(((n, k) for k, g in enumerate(goals) if (n := nav.actions_to(start, g)) is not None),
               default=None)
    if best is None:
        return None
    states = nav.path(start, goals[best[1]])
    if states is None:
        return None
    return [Step(t0 + k * dt, c, h) for k, (c, h) in enumerate(states)]


def _static_if_free(res: Reservations, nav: Navigator, robot: str, start: Cell, t0: float, dt: float,
                    goals: Sequence[Pose], heading: int | None) -> list[Step] | None:
    """The static shortest path to the nearest goal, timed from ``t0``, when no reservation
    is in its way (the common case: most drives meet nobody, and this costs no search)."""
    if heading is not None or not goals:
        return None
    path = _static(nav, start, t0, dt, goals)
    if path is None:
        return None
    for a, b in itertools.pairwise(path):
        if not (res.free(a.cell, a.t, b.t, robot) and res.free(b.cell, a.t, b.t, robot)):
            return None
    return path if res.free(path[-1].cell, path[-1].t, INF, robot) else None


def _table(nav: Navigator, goal: Pose) -> dict[tuple[Cell, int], int]:
    return cost_table(nav.floor_plan, goal)


def _unwind(parent: dict[tuple[Cell, int, int], tuple[Cell, int, int] | None],
            key: tuple[Cell, int, int], t0: float, dt: float) -> list[Step]:
    out = []
    cur: tuple[Cell, int, int] | None = key
    while cur is not None:
        cell, h, k = cur
        out.append(Step(t0 + k * dt, cell, h))
        cur = parent[cur]
    return out[::-1]


@dataclass
class Traffic:
    """The team's reservations and paths on one floor plan (owned by the simulator)."""

    nav: Navigator
    avoid: bool = True
    res: Reservations = field(default_factory=Reservations)
    paths: dict[str, list[Step]] = field(default_factory=dict)
    moves: list[Move] = field(default_factory=list)
    starts: dict[str, tuple[float, Cell]] = field(default_factory=dict)
    waits: int = 0
    replans: int = 0
    yields: int = 0
    #: robots that broke down: their cells are walls for good
    down: dict[str, Cell] = field(default_factory=dict)
    #: seconds spent searching (the cost of path planning, reported with the episode)
    search_seconds: float = 0.0
    #: the latest start of each robot's moves in :attr:`moves` (or later: moves are only
    #: added by :meth:`_commit`), so a drive that starts after them all keeps the list
    #: as it is without going through every robot's moves (a 32-robot plan's simulation
    #: commits hundreds of drives)
    _latest: dict[str, float] = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        for m in self.moves:
            self._latest[m.robot] = max(self._latest.get(m.robot, m.start), m.start)

    # ---- robots entering and standing --------------------------------------------------
    def place(self, robot: str, cell: Cell, t: float, heading: int = 0) -> Cell:
        """Put a robot on the grid at ``t`` (start or join): on ``cell``, or the nearest
        cell free from ``t`` on when that one is taken."""
        if not self.res.free(cell, t, INF, robot):
            cell = self._free_cell_near(cell, t, robot, avoid=set()) or cell
        self.res.add(robot, cell, t, INF)
        self.paths[robot] = [Step(t, cell, heading)]
        self.starts[robot] = (t, cell)
        return cell

    def cell(self, robot: str, t: float) -> Step:
        """Where ``robot`` is at ``t`` (the last step at or before ``t``)."""
        path = self.paths[robot]
        last = path[0]
        for s in path:
            if s.t > t + EPS:
                break
            last = s
        return last

    def point(self, robot: str, t: float) -> tuple[float, float]:
        """Floor point at ``t``, interpolated along a move."""
        path = self.paths[robot]
        for a, b in itertools.pairwise(path):
            if a.t - EPS <= t <= b.t + EPS and a.cell != b.cell:
                f = min(1.0, max(0.0, (t - a.t) / (b.t - a.t))) if b.t > a.t else 1.0
                (xa, za), (xb, zb) = NavGrid.point(a.cell), NavGrid.point(b.cell)
                return (xa + f * (xb - xa), za + f * (zb - za))
        return NavGrid.point(self.cell(robot, t).cell)

    def end_time(self, robot: str) -> float:
        return self.paths[robot][-1].t

    # ---- drives ------------------------------------------------------------------------
    def drive(self, robot: str, t: float, dt: float, goals: Sequence[Pose]) -> list[Step] | None:
        """Plan and reserve ``robot``'s drive from where it is at ``t`` (or where its
        current path ends, if later) to one of ``goals``. ``None``: blocked (nothing is
        reserved; the robot keeps its cell)."""
        here = self.paths[robot][-1] if self.end_time(robot) > t else self.cell(robot, t)
        t0 = max(t, here.t)
        began = time.perf_counter()
        if self.avoid:
            self.res.release_after(robot, t0)
            usable = self._usable(goals, t0, robot)
            path = search(self.res, self.nav, robot, here.cell, t0, dt, usable) if usable else None
        else:
            path = _static(self.nav, here.cell, t0, dt, goals[:POSE_CHOICES])
        self.search_seconds += time.perf_counter() - began
        if path is None:
            if self.avoid:
                self.res.add(robot, here.cell, t0, INF)
            return None
        self._commit(robot, t0, path)
        return path

    def _usable(self, goals: Sequence[Pose], t: float, robot: str) -> list[Pose]:
        """Goal poses a robot can end at and stay: no other robot holds the cell from ``t``
        on (parked there, or passing through later), and no broken robot walls it off. None
        usable: the drive is blocked for now (searching in time towards a cell it could
        never keep would only burn time)."""
        if self.down:
            open_cells = self.open_cells(robot, t)
            goals = [g for g in goals if g.cell in open_cells]
        return [g for g in goals if self.res.free(g.cell, t, INF, robot)][:POSE_CHOICES]

    def open_cells(self, robot: str, t: float) -> set[Cell]:
        """Cells ``robot`` can ever reach from where it is at ``t``: every cell but the
        broken robots' (the others move or make way in time)."""
        walls = set(self.down.values())
        start = self.paths[robot][-1].cell if self.end_time(robot) > t else self.cell(robot, t).cell
        seen = {start}
        stack = [start]
        while stack:
            for n in self.nav.grid.neighbours(stack.pop()):
                if n not in seen and n not in walls:
                    seen.add(n)
                    stack.append(n)
        return seen

    def walled_off(self, robot: str, t: float, goals: Sequence[Pose]) -> list[str]:
        """The broken robots that wall ``robot`` off from every pose of ``goals`` for good
        (empty: some pose can still be reached, perhaps once others make way)."""
        if not self.down or any(g.cell in self.open_cells(robot, t) for g in goals):
            return []
        return sorted(self.down)

    def _commit(self, robot: str, t0: float, path: list[Step]) -> None:
        """Make ``path`` (starting at ``t0``) the robot's plan from ``t0`` on."""
        kept = [s for s in self.paths[robot] if s.t < t0 - EPS]
        if self._latest.get(robot, -INF) >= t0 - EPS:
            self.moves = [m for m in self.moves if not (m.robot == robot and m.start >= t0 - EPS)]
        self.paths[robot] = kept + path
        if self.avoid:
            for cell, since, until in intervals(path):
                self.res.add(robot, cell, since, until)
        for a, b in itertools.pairwise(path):
            if a.cell != b.cell:
                self.moves.append(Move(robot, a.t, b.t, a.cell, b.cell))
                self._latest[robot] = max(self._latest.get(robot, a.t), a.t)
        self.waits += wait_segments(path)

    def stop(self, robot: str, t: float) -> Step:
        """``robot`` stops for good at ``t`` (it broke down): it keeps the cell it is in or
        entering. Returns that step."""
        path = self.paths[robot]
        stop = self.cell(robot, t)
        for a, b in itertools.pairwise(path):
            if a.t < t < b.t and a.cell != b.cell:
                stop = Step(b.t, b.cell, b.heading)  # mid-move: it completes the step
        cut = stop.t + EPS
        self.paths[robot] = [s for s in path if s.t <= cut - 2 * EPS] or [stop]
        if self.paths[robot][-1] != stop:
            self.paths[robot].append(stop)
        self.moves = [m for m in self.moves if not (m.robot == robot and m.start >= stop.t - EPS
                                                    and not (m.b == stop.cell and m.end <= stop.t + EPS))]
        if self.avoid:
            self.res.release_after(robot, t)
            self.res.add(robot, stop.cell, t, INF)
            self.down[robot] = stop.cell
        return stop

    def halt(self, robot: str, t: float, cell: Cell, heading: int) -> None:
        """``robot``'s drive ended at ``t`` on ``cell`` (the world refused its next step):
        it stands there from ``t`` on, and the rest of its plan is dropped."""
        self.paths[robot] = [s for s in self.paths[robot] if s.t < t - EPS] + [Step(t, cell, heading)]
        def done(m: Move) -> bool:  # moves that ended before t, or at t on the cell it is on
            return m.robot != robot or m.end < t - EPS or (m.end <= t + EPS and m.b == cell)

        self.moves = [m for m in self.moves if done(m)]
        if self.avoid:
            self.res.release_after(robot, t)
            self.res.add(robot, cell, t, INF)

    def record(self, floor_plan: str, now: float) -> dict[str, object]:
        """The robots' motion up to ``now``, for the trace (``nav`` event) and its checker
        (:mod:`emboteam.exec.nav_check`): start cells, every MoveAhead begun before now, and
        the counters."""
        return {
            "floor_plan": floor_plan, "grid": GRID, "avoidance": self.avoid,
            "starts": {r: [round(t, 6), c[0], c[1]] for r, (t, c) in sorted(self.starts.items())},
            "moves": [[m.robot, round(m.start, 6), round(m.end, 6), m.a[0], m.a[1], m.b[0], m.b[1]]
                      for m in sorted(self.moves, key=lambda m: (m.start, m.robot)) if m.start < now],
            "waits": self.waits, "replans": self.replans, "yields": self.yields,
        }

    def crossing(self, cell: Cell, t: float, robot: str) -> list[str]:
        """Other robots whose reserved future (after ``t``) passes through ``cell``."""
        return sorted({r for r, p in self.paths.items() if r != robot
                       and any(s.cell == cell and s.t > t - EPS for s in p)})

    def replan(self, robot: str, t: float, dt: float, goals: Sequence[Pose]) -> list[Step] | None:
        """Re-plan a robot's drive from its next step boundary at or after ``t``."""
        path = self.paths[robot]
        nxt = next((s for s in path if s.t >= t - EPS), path[-1])
        self.paths[robot] = [s for s in path if s.t <= nxt.t + EPS]
        self.moves = [m for m in self.moves if not (m.robot == robot and m.start >= nxt.t - EPS)]
        self.res.release_after(robot, nxt.t)
        self.res.add(robot, nxt.cell, nxt.t, INF)
        self.replans += 1
        return self.drive(robot, nxt.t, dt, goals)

    # ---- making way --------------------------------------------------------------------
    def blockers(self, robot: str, t: float, goals: Sequence[Pose]) -> list[str]:
        """Robots parked on ``robot``'s shortest way (ignoring everyone), in path order."""
        here = self.cell(robot, t).cell if self.end_time(robot) <= t else self.paths[robot][-1].cell
        path = search(None, self.nav, robot, here, t, 1.0, goals[:POSE_CHOICES])
        out: list[str] = []
        for s in path or ():
            who = self.res.parked_at(s.cell, t)
            if who is not None and who != robot and who not in out:
                out.append(who)
        return out

    def step_aside(self, robot: str, t: float, dt: float, keep_clear: set[Cell],
                   near: tuple[float, float] | None = None) -> list[Step] | None:
        """Move an idle ``robot`` to the nearest cell off ``keep_clear`` (another robot's
        way), one still within reach of ``near`` (what it works on) when there is one;
        ``None`` when there is no such cell it can reach."""
        here = self.cell(robot, t).cell
        target = self._free_cell_near(here, t, robot, avoid=keep_clear, near=near)
        if target is None:
            return None
        poses = [Pose(target, h) for h in range(4)]
        self.res.release_after(robot, t)
        path = search(self.res, self.nav, robot, here, t, dt, poses)
        if path is None:
            self.res.add(robot, here, t, INF)
            return None
        self._commit(robot, t, path)
        self.yields += 1
        return path

    def way_of(self, robot: str, t: float, goals: Sequence[Pose]) -> set[Cell]:
        here = self.cell(robot, t).cell
        path = search(None, self.nav, robot, here, t, 1.0, goals[:POSE_CHOICES])
        return {s.cell for s in path or ()}

    def _free_cell_near(self, cell: Cell, t: float, robot: str, avoid: set[Cell],
                        near: tuple[float, float] | None = None) -> Cell | None:
        """Breadth-first from ``cell``: the nearest cell not in ``avoid`` and free from ``t``
        on (moving through cells that are not parked on); with ``near``, the nearest such
        cell within reach of that point if any."""
        seen = {cell}
        frontier = [cell]
        fallback: Cell | None = None
        while frontier:
            nxt: list[Cell] = []
            for c in frontier:
                for n in self.nav.grid.neighbours(c):
                    if n in seen:
                        continue
                    seen.add(n)
                    if self.res.parked_at(n, t) not in (None, robot):
                        continue
                    if n not in avoid and self.res.free(n, t, INF, robot):
                        if near is None or _within_reach(n, near):
                            return n
                        fallback = fallback or n
                    nxt.append(n)
            frontier = nxt
        return fallback
