"""A cheaper route search for large plans: only the jobs of the robots that end last
move (issue 28: the 8- and 32-robot, 96-goal cells, plans of 200+ steps, where one
robot's long cluster makes the makespan while others stand idle).

:func:`emboteam.hp.routes.improve` tries every job everywhere, which walks hundreds of
thousands of stops on such a plan (5 s here); most of those moves cannot lower the
makespan, since they do not touch the robots that end last. Here each step asks only:
which job of one of the :data:`LATE_ROBOTS` robots that end last (latest first; its
jobs from its last to its first) can go elsewhere, into another robot's route or another
place in its own, so that the routes, walked together, end earlier. The routes' ends
are compared latest first (the makespan, then the next robot's end, ...): a move that
shortens the second-latest robot counts, so a robot that ties the makespan does not
stop the search. First improvement; the budget counts stops walked, never seconds.
"""

from __future__ import annotations

import bisect
from collections.abc import Mapping

from emboteam.hp.routes import Routes, nearest_robots

#: robots whose jobs are tried, those that end last (each of them may hold the makespan
#: after the next move)
LATE_ROBOTS = 3
#: robots tried for a job besides the nearest ones: those whose routes end earliest
#: (an idle robot far away may still be the one with time to spare)
EARLIEST_ROBOTS = 4

Ends = tuple[float, ...]


def _key(ends: Mapping[str, float]) -> Ends:
    """The ends latest first: what the search lowers, in that order."""
    return tuple(sorted(ends.values(), reverse=True))


def _earlier(new: Ends, old: Ends, eps: float = 1e-6) -> bool:
    """``new`` ends earlier: at the first end that differs by more than ``eps``."""
    for a, b in zip(new, old, strict=True):
        if a < b - eps:
            return True
        if a > b + eps:
            return False
    return False


def _late(routes: Routes) -> list[str]:
    """The :data:`LATE_ROBOTS` robots that end last, latest first (ties: by name)."""
    return sorted(routes.ends, key=lambda r: (-routes.ends[r], r))[:LATE_ROBOTS]


def _targets(routes: Routes, nid: str, home: str) -> list[str]:
    """The robots a job of ``home`` is tried on: ``home`` itself, the nearest able ones
    and the able ones whose routes end earliest, without repeats, in that order."""
    near = nearest_robots(routes, nid, home)
    able = [r for r in routes.nodes[nid].robots if r in routes.order and r not in near]
    early = sorted(able, key=lambda r: (routes.ends[r], r))[:EARLIEST_ROBOTS]
    return [*near, *early]


def _moves(routes: Routes, nid: str, home: str, starts: Mapping[str, float]) -> list[dict[str, list[str]]]:
    """The changes that hand job ``nid`` to another robot: into each target's route where
    its jobs start around the time ``nid`` starts now (the place before and after), not
    at every place (each try walks the whole plan)."""
    rest = [x for x in routes.order[home] if x != nid]
    when = starts[routes.nodes[nid].stops[0].step]
    out: list[dict[str, list[str]]] = []
    for robot in _targets(routes, nid, home)[1:]:
        base = routes.order[robot]
        at = bisect.bisect([starts[routes.nodes[x].stops[0].step] for x in base], when)
        for i in sorted({max(at - 1, 0), at, min(at + 1, len(base))}):
            out.append({home: rest, robot: [*base[:i], nid, *base[i:]]})
    return out


def _first_earlier(routes: Routes, changes: list[dict[str, list[str]]], budget: int) -> bool:
    """Apply the first change whose routes end earlier; False when none does (or the
    budget ran out)."""
    best = _key(routes.ends)
    for change in changes:
        if routes.walked >= budget:
            return False
        if not all(routes.keeps_order(route) for route in change.values()):
            continue
        ends = routes.ends_with(change)
        if ends is not None and _earlier(_key(ends), best):
            routes.apply(change)
            return True
    return False


def improve_late(routes: Routes, budget: int) -> Routes:
    """Move jobs off the robots that end last while that ends the routes earlier, until
    no such job can go anywhere better or ``budget`` stops have been walked."""
    while routes.walked < budget:
        found = routes.timetable()
        if found is None:
            break
        routes.walked += found[2]
        if not any(_first_earlier(routes, _moves(routes, nid, home, found[0]), budget)
                   for home in _late(routes) for nid in reversed(routes.order[home]) if routes.nodes[nid].stops):
            break
    return routes
