"""Goals walled off by broken-down robots.

A robot that breaks down keeps its grid cell for good (:mod:`emboteam.sim.traffic`). When
it stands in the only way into a corner (FloorPlan201's one-cell corridor to the spot by
the window), everything beyond it is out of reach of the robots left, although the
planner, whose drive costs ignore other robots, still finds a plan. Without this check the
team drove at the wall until the replan budget ran out and the episode ended ``failed``
with no error, and the ceiling called the task savable.

:func:`check_not_walled_off` is the planner's missing piece: before replanning (and in the
benchmark's ceiling) it floods the grid from the working robots' cells, past every cell but
the broken robots', and raises :class:`WalledOffError` (an :class:`ImpossibleGoalError`, so
the executor ends the run ``unsavable`` at once with a typed error) when an unmet goal
condition can only be met with objects no working robot can stand within reach of. It only
claims what is certain: an object counts as reachable when any of its interaction poses is.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from emboteam.pddl.errors import ImpossibleGoalError
from emboteam.world.catalogue import place_types
from emboteam.world.checker import check_condition, matches
from emboteam.world.goals import Condition, Goal, ObjectRef
from emboteam.world.navgrid import Cell
from emboteam.world.navigation import Navigator, navigator
from emboteam.world.state import WorldState


class WalledOffError(ImpossibleGoalError):
    """Broken-down robots stand in the only way to what an unmet goal condition needs."""


def _flood(nav: Navigator, starts: Iterable[Cell], walls: set[Cell]) -> set[Cell]:
    """Grid cells reachable from ``starts`` without entering ``walls``."""
    seen = {c for c in starts if c not in walls}
    stack = list(seen)
    while stack:
        for n in nav.grid.neighbours(stack.pop()):
            if n not in seen and n not in walls:
                seen.add(n)
                stack.append(n)
    return seen


class _Reach:
    """Which objects the working robots can stand within reach of."""

    def __init__(self, state: WorldState, robots: Sequence[str]) -> None:
        self.state = state
        self.nav = navigator(state.floor_plan)
        self.working = set(robots)
        down = [r for r in state.robots.values() if r.down]
        self.walls = {self.nav.cell_of(r.position) for r in down}
        self.blockers = sorted(r.name for r in down)
        starts = [self.nav.cell_of(state.robots[r].position) for r in robots if r in state.robots]
        self.cells = _flood(self.nav, starts, self.walls)

    def reachable(self, object_id: str) -> bool:
        o = self.state.objects[object_id]
        if o.held_by is not None:
            return o.held_by in self.working
        point = (o.position[0], o.position[2])
        return any(p.cell in self.cells for p in self.nav.poses_for(point))

    def candidates(self, ref: ObjectRef) -> list[str]:
        return [o.id for o in self.state.objects.values() if not o.gone and matches(ref, o, self.state)]


def _why_walled(cond: Condition, reach: _Reach) -> str | None:
    """Why ``cond`` (unmet) cannot be met by the working robots, or ``None`` when it may be."""
    result = check_condition(cond, reach.state)
    subjects = [o for o in reach.candidates(cond.subject) if o not in result.witnesses]
    if subjects and result.satisfied + sum(map(reach.reachable, subjects)) < cond.count:
        walled = [o for o in subjects if not reach.reachable(o)]
        return f"{cond} needs {' or '.join(walled)}"
    if cond.receptacle is not None:
        where = cond.receptacle
        if where.types:
            where = ObjectRef(types=tuple(sorted(place_types(where.types))))
        places = reach.candidates(where)
        if places and not any(map(reach.reachable, places)):
            return f"{cond} needs {' or '.join(places)}"
    return None


def check_not_walled_off(goal: Goal, state: WorldState, robots: Sequence[str]) -> None:
    """Raise :class:`WalledOffError` when broken-down robots wall the working ``robots`` off
    from objects an unmet condition of ``goal`` needs (nothing to check when none is down)."""
    if not any(r.down for r in state.robots.values()) or not robots:
        return
    reach = _Reach(state, robots)
    problems = [why for cond in goal.conditions
                if not check_condition(cond, state).holds and (why := _why_walled(cond, reach))]
    if problems:
        raise WalledOffError(f"{', '.join(reach.blockers)} broke down in the only way on {state.floor_plan}'s "
                             f"navigation grid from {', '.join(robots)} to what the goal needs: "
                             + "; ".join(problems))
