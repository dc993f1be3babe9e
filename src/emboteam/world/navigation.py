"""Shortest drives on a floor plan's navigation grid, and how many agent actions they take.

A robot moves as AI2-THOR's agent does: MoveAhead (0.25 m) along its heading and
RotateLeft/RotateRight (90°), each one agent action. A drive ends at the target's
interaction pose (:mod:`emboteam.world.poses`), facing it. The heading a robot sets off
with is not tracked (its first rotation overlaps the end of its previous action), so a
drive costs its moves, the turns along the way and the final turn to face the target.

The search is a breadth-first search written here rather than a graph library's call:
every action costs the same, the state graph is small (at most ~500 cells x 4 headings),
and one search from a pose answers every start at once; the table is cached per pose, so
the planner's cost model, its resource-aware bound and the simulator read the same
distances at a dictionary lookup each (networkx is not a dependency of the package, and a
breadth-first search is a dozen lines).
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass
from functools import cache, lru_cache

from emboteam.errors import EmboTeamError
from emboteam.world.navgrid import STEPS, Cell, NavGrid, load_grid
from emboteam.world.poses import Pose, candidate_poses
from emboteam.world.scene import SceneObject, load_scene

State = tuple[Cell, int]
#: a drive ends at the nearest of this many best poses of its target (a robot already
#: standing next to the thing need not walk round to its preferred side)
POSE_CHOICES = 4


#: :meth:`Navigator.actions_to`'s memo: a missing answer, and at most this many kept
_UNKNOWN = object()
_ACTIONS_KEPT = 1 << 18


class Navigator:
    """Poses, drive lengths and paths on one floor plan (use :func:`navigator`)."""

    def __init__(self, floor_plan: str) -> None:
        self.floor_plan = floor_plan
        self.grid: NavGrid = load_grid(floor_plan)
        scene = load_scene(floor_plan)
        #: ALFRED keys its openable poses by AI2-THOR id; the symbolic state knows points
        self._thor_at = {(round(o.position[0], 3), round(o.position[2], 3)): key
                         for o in scene.objects if (key := alfred_key(o, self.grid)) is not None}
        #: :meth:`actions_to`'s answers by (start, goal cell, goal heading): every simulated
        #: drive and every cold drive estimate asks it, the same few thousand pairs a plan
        self._actions: dict[tuple[Cell, Cell, int], int | None] = {}

    # ---- poses -------------------------------------------------------------------------
    def poses_for(self, point: tuple[float, float]) -> tuple[Pose, ...]:
        """Poses to act on the thing at ``point``, best first (empty: out of every reach)."""
        key = (round(point[0], 3), round(point[1], 3))
        return candidate_poses(self.grid, key, self._thor_at.get(key))

    def pose_for(self, point: tuple[float, float]) -> Pose | None:
        poses = self.poses_for(point)
        return poses[0] if poses else None

    def cell_of(self, point: tuple[float, float]) -> Cell:
        """The cell a robot at ``point`` stands on: the cell itself, or, for a robot the
        symbolic state puts at an object's point (the planner's replay does), that
        object's pose cell, else the nearest cell."""
        exact = self.grid.cell_at(point)
        if exact is not None:
            return exact
        pose = self.pose_for(point)
        return pose.cell if pose is not None else self.grid.nearest(point)

    # ---- distances and paths -----------------------------------------------------------
    def nearest_pose(self, start: Cell, point: tuple[float, float]) -> tuple[Pose, int] | None:
        """Of the :data:`POSE_CHOICES` best poses for the thing at ``point``, the one
        reached in the fewest actions from ``start`` (ties: the better pose), with that count."""
        best: tuple[Pose, int] | None = None
        for pose in self.poses_for(point)[:POSE_CHOICES]:
            n = self.actions_to(start, pose)
            if n is not None and (best is None or n < best[1]):
                best = (pose, n)
        return best

    def actions_to(self, start: Cell, pose: Pose) -> int | None:
        """Agent actions from ``start`` (any heading) to ``pose``; ``None`` if unreachable.
        Kept by plain tuples (a pure function of the grid): a hit hashes no :class:`Pose`
        and asks no table (issue 28: some 8,000 calls in the 32 x 96 cell's plan)."""
        key = (start, pose.cell, pose.heading)
        known = self._actions.get(key, _UNKNOWN)
        if known is not _UNKNOWN:
            return known  # type: ignore[return-value]
        table = cost_table(self.floor_plan, pose)
        best = [d for h in range(4) if (d := table.get((start, h))) is not None]
        found = min(best) if best else None
        if len(self._actions) >= _ACTIONS_KEPT:
            self._actions.clear()  # a bound on memory in a long-lived process; answers stay the same
        self._actions[key] = found
        return found

    def travel_actions(self, a: tuple[float, float], b: tuple[float, float]) -> int | None:
        """Agent actions for a robot at point ``a`` to reach the nearest pose of the thing at
        ``b`` (:meth:`nearest_pose`)."""
        return _travel_points(self.floor_plan, tuple(a), tuple(b))  # hashable whatever the caller passes

    def path(self, start: Cell, pose: Pose) -> list[State] | None:
        """The states (cell, heading) of a shortest drive, start and end included; each
        consecutive pair is one action (a move or a 90° turn). Cached."""
        found = _path(self.floor_plan, start, pose)
        return list(found) if found is not None else None


@lru_cache(maxsize=65536)
def _path(floor_plan: str, start: Cell, pose: Pose) -> tuple[State, ...] | None:
    table = cost_table(floor_plan, pose)
    options = [(d, h) for h in range(4) if (d := table.get((start, h))) is not None]
    if not options:
        return None
    grid = load_grid(floor_plan)
    d, h = min(options)
    state: State = (start, h)
    out = [state]
    while d > 0:
        for nxt in _successors(grid, state):
            if table.get(nxt) == d - 1:
                state, d = nxt, d - 1
                out.append(state)
                break
    return tuple(out)


#: an AI2-THOR 2.1 object id still names a 5.x object of its type this close (m): ids
#: encode positions, and some objects moved by a few centimetres between versions
ID_DRIFT = 0.1


def alfred_key(obj: SceneObject, grid: NavGrid) -> str | None:
    """The ALFRED openable-pose key of a scene object: its own AI2-THOR id, or the id of
    the same type whose encoded position lies within :data:`ID_DRIFT` of it."""
    if obj.thor_id in grid.openable:
        return obj.thor_id
    best: tuple[float, str] | None = None
    for key in grid.openable:
        parts = key.split("|")
        if len(parts) < 4 or (parts[-1] != obj.type and not (len(parts) == 4 and parts[0] == obj.type)):
            continue
        try:
            x, y, z = (float(v) for v in parts[1:4])
        except ValueError:
            continue
        d = math.dist((x, y, z), obj.position)
        if d <= ID_DRIFT and (best is None or d < best[0]):
            best = (d, key)
    return best[1] if best else None


def _successors(grid: NavGrid, state: State) -> list[State]:
    """States one action away: MoveAhead (if the next cell is reachable), then turns."""
    (i, j), h = state
    di, dj = STEPS[h]
    out: list[State] = []
    if (i + di, j + dj) in grid.cells:
        out.append(((i + di, j + dj), h))
    out.append(((i, j), (h + 1) % 4))
    out.append(((i, j), (h + 3) % 4))
    return out


@lru_cache(maxsize=4096)
def cost_table(floor_plan: str, goal: Pose) -> dict[State, int]:
    """Actions from every state to ``goal``: a breadth-first search over reversed actions
    (a move's predecessor is one cell back along the same heading; turns reverse).

    The search runs on the floor plan's state graph numbered once (:func:`_reverse_graph`):
    a list of distances indexed by state, not a dictionary of tuples, since a cold planning
    call builds a hundred of these tables. The states are visited in the same order as a
    search over the tuples, so the table is the same, entry for entry."""
    graph = _reverse_graph(floor_plan)
    start = graph.index.get((goal.cell, goal.heading))
    if start is None:
        return _table_off_grid(floor_plan, goal)
    preds = graph.preds
    dist = [-1] * len(preds)
    dist[start] = 0
    order = [start]
    for k in order:  # the list grows as it is read: a FIFO queue
        d = dist[k] + 1
        for p in preds[k]:
            if dist[p] < 0:
                dist[p] = d
                order.append(p)
    states = graph.states
    return {states[k]: dist[k] for k in order}


@dataclass(frozen=True)
class _ReverseGraph:
    """A floor plan's states (cell, heading), numbered, and each one's predecessors (the
    states one action before it: the two turns, then the move from one cell back)."""

    states: tuple[State, ...]
    index: dict[State, int]
    preds: tuple[tuple[int, ...], ...]


@cache
def _reverse_graph(floor_plan: str) -> _ReverseGraph:
    grid = load_grid(floor_plan)
    states = tuple((c, h) for c in grid.ordered for h in range(4))
    index = {s: k for k, s in enumerate(states)}
    preds = []
    for (i, j), h in states:
        di, dj = STEPS[h]
        ks = [index[((i, j), (h + 1) % 4)], index[((i, j), (h + 3) % 4)]]
        back = index.get(((i - di, j - dj), h))
        if back is not None:
            ks.append(back)
        preds.append(tuple(ks))
    return _ReverseGraph(states, index, tuple(preds))


def _table_off_grid(floor_plan: str, goal: Pose) -> dict[State, int]:
    """:func:`cost_table` for a goal cell that is not on the grid (a pose made by hand):
    the same search on tuples, since such a state has no number."""
    grid = load_grid(floor_plan)
    start: State = (goal.cell, goal.heading)
    dist = {start: 0}
    queue = deque([start])
    while queue:
        state = queue.popleft()
        (i, j), h = state
        d = dist[state] + 1
        di, dj = STEPS[h]
        back = (i - di, j - dj)
        preds = [((i, j), (h + 1) % 4), ((i, j), (h + 3) % 4)]
        if back in grid.cells:
            preds.append((back, h))
        for p in preds:
            if p not in dist:
                dist[p] = d
                queue.append(p)
    return dist


@lru_cache(maxsize=262144)
def _travel_points(floor_plan: str, a: tuple[float, float], b: tuple[float, float]) -> int | None:
    """:func:`_travel` by the points as given: the planner's cost model asks the same pairs
    thousands of times a plan, and a hit here is one lookup, with no rounding."""
    return _travel(floor_plan, round(a[0], 3), round(a[1], 3), round(b[0], 3), round(b[1], 3))


@lru_cache(maxsize=262144)
def _travel(floor_plan: str, ax: float, az: float, bx: float, bz: float) -> int | None:
    nav = navigator(floor_plan)
    best = nav.nearest_pose(nav.cell_of((ax, az)), (bx, bz))
    return best[1] if best is not None else None


@lru_cache(maxsize=262144)
def arrival_point(floor_plan: str, here: tuple[float, float], there: tuple[float, float]) -> tuple[float, float]:
    """Where a robot at ``here`` ends a drive to the thing at ``there`` when nobody is in
    the way: the cell of its nearest pose (``there`` itself when it has none)."""
    try:
        nav = navigator(floor_plan)
    except EmboTeamError:
        return there
    best = nav.nearest_pose(nav.cell_of(here), there)
    return NavGrid.point(best[0].cell) if best is not None else there


@cache
def navigator(floor_plan: str) -> Navigator:
    """The (cached) navigator of a floor plan."""
    return Navigator(floor_plan)
