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

import heapq
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
#: a node is tried on its own robot and on this many others, those passing nearest
NEAR_ROBOTS = 3


@dataclass(frozen=True)
class Stop:
    """One step of a node: the thing it acts at (None: where the robot stands), the
    seconds it takes there, and whether a drive goes there whatever the reach."""

    step: str
    point: Point | None
    seconds: float
    forced: bool = False
    #: the interaction spot it holds (one robot at a time), if any
    spot: str | None = None


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
    #: (speed, from, to) -> (where the drive ends, its seconds): the search asks the same
    #: drives many times, and the navigation's own caches sit behind several calls
    drives: dict[tuple[float, Point, Point], tuple[Point, float]] = field(default_factory=dict)

    def drive(self, robot: str, here: Point, there: Point) -> tuple[Point, float]:
        """Where a drive from ``here`` to the thing at ``there`` ends, and its seconds."""
        key = (self.speeds[robot], here, there)
        found = self.drives.get(key)
        if found is None:
            seconds = navigation_seconds(here, there, key[0], self.floor_plan or None)
            end = arrival_point(self.floor_plan, here, there) if self.floor_plan else there
            found = self.drives[key] = (end, seconds)
        return found

    def stop(self, robot: str, here: Point, stop: Stop) -> tuple[Point, float]:
        """Where the robot stands after ``stop`` and the seconds it took (drive included)."""
        p = stop.point
        if p is None or (not stop.forced and math.hypot(p[0] - here[0], p[1] - here[1]) <= REACH):
            return here, stop.seconds
        end, seconds = self.drive(robot, here, p)
        return end, seconds + stop.seconds

    def walk(self, robot: str, here: Point, clock: float, nodes: Sequence[Node]) -> tuple[Point, float, int]:
        """Walk ``nodes`` from ``here`` at ``clock``: the end point, the clock, stops walked."""
        n = 0
        for node in nodes:
            for s in node.stops:
                here, dt = self.stop(robot, here, s)
                clock += dt
            n += len(node.stops)
        return here, clock, n

#: a stop as a robot walks it: where the robot stands after it, and the seconds
#: :meth:`Walker.stop` gives it (the drive there included)
Leg = tuple[Point, float]


@dataclass
class _Clock:
    """One robot in :func:`timetable`: its stops and their legs, the next one, and when
    it is free."""

    stops: Sequence[Stop]
    legs: Sequence[Leg]
    free: float = 0.0
    next: int = 0


def legs_of(walker: Walker, robot: str, stops: Sequence[Stop]) -> list[Leg]:
    """The legs of ``robot`` walking ``stops`` from its start: a robot's legs depend on
    its own route alone (where it stands comes from its own stops), never on the others'."""
    here = walker.starts[robot]
    out: list[Leg] = []
    for st in stops:
        here, dt = walker.stop(robot, here, st)
        out.append((here, dt))
    return out


@dataclass(frozen=True)
class Prepared:
    """What :func:`timetable` reads that a search over one plan's routes shares across
    the thousands of orders it times: how many stops each stop waits for, the stops
    waiting for each one (both from the waits alone), and each route walked so far
    (robot and its node ids -> its stops and legs: a change moves two routes, and the
    other robots' legs are the ones walked before)."""

    counts: dict[str, int]
    waiters: dict[str, tuple[str, ...]]
    walked: dict[tuple[str, tuple[str, ...]], tuple[list[Stop], list[Leg]]] = field(default_factory=dict)

    @classmethod
    def of(cls, stops: Sequence[str], waits: Mapping[str, frozenset[str]]) -> Prepared:
        waiters: dict[str, list[str]] = {}
        for s in stops:
            for p in waits.get(s, ()):
                waiters.setdefault(p, []).append(s)
        return cls({s: len(waits.get(s, ())) for s in stops}, {p: tuple(v) for p, v in waiters.items()})

    def route(self, walker: Walker, nodes: Mapping[str, Node], robot: str, route: Sequence[str]
              ) -> tuple[list[Stop], list[Leg]]:
        key = (robot, tuple(route))
        found = self.walked.get(key)
        if found is None:
            stops = [st for nid in route for st in nodes[nid].stops]
            found = self.walked[key] = (stops, legs_of(walker, robot, stops))
        return found


def timetable(walker: Walker, nodes: Mapping[str, Node], order: Mapping[str, Sequence[str]],
              waits: Mapping[str, frozenset[str]], prepared: Prepared | None = None
              ) -> tuple[dict[str, float], dict[str, float], int] | None:
    """Walk every route at once, stop by stop, as the simulator runs a plan: the robot
    that arrives first at a stop it may start goes next (ties: by name); a stop starts
    when its robot has driven there, the stops it waits for (``waits``: step id -> step
    ids, on any robot) have ended and nobody else is at its spot. Each stop's start (step
    id -> seconds), each robot's end, the stops walked; None when the routes wait on each
    other in a circle. ``prepared``: :meth:`Prepared.of` the routes' stops and ``waits``
    (made here when not given; a search passes its own, the same for every order of the
    same stops).

    Event-driven (a heap of the robots whose next stop may start, keyed by arrival and
    name; a robot whose next stop waits joins it when the last stop it waits for ends):
    the same choices as scanning every robot at each stop, in O(stops log robots), which
    the search over a 32-robot, 230-step plan needs (it prices thousands of changes)."""
    if prepared is None:
        stops = {r: [st for nid in order[r] for st in nodes[nid].stops] for r in order}
        prepared = Prepared.of([st.step for r in order for st in stops[r]], waits)
        clocks = {r: _Clock(stops[r], legs_of(walker, r, stops[r])) for r in order}
    else:
        clocks = {r: _Clock(*prepared.route(walker, nodes, r, order[r])) for r in order}
    robot_of = {st.step: r for r, c in clocks.items() for st in c.stops}
    missing = dict(prepared.counts)
    waiters = prepared.waiters
    ready: list[tuple[float, str, Point]] = []
    for r, c in sorted(clocks.items()):
        _queue(ready, r, c, missing)
    ends: dict[str, float] = {}
    spots: dict[str, float] = {}
    starts: dict[str, float] = {}
    no_wait: frozenset[str] = frozenset()
    while ready:
        arrival, r, _ = heapq.heappop(ready)
        c = clocks[r]
        st = c.stops[c.next]
        # the latest of the arrival, the spot's release and the waits' ends (the first
        # of equal values, as max() takes it)
        start = arrival
        if st.spot is not None and spots.get(st.spot, 0.0) > start:
            start = spots[st.spot]
        for p in waits.get(st.step, no_wait):
            if ends[p] > start:
                start = ends[p]
        end = start + st.seconds
        starts[st.step], ends[st.step] = start, end
        if st.spot is not None:
            spots[st.spot] = end
        c.free, c.next = end, c.next + 1
        _queue(ready, r, c, missing)
        for s in waiters.get(st.step, ()):
            missing[s] -= 1
            if missing[s] == 0:
                other = clocks[robot_of[s]]
                if other.stops[other.next].step == s:
                    _queue(ready, robot_of[s], other, missing)
    if len(starts) < len(missing):
        return None
    return starts, {r: c.free for r, c in clocks.items()}, len(starts)


def _queue(ready: list[tuple[float, str, Point]], robot: str, c: _Clock, missing: Mapping[str, int]) -> None:
    """Put the robot on the heap when its next stop waits for nothing unfinished: keyed
    by when it arrives there (driving first) and its name, with where it will stand."""
    if c.next < len(c.stops) and missing[c.stops[c.next].step] == 0:
        st = c.stops[c.next]
        here, dt = c.legs[c.next]
        heapq.heappush(ready, (c.free + dt - st.seconds, robot, here))


@dataclass
class Routes:
    """Each robot's route (node ids in order). A change whose routes wait for no other
    robot's nodes (nor are waited for) is priced route by route, from each walked prefix
    (point and clock after each node); any other by the whole :func:`timetable`."""

    walker: Walker
    nodes: Mapping[str, Node]
    #: step -> the steps it waits for (on any robot), as :func:`timetable` takes them
    waits: Mapping[str, frozenset[str]]
    order: dict[str, list[str]]
    walked: int = 0
    prefix: dict[str, list[tuple[Point, float]]] = field(default_factory=dict)
    ends: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        node_of = {st.step: n.id for n in self.nodes.values() for st in n.stops}
        #: (a, b): node b waits for node a (on one robot, a comes first)
        self.before = frozenset((node_of[p], node_of[s]) for s, ps in self.waits.items() for p in ps
                                if node_of[p] != node_of[s])
        #: node -> the nodes it waits for or that wait for it
        self.partners: dict[str, set[str]] = {n: set() for n in self.nodes}
        for a, b in self.before:
            self.partners[a].add(b)
            self.partners[b].add(a)
        #: the waits as :func:`timetable` reads them, for the routes' stops (which every
        #: change only moves: a change's routes hold the same nodes)
        self._last: tuple[tuple[tuple[str, ...], ...], tuple[dict[str, float], dict[str, float], int] | None] | None \
            = None
        self.prepared = Prepared.of([st.step for route in self.order.values() for nid in route
                                   for st in self.nodes[nid].stops], self.waits)
        self.apply(dict(self.order))

    def timetable(self, order: Mapping[str, Sequence[str]] | None = None
                  ) -> tuple[dict[str, float], dict[str, float], int] | None:
        """:func:`timetable` of these routes (or of ``order``: the same nodes, moved). The
        last one is kept: a change is timed when it is priced, again when it is applied,
        and the search times the routes it made once more (copies handed out: callers
        keep and change the dictionaries)."""
        order = self.order if order is None else order
        key = tuple((r, *route) for r, route in order.items())
        if self._last is None or self._last[0] != key:
            self._last = (key, timetable(self.walker, self.nodes, order, self.waits, self.prepared))
        found = self._last[1]
        return None if found is None else (dict(found[0]), dict(found[1]), found[2])

    def _alone(self, change: Mapping[str, list[str]]) -> bool:
        """No node of the changed routes waits for, or is waited for by, a node on another
        robot once ``change`` is made: each changed route is priced alone."""
        robot_of = {x: r for r, route in self.order.items() for x in route}
        robot_of.update({x: r for r, route in change.items() for x in route})
        return all(robot_of[p] == r for r, route in change.items() for x in route for p in self.partners[x])

    def _refresh(self, robot: str) -> None:
        here, clock = self.walker.starts[robot], 0.0
        out = [(here, clock)]
        for nid in self.order[robot]:
            here, clock, n = self.walker.walk(robot, here, clock, [self.nodes[nid]])
            self.walked += n
            out.append((here, clock))
        self.prefix[robot] = out
        self.ends[robot] = clock

    def cost(self) -> tuple[float, float]:
        """(makespan, sum of the robots' ends): what the search minimises, in that order."""
        return (max(self.ends.values(), default=0.0), sum(self.ends.values()))

    def price(self, change: Mapping[str, list[str]]) -> tuple[float, float] | None:
        """The cost with ``change`` made (None: the routes would wait in a circle)."""
        ends = self.ends_with(change)
        if ends is None:
            return None
        return (max(ends.values(), default=0.0), sum(ends.values()))

    def ends_with(self, change: Mapping[str, list[str]]) -> dict[str, float] | None:
        """Each robot's end with ``change`` made (None: the routes would wait in a circle)."""
        if not self._alone(change):
            found = self.timetable({**self.order, **change})
            if found is None:
                return None
            self.walked += found[2]
            return found[1]
        ends = dict(self.ends)
        for r, route in change.items():
            here, clock = self.prefix[r][same := _first_common(self.order[r], route)]
            _, ends[r], n = self.walker.walk(r, here, clock, [self.nodes[x] for x in route[same:]])
            self.walked += n
        return ends

    def keeps_order(self, route: Sequence[str]) -> bool:
        pos = {x: i for i, x in enumerate(route)}
        return all(pos[a] < pos[b] for a, b in self.before if a in pos and b in pos)

    def apply(self, changed: Mapping[str, list[str]]) -> None:
        for r, route in changed.items():
            self.order[r] = route
            self._refresh(r)
        if self.before:
            found = self.timetable()
            assert found is not None, "a change was applied that waits in a circle"
            self.ends = found[1]


def nearest_robots(routes: Routes, nid: str, home: str) -> list[str]:
    """The robot of node ``nid`` and the :data:`NEAR_ROBOTS` others able to do it whose
    routes come nearest to it (its first stop against their start and stops, straight
    line), nearest first: a node is tried where a robot passes by, not on every robot."""
    first = next((s.point for s in routes.nodes[nid].stops if s.point is not None), None)
    others = [r for r in routes.nodes[nid].robots if r != home and r in routes.order]
    if first is None or len(others) <= NEAR_ROBOTS:
        return [home, *others]

    def gap(robot: str) -> float:
        points = [routes.walker.starts[robot], *(s.point for x in routes.order[robot]
                                                 for s in routes.nodes[x].stops if s.point is not None)]
        return min(math.hypot(p[0] - first[0], p[1] - first[1]) for p in points)

    return [home, *sorted(others, key=lambda r: (gap(r), r))[:NEAR_ROBOTS]]


def _relocations(routes: Routes, nid: str, home: str) -> list[dict[str, list[str]]]:
    """Every route change that moves node ``nid`` elsewhere (same robot or a near one)."""
    out: list[dict[str, list[str]]] = []
    rest = [x for x in routes.order[home] if x != nid]
    for robot in nearest_robots(routes, nid, home):
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
    for robot in nearest_robots(routes, nid, home)[1:]:
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
    best = routes.cost()
    for change in changes:
        if routes.walked >= budget:
            return False
        if not all(routes.keeps_order(route) for route in change.values()):
            continue
        priced = routes.price(change)
        if priced is not None and better(priced, best):
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
            if any(_try(routes, moves(routes, nid, home), budget) for moves in (_relocations, _swaps)):
                improved = True
    return routes
