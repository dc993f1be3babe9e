"""A switch or a door other robots wait for, taken over by one of them.

Each robot's plan is made alone, and a state several plans need (the faucet running, the
fridge open) is set by whichever plan was accepted first; the others' steps then skip it
and the merge makes them wait for it. When that robot reaches the switch late in its own
chain, everybody waits (FloorPlan1, goal seed 2, 32 x 96: robot4 switches the faucet on at
11.5 s after breaking a plate and a mug; robot2, robot3, robot1 and robot14b stand holding
their bowl, cup, kettle and sponge from 1-7.5 s until then). The step needs no hands (it
only switches, opens or closes), so a waiting robot can do it itself, when it is free.

:func:`candidates` finds such steps in a merged plan, with the waiting robots each could go
to (the robot free earliest first); :func:`taken_over` gives the step done by another robot,
to be put in the same place of the sequence (so every step that read the state it sets
still comes after it). Whether the plan is shorter is the simulator's
(:mod:`emboteam.hp.stages.take_over`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from emboteam.hp.merge import GroundedStep
from emboteam.hp.plan import MergedPlan
from emboteam.world.actions import Skill

#: a wait shorter than this is not worth a rebuild (seconds)
MIN_WAIT = 1.0
#: only a step a robot that ends late waited for (at or after this share of the makespan):
#: an earlier robot's wait rarely moves the makespan, and each try is a rebuild
#: (FloorPlan1 32 x 96, goal seed 0: three tries, none shorter, 0.27 s of CPU)
LATE = 0.75
#: the steps another robot may take over: they set a state and need no hands
TOGGLES = frozenset({Skill.SwitchOn, Skill.SwitchOff, Skill.OpenObject, Skill.CloseObject})


@dataclass(frozen=True)
class Candidate:
    """A step (its index in the plan) others waited for, the seconds they waited in all,
    and the robots that waited, the one free earliest first."""

    index: int
    waited: float
    robots: tuple[str, ...]


def candidates(plan: MergedPlan) -> list[Candidate]:
    """The toggles other robots waited for at least :data:`MIN_WAIT` s, one of them a
    robot that ends late (:data:`LATE`), and one was free at least :data:`MIN_WAIT` s
    before the toggle began (else it could not do it sooner: the microwave opened by the
    robot before it in the queue); the longest total wait first (ties: the earlier step)."""
    waits = _waits(plan)
    ends: dict[str, float] = {}
    for s in plan.steps:
        ends[s.robot] = max(ends.get(s.robot, 0.0), s.est_end)
    out: list[Candidate] = []
    for i, by in waits.items():
        robots = tuple(sorted(by, key=lambda r: (by[r][0], r)))
        early = plan.steps[i].est_start - by[robots[0]][0] >= MIN_WAIT  # free before it began
        if early and any(ends[r] >= LATE * plan.makespan for r in by):
            out.append(Candidate(i, sum(w for _, w in by.values()), robots))
    return sorted(out, key=lambda c: (-c.waited, c.index))


def _waits(plan: MergedPlan) -> dict[int, dict[str, tuple[float, float]]]:
    """Index of a toggle others waited for -> each robot that waited: when it was free,
    how long it waited (its first such wait)."""
    index = {s.id: i for i, s in enumerate(plan.steps)}
    free: dict[str, float] = {}
    waits: dict[int, dict[str, tuple[float, float]]] = {}
    for s in plan.steps:
        ready = free.get(s.robot, 0.0)
        if s.est_start - ready >= MIN_WAIT:
            for p in s.after:
                producer = plan.steps[index[p]]
                if producer.action.skill in TOGGLES and producer.robot != s.robot:
                    waits.setdefault(index[p], {}).setdefault(s.robot, (ready, s.est_start - ready))
        free[s.robot] = s.est_end
    return waits


def taken_over(sequence: Sequence[GroundedStep], index: int, robot: str) -> GroundedStep:
    """The step at ``index`` done by ``robot`` (for the subtask of that robot's next step,
    so it counts with that robot's work); to be grounded again where it stands."""
    g = sequence[index]
    subtask, group = next(((x.subtask, x.group) for x in sequence[index + 1:] if x.robot == robot),
                          (g.subtask, g.group))
    return replace(g, robot=robot, subtask=subtask, group=group)
