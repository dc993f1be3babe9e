"""A switch or a door other robots wait for, taken over by one of them.

Each robot's plan is made alone, and a state several plans need (the faucet running, the
fridge open) is set by whichever plan was accepted first; the others' steps then skip it
and the merge makes them wait for it. When that robot reaches the switch late in its own
chain, everybody waits (FloorPlan1, goal seed 2, 32 x 96: robot4 switches the faucet on at
11.5 s after breaking a plate and a mug; robot2, robot3, robot1 and robot14b stand holding
their bowl, cup, kettle and sponge from 1-7.5 s until then). The step needs no hands (it
only switches, opens or closes), so a waiting robot can do it itself, when it is free.

:func:`candidates` finds such steps in a merged plan, with the waiting robots each could go
to (the robot free earliest first); :func:`taken_over` gives the sequence with the step
done by another robot, in the same place of the sequence (so every step that read the
state it sets still comes after it). Whether the plan is shorter is the simulator's
(:mod:`emboteam.hp.stages.take_over`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from emboteam.hp.merge import GroundedStep, SeqStep
from emboteam.hp.plan import MergedPlan
from emboteam.world.actions import Skill

#: a wait shorter than this is not worth a rebuild (seconds)
MIN_WAIT = 1.0
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
    """The toggles other robots waited for at least :data:`MIN_WAIT` s, the longest total
    wait first (ties: the earlier step)."""
    index = {s.id: i for i, s in enumerate(plan.steps)}
    free: dict[str, float] = {}
    waits: dict[int, dict[str, tuple[float, float]]] = {}
    for s in plan.steps:
        ready = free.get(s.robot, 0.0)
        wait = s.est_start - ready
        if wait >= MIN_WAIT:
            for p in s.after:
                producer = plan.steps[index[p]]
                if producer.action.skill in TOGGLES and producer.robot != s.robot:
                    by = waits.setdefault(index[p], {})
                    by.setdefault(s.robot, (ready, wait))
        free[s.robot] = s.est_end
    out = [Candidate(i, sum(w for _, w in by.values()), tuple(sorted(by, key=lambda r: (by[r][0], r))))
           for i, by in waits.items()]
    return sorted(out, key=lambda c: (-c.waited, c.index))


def taken_over(sequence: Sequence[GroundedStep], index: int, robot: str) -> list[SeqStep]:
    """The sequence as steps to replay, the step at ``index`` done by ``robot`` (for the
    subtask of that robot's next step, so it counts with that robot's work)."""
    serves = next(((g.subtask, g.group) for g in sequence[index + 1:] if g.robot == robot),
                  (sequence[index].subtask, sequence[index].group))
    out: list[SeqStep] = []
    for i, g in enumerate(sequence):
        if i == index:
            out.append(SeqStep(robot, g.action, *serves))
        else:
            out.append(SeqStep(g.robot, g.action, g.subtask, g.group))
    return out
