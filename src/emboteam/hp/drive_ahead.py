"""Drive ahead to where a thing is going: the drives that wait for another robot to bring
their object.

A robot that is to put a book into a box which another robot carries to a side table gets
a plan that drives to the box *after* the box is on the table (``GoToObject(Box_1)``: the
drive reads where the box is, so the merge orders it after the put that moves it). The
robot stands idle all that time, then drives the whole way (FloorPlan201, goal seed 1,
8 x 8: the box arrives at 15.0 s, the book's robot drives 15.0-21.0 and puts at 22.0).
Driving to the side table instead (``GoToObject(SideTable_3)``: a place nobody moves)
needs no wait; the put into the box still waits for the box, with the robot already there.

:func:`retargets` finds such drives in a grounded sequence whose merged plan made them
wait, and names the place each may drive to instead: the receptacle the other robot's last
put left the object in, when that receptacle does not move in between. Whether the robot
can reach the object from there is the replay's business (it drives the rest of the way
when it cannot: :func:`emboteam.hp.rounds.preparations`), and whether the plan is shorter
the simulator's (:mod:`emboteam.hp.stages.drive_ahead`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from emboteam.hp.merge import GroundedStep, SeqStep
from emboteam.hp.plan import MergedPlan
from emboteam.world.actions import Action, Skill

#: a drive that started at least this many seconds after its robot was free waited
WAITED = 0.25
#: what takes an object from where it was put
_LIFTS = (Skill.PickupObject, Skill.DropHandObject, Skill.ThrowObject)


@dataclass(frozen=True)
class _Put:
    """The last put of an object: by whom, into what, at which index."""

    robot: str
    receptacle: str
    index: int


def waited(plan: MergedPlan) -> set[int]:
    """Indices of the plan's steps that started later than their robot was free (they
    waited for another robot's step)."""
    free: dict[str, float] = {}
    out: set[int] = set()
    for i, s in enumerate(plan.steps):
        if s.after and s.est_start > free.get(s.robot, 0.0) + WAITED:
            out.add(i)
        free[s.robot] = s.est_end
    return out


def retargets(sequence: Sequence[GroundedStep], waiting: set[int]) -> dict[int, str]:
    """Index of a drive in ``sequence`` -> the place to drive to instead: for each drive
    in ``waiting`` to an object another robot put last, into a receptacle nobody lifts
    between that put and the drive."""
    last_put: dict[str, _Put] = {}
    lifted: dict[str, int] = {}
    out: dict[int, str] = {}
    for i, g in enumerate(sequence):
        a = g.action
        if a.skill is Skill.GoToObject:
            put = last_put.get(a.target)
            if (i in waiting and put is not None and put.robot != g.robot
                    and lifted.get(put.receptacle, -1) < put.index):
                out[i] = put.receptacle
        elif a.skill in _LIFTS:
            lifted[a.target] = i
            last_put.pop(a.target, None)
        elif a.skill is Skill.PutObject and a.receptacle:
            last_put[a.target] = _Put(g.robot, a.receptacle, i)
    return out


def driven_ahead(sequence: Sequence[GroundedStep], targets: Mapping[int, str]) -> list[SeqStep]:
    """The sequence as steps to replay, each drive of ``targets`` to its new place."""
    out: list[SeqStep] = []
    for i, g in enumerate(sequence):
        action = Action(skill=Skill.GoToObject, target=targets[i]) if i in targets else g.action
        out.append(SeqStep(g.robot, action, g.subtask, g.group))
    return out
