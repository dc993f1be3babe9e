"""Who goes first at a shared spot: validated block moves over the accepted sequence.

The merge orders two robots' steps at one spot (the microwave, the sink) as they come in
the accepted sequence, and the sequence follows the order units were accepted in, not
the order robots arrive. In FloorPlan1 (16 robots x 96 conditions) a robot puts a plate
in the microwave at 5 s and leaves the door open while it fetches an apple slice and a
sponge to put on it, heating at 30 s; the egg, the cup and the potato slice that reach the
microwave at 12-17 s queue behind it, each heated after the previous, and the last robot
ends at 51 s where its own work is 28 s.

Here a *block* is a run of one robot's consecutive steps at one spot (put the egg in,
close, switch on and off, open, take it out). A block that waited (it started later than
its robot was free) is moved, in the sequence, before the other robots' steps at its spot
that started after its robot was free, together with its robot's own steps since then (so
the robot's order stays). The planner replays the moved sequence (the same repairs as
any accepted plan), merges and simulates it, and keeps it only when the makespan is
shorter; heating the egg while the plate waits inside is then a valid plan or not by the
simulator's word, not by this module's.
"""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict

from emboteam.hp.merge import SeqStep
from emboteam.hp.plan import MergedPlan
from emboteam.world.actions import Action, Skill
from emboteam.world.catalogue import INTERLOCKED
from emboteam.world.state import WorldState

#: a block that waited less than this (seconds) is not worth a replay (the moves kept in
#: the latency sweep were of blocks that waited 3.4-22 s)
MIN_WAIT = 3.0
#: blocks tried per plan (each costs a replay, a merge and a simulation, no planner call:
#: 0.02-0.04 s in FloorPlan1 32 x 96; a fourth try and more gained nothing in the sweep)
TRIES = 3


class Block(BaseModel):
    """A run of one robot's consecutive steps at one spot: its steps' indices in the plan
    (= the accepted sequence), when its robot was free for it, and how long it waited."""

    model_config = ConfigDict(frozen=True)

    robot: str
    spot: str
    indices: tuple[int, ...]
    ready: float
    wait: float


def waiting_blocks(plan: MergedPlan) -> list[Block]:
    """The plan's blocks that waited at least ``MIN_WAIT``, longest wait first."""
    steps = plan.steps
    prev_end: dict[str, float] = {}
    current: dict[str, list[int]] = {}
    runs: list[tuple[str, str, list[int], float]] = []
    for i, s in enumerate(steps):
        spot = s.resources[0] if s.resources else None
        run = current.get(s.robot)
        if run is not None and spot is not None and steps[run[0]].resources[0] == spot:
            run.append(i)
        else:
            current.pop(s.robot, None)
            if spot is not None:
                run = [i]
                current[s.robot] = run
                runs.append((s.robot, spot, run, prev_end.get(s.robot, 0.0)))
        prev_end[s.robot] = s.est_end
    out = [Block(robot=r, spot=spot, indices=tuple(run), ready=ready, wait=steps[run[0]].est_start - ready)
           for r, spot, run, ready in runs]
    return sorted((b for b in out if b.wait >= MIN_WAIT), key=lambda b: (-b.wait, b.indices[0]))


def moved(plan: MergedPlan, block: Block) -> list[int] | None:
    """The sequence's indices in a new order with ``block`` before the other robots'
    steps at its spot that started after its robot was free (None: there are none
    before it in the sequence). The block is taken to its robot's last step at the spot
    (a knife picked up is held until it is dropped there; a microwave switched on is
    opened again), and the robot's own steps from that point on move with it, in their
    order; everything else keeps its order."""
    steps = plan.steps
    first = block.indices[0]
    ahead = [i for i in range(first) if steps[i].robot != block.robot and steps[i].resources
             and steps[i].resources[0] == block.spot and steps[i].est_start >= block.ready]
    if not ahead:
        return None
    p = ahead[0]
    last = max(i for i, s in enumerate(steps) if s.robot == block.robot and s.resources
               and s.resources[0] == block.spot)
    mine = [i for i in range(p, last + 1) if steps[i].robot == block.robot]
    others = [i for i in range(p, last + 1) if steps[i].robot != block.robot]
    return [*range(p), *mine, *others, *range(last + 1, len(steps))]


def critical_waits(plan: MergedPlan) -> list[int]:
    """Steps that waited on the chain that ends last: from the step that ends last back,
    through the robot's previous step when it started as soon as that ended, else through
    the step it waited for (a wait it names, or another robot's step at its spot ending
    when it started)."""
    steps = plan.steps
    if not steps:
        return []
    index = {s.id: i for i, s in enumerate(steps)}
    own: list[int | None] = []
    last: dict[str, int] = {}
    for i, s in enumerate(steps):
        own.append(last.get(s.robot))
        last[s.robot] = i
    out: list[int] = []
    cur: int | None = max(range(len(steps)), key=lambda i: (steps[i].est_end, -i))
    seen: set[int] = set()
    while cur is not None and cur not in seen:
        seen.add(cur)
        s = steps[cur]
        prev = own[cur]
        ready = steps[prev].est_end if prev is not None else 0.0
        if s.est_start <= ready + 1e-6:
            cur = prev
            continue
        out.append(cur)
        why = [index[a] for a in s.after if a in index and abs(steps[index[a]].est_end - s.est_start) < 1e-6]
        if not why and s.resources:
            why = [j for j, o in enumerate(steps) if o.robot != s.robot and o.resources == s.resources
                   and abs(o.est_end - s.est_start) < 1e-6]
        cur = why[0] if why else prev
    return out


def candidates(plan: MergedPlan, tries: int = TRIES) -> list[tuple[Block, list[int]]]:
    """Up to ``tries`` block moves: blocks whose wait is on the chain that ends last
    first, then the others, longest waits first."""
    critical = set(critical_waits(plan))
    blocks = sorted(waiting_blocks(plan), key=lambda b: (not critical.intersection(b.indices), -b.wait))
    out: list[tuple[Block, list[int]]] = []
    for b in blocks:
        order = moved(plan, b)
        if order is not None:
            out.append((b, order))
        if len(out) >= tries:
            break
    return out


def reopen(state: WorldState, step: SeqStep) -> list[Action]:
    """Open the closed receptacle hiding a step's object (switching a running microwave
    off first): a block moved ahead may leave the microwave shut on another robot's plate,
    which that robot then puts a sponge on or takes out. Validated like any step."""
    robot = state.robots.get(step.robot)
    a = step.action
    if robot is None or a.skill is Skill.GoToObject or not robot.profile.can(Skill.OpenObject):
        return []
    for ref in (a.receptacle, a.target):
        if not ref or ref not in state.objects or state.objects[ref].held_by is not None:
            continue
        shut = state.enclosing_closed(ref)
        if shut is None:
            continue
        if state.objects[shut].type in INTERLOCKED and state.objects[shut].is_on:
            if not robot.profile.can(Skill.SwitchOff):
                return []
            return [Action(skill=Skill.SwitchOff, target=shut), Action(skill=Skill.OpenObject, target=shut)]
        return [Action(skill=Skill.OpenObject, target=shut)]
    return []
