"""Robots' routes over a plan's jobs, priced as the simulator drives them, and a local
search that shortens them (issue 28: the heuristic's gap to CP-SAT's optimum).

A *node* is a block of one robot's work that moves as a whole (the jobs of one subtask:
:mod:`emboteam.hp.optimal`'s groups); its *stops* are what it does in order: an
operation at a thing, reached by a drive only when the thing is out of reach from where
the robot stands, or a drive the plan makes whatever the reach (to a garbage can before
a throw). A route is priced by *walking* it as :mod:`emboteam.sim.rules` moves a robot:
a drive ends on the thing's pose nearest to where the robot came from
(:func:`emboteam.world.navigation.arrival_point`), so the price of a job depends on where
the robot was before it. CP-SAT's model prices a job from one fixed place, and its better
orders simulated longer once rebuilt (docs/planning.md); this walk is what the rebuild
(:mod:`emboteam.hp.stages.route`, which plans the drives again) will do.

The search relocates nodes (to another place in the route, or to another robot able to
do them) and swaps pairs, first improvement, minimising the longest route and then the
sum of routes; an order two nodes of a robot must keep (one needs what the other does)
is kept. Its budget counts stops walked, never seconds: the same input, the same routes.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from emboteam.sim.durations import navigation_seconds
from emboteam.world.navigation import arrival_point
from emboteam.world.state import REACH

Point = tuple[float, float]

#: stops walked by one search at most (a count, so the routes never depend on the clock);
#: a 2-robot, 32-goal cell's search walks about a tenth of it
WALK_BUDGET = 400_000


@dataclass(frozen=True)
class Stop:
    """One step of a node: the thing it acts at (None: where the robot stands), the
    seconds it takes there, and whether a drive goes there whatever the reach."""

    step: str
    point: Point | None
    seconds: float
    forced: bool = False


@dataclass(frozen=True)
class Node:
    """A block that moves as a whole: its stops in order and the robots that may do it."""

    id: str
    stops: tuple[Stop, ...]
    robots: tuple[str, ...]


@dataclass(frozen=True)
class Walker:
    """Drives on one floor plan at each robot's speed (the simulator's navigation)."""

    floor_plan: str
    speeds: Mapping[str, float]
    starts: Mapping[str, Point]

    def stop(self, robot: str, here: Point, stop: Stop) -> tuple[Point, float]:
        """Where the robot stands after ``stop`` and the seconds it took (drive included)."""
        p = stop.point
        if p is None or (not stop.forced and math.hypot(p[0] - here[0], p[1] - here[1]) <= REACH):
            return here, stop.seconds
        drive = navigation_seconds(here, p, self.speeds[robot], self.floor_plan or None)
        return arrival_point(self.floor_plan, here, p) if self.floor_plan else p, drive + stop.seconds

    def walk(self, robot: str, here: Point, clock: float, nodes: Sequence[Node]) -> tuple[Point, float, int]:
        """Walk ``nodes`` from ``here`` at ``clock``: the end point, the clock, stops walked."""
        n = 0
        for node in nodes:
            for s in node.stops:
                here, dt = self.stop(robot, here, s)
                clock += dt
            n += len(node.stops)
        return here, clock, n

    def times(self, robot: str, nodes: Sequence[Node]) -> dict[str, float]:
        """Each stop's start (step id -> seconds from the route's start, the drive to it
        before it)."""
        here, clock = self.starts[robot], 0.0
        out: dict[str, float] = {}
        for node in nodes:
            for s in node.stops:
                here, dt = self.stop(robot, here, s)
                out[s.step] = clock + dt - s.seconds
                clock += dt
        return out


@dataclass
class Routes:
    """Each robot's route (node ids in order), with its walked prefix (point and clock after
    each node) kept for cheap evaluation of a change."""

    walker: Walker
    nodes: Mapping[str, Node]
    #: (a, b): when a and b are on one robot, a comes first
    before: frozenset[tuple[str, str]]
    order: dict[str, list[str]]
    walked: int = 0
    prefix: dict[str, list[tuple[Point, float]]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for r in self.order:
            self._refresh(r)

    def _refresh(self, robot: str) -> None:
        here, clock = self.walker.starts[robot], 0.0
        out = [(here, clock)]
        for nid in self.order[robot]:
            here, clock, n = self.walker.walk(robot, here, clock, [self.nodes[nid]])
            self.walked += n
            out.append((here, clock))
        self.prefix[robot] = out

    def length(self, robot: str) -> float:
        return self.prefix[robot][-1][1]

    def cost(self) -> tuple[float, float]:
        """(longest route, sum of routes): what the search minimises, in that order."""
        lengths = [self.length(r) for r in self.order]
        return (max(lengths, default=0.0), sum(lengths))

    def priced(self, robot: str, route: Sequence[str], same_from: int) -> float:
        """The length of ``route`` for ``robot``, walking only from position ``same_from``
        (the prefix up to there is that of its current route)."""
        here, clock = self.prefix[robot][same_from]
        _, clock, n = self.walker.walk(robot, here, clock, [self.nodes[x] for x in route[same_from:]])
        self.walked += n
        return clock

    def keeps_order(self, route: Sequence[str]) -> bool:
        pos = {x: i for i, x in enumerate(route)}
        return all(pos[a] < pos[b] for a, b in self.before if a in pos and b in pos)

    def apply(self, changed: Mapping[str, list[str]]) -> None:
        for r, route in changed.items():
            self.order[r] = route
            self._refresh(r)


def _with(lengths: Mapping[str, float], changed: Mapping[str, float]) -> tuple[float, float]:
    values = [changed.get(r, v) for r, v in lengths.items()]
    return (max(values, default=0.0), sum(values))


def _relocations(routes: Routes, nid: str, home: str) -> list[dict[str, list[str]]]:
    """Every route change that moves node ``nid`` elsewhere (same robot or another)."""
    out: list[dict[str, list[str]]] = []
    rest = [x for x in routes.order[home] if x != nid]
    for robot in routes.nodes[nid].robots:
        if robot not in routes.order:
            continue
        base = rest if robot == home else routes.order[robot]
        for i in range(len(base) + 1):
            route = [*base[:i], nid, *base[i:]]
            if robot == home and route == routes.order[home]:
                continue
            out.append({robot: route} if robot == home else {home: rest, robot: route})
    return out


def _swaps(routes: Routes, nid: str, home: str) -> list[dict[str, list[str]]]:
    """Every exchange of node ``nid`` with a node of another robot both may do."""
    out: list[dict[str, list[str]]] = []
    i = routes.order[home].index(nid)
    for robot in routes.nodes[nid].robots:
        if robot == home or robot not in routes.order:
            continue
        for j, other in enumerate(routes.order[robot]):
            if home not in routes.nodes[other].robots:
                continue
            mine, theirs = list(routes.order[home]), list(routes.order[robot])
            mine[i], theirs[j] = other, nid
            out.append({home: mine, robot: theirs})
    return out


def better(new: tuple[float, float], old: tuple[float, float], eps: float = 1e-6) -> bool:
    """A shorter longest route, or as long a one and a shorter sum."""
    return new[0] < old[0] - eps or (abs(new[0] - old[0]) <= eps and new[1] < old[1] - eps)


def _first_common(a: Sequence[str], b: Sequence[str]) -> int:
    k = 0
    while k < min(len(a), len(b)) and a[k] == b[k]:
        k += 1
    return k


def _try(routes: Routes, changes: list[dict[str, list[str]]], budget: int) -> bool:
    """Apply the first change that lowers the cost; False when none does (or the budget
    ran out)."""
    lengths = {r: routes.length(r) for r in routes.order}
    best = routes.cost()
    for change in changes:
        if routes.walked >= budget:
            return False
        if not all(routes.keeps_order(route) for route in change.values()):
            continue
        priced = {r: routes.priced(r, route, _first_common(routes.order[r], route)) for r, route in change.items()}
        if better(_with(lengths, priced), best):
            routes.apply(change)
            return True
    return False


def improve(routes: Routes, budget: int = WALK_BUDGET) -> Routes:
    """Relocate and swap nodes while that shortens the routes (first improvement, nodes in
    a fixed order), until no move helps or ``budget`` stops have been walked."""
    improved = True
    while improved and routes.walked < budget:
        improved = False
        for nid in sorted(routes.nodes):
            home = next(r for r, route in routes.order.items() if nid in route)
            if _try(routes, _relocations(routes, nid, home), budget) or _try(
                    routes, _swaps(routes, nid, home), budget):
                improved = True
    return routes
