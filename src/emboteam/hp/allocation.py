"""Which robots plan each subtask: by capability, then balancing expected work.

A subtask keeps the robot its front end named when that robot can fill all its roles.
Otherwise (no robot named, an unknown or incapable one) the candidates are the single
robots that can do it alone; among them the one that would finish earliest (its work so
far plus this subtask's estimate) wins: greedy list scheduling, longest subtasks first
(LPT), which bounds the makespan by 4/3 of the optimum for independent jobs. When no
robot can do it alone (only robot A opens the fridge, only B carries the apple), a small
team is assembled greedily, role by role, preferring robots already chosen and the least
loaded; that team plans the subtask together as one multi-robot problem.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from emboteam.hp.requirements import Need, covers, estimate
from emboteam.pfg.taskspec import Subtask
from emboteam.world.state import WorldState


@dataclass(frozen=True)
class Assignment:
    subtask: str
    robots: tuple[str, ...]
    #: estimated seconds of work it adds to its robots
    estimate: float
    #: why: "as specified", "reassigned: robotX cannot ...", "allocated"
    note: str


def _team_for(needs: Sequence[Need], state: WorldState, team: Sequence[str],
              load: Mapping[str, float]) -> tuple[str, ...]:
    chosen: list[str] = []
    profiles = {r: state.robots[r].profile for r in team}
    for need in needs:
        if need.satisfied or covers([profiles[r] for r in chosen], need):
            continue
        # the alternative that needs the fewest new robots
        best: list[str] | None = None
        for alt in need.alternatives:
            extra: list[str] = []
            for role in alt:
                if any(role.covered_by(profiles[r]) for r in (*chosen, *extra)):
                    continue
                able = [r for r in team if role.covered_by(profiles[r])]
                if not able:
                    break
                extra.append(min(able, key=lambda r: (load.get(r, 0.0), r)))
            else:
                if best is None or len(extra) < len(best):
                    best = extra
        if best is None:
            return tuple(team)  # nobody can: let the planner prove it with everyone
        chosen += [r for r in best if r not in chosen]
    return tuple(chosen) or (min(team, key=lambda r: (load.get(r, 0.0), r)),)


def allocate(subtasks: Sequence[Subtask], needs: Mapping[str, Sequence[Need]], state: WorldState,
             team: Sequence[str], load: dict[str, float],
             prefer: Mapping[str, str] | None = None) -> list[Assignment]:
    """Assign robots to ``subtasks`` (updating ``load``, seconds of work per robot).
    ``prefer`` names a robot for some subtasks (a re-allocation from measured plans,
    :mod:`emboteam.hp.rebalance`): it is taken when it can do the subtask alone."""
    profiles = {r: state.robots[r].profile for r in team}
    work = {t.id: max((estimate(state, r, needs[t.id]) for r in team), default=0.0) for t in subtasks}
    fixed = [t for t in subtasks if t.robot in profiles]
    free = sorted((t for t in subtasks if t.robot not in profiles), key=lambda t: (-work[t.id], t.id))
    out: list[Assignment] = []
    for t in [*fixed, *free]:
        ns = needs[t.id]
        if t.robot in profiles and all(covers([profiles[t.robot]], n) for n in ns):
            robots: tuple[str, ...] = (t.robot,)
            note = "as specified"
        else:
            solo = [r for r in team if all(covers([profiles[r]], n) for n in ns)]
            if prefer and prefer.get(t.id) in solo:
                robots = (prefer[t.id],)
            elif solo:
                robots = (min(solo, key=lambda r: (load.get(r, 0.0) + estimate(state, r, ns), r)),)
            else:
                robots = _team_for(ns, state, team, load)
            if t.robot is None:
                note = "allocated"
            elif t.robot not in profiles:
                note = f"reassigned: {t.robot} is not a working member of the team"
            else:
                note = f"reassigned: {t.robot} cannot do it alone"
        est = max(estimate(state, r, ns) for r in robots)
        for r in robots:
            load[r] = load.get(r, 0.0) + est / len(robots)
        out.append(Assignment(t.id, robots, est, note))
    return out
