"""The carry term of the resource-aware bound: a receptacle one robot carries and puts
down, then the work done into it at its new place (issue 28).

A box is picked up, carried and put down on a table; robots then put a pencil, a book and
a statue into it. Each put happens where the box stands (the plan fixes every action's
place: put into the box on the table), so none can start before the put-down ends, and
the puts hold the box's spot one robot at a time. The put-down in turn ends no earlier
than the least drive any robot needs to reach the box (from its start, or from a place
where a robot's hands are empty: a pickup needs empty hands), plus the carrier's steps
from the pickup to the put-down, its drives at the team's highest speed. So any schedule
of these actions takes at least that release + the puts' serial time + the least time
left after them in their jobs. The spot and object windows of :mod:`emboteam.hp.validate`
miss it: they count the box's spot used by the carrier (its pickup) and by the puts, but
not that the puts wait for the carrier's *last* step. On FloorPlan201 4 x 8 (goal seed 1)
the plan's bound was 15.5 where the optimum is 18.0: the box is down at 15.0 at the
earliest, then three puts of 1 s.

Polynomial (one replay of the plan, navigation queries from the robots' starts and the
empty-hand places to each such box) and computed only when the plan carries a receptacle
and acts on it after putting it down, and the measured times could beat the other terms.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.sim.durations import navigation_seconds
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.actions import Skill
from emboteam.world.state import WorldState

_RELEASES = frozenset({Skill.PutObject, Skill.ThrowObject, Skill.DropHandObject})

Point = tuple[float, float]


@dataclass
class Carry:
    """One carry of ``obj`` ending in a put-down: the carrier's steps from the pickup to
    the put-down (indices into the plan), the drive before the pickup (if any), and the
    later steps acting on ``obj`` before it is picked up again."""

    obj: str
    drive: int | None
    steps: list[int]
    after: list[int] = field(default_factory=list)


def carries(plan: MergedPlan) -> list[Carry]:
    """Every carry of an object put down (``PutObject``) and then acted on (the put-down's
    object as target, or as the receptacle of a put) by steps later in the plan's order,
    up to the object's next pickup."""
    out: list[Carry] = []
    steps = plan.steps
    last: dict[str, int] = {}  # robot -> index of its previous step
    open_: dict[str, Carry] = {}  # robot -> its carry in progress
    for k, s in enumerate(steps):
        prev = last.get(s.robot)
        last[s.robot] = k
        if s.action.skill is Skill.PickupObject:
            drive = prev if prev is not None and steps[prev].action.skill is Skill.GoToObject else None
            open_[s.robot] = Carry(s.action.target, drive, [k])
        elif s.robot in open_:
            carry = open_[s.robot]
            carry.steps.append(k)
            if s.action.skill in _RELEASES:
                del open_[s.robot]
                if s.action.skill is Skill.PutObject and s.action.target == carry.obj:
                    carry.after = _acting_on(steps, carry.obj, k)
                    if carry.after:
                        out.append(carry)
    return out


def _acting_on(steps: tuple[PlanStep, ...], obj: str, put: int) -> list[int]:
    """The steps after index ``put`` that act on ``obj`` where it was put, up to its next pickup."""
    out: list[int] = []
    for k in range(put + 1, len(steps)):
        a = steps[k].action
        if a.skill is Skill.PickupObject and a.target == obj:
            break
        if a.receptacle == obj or (a.target == obj and a.skill is not Skill.GoToObject):
            out.append(k)
    return out


@dataclass
class _Replay:
    """Where things are during a replay of the plan in its order: every drive's start and
    goal, and the places where each carried object is picked up from and put down."""

    drives: dict[int, tuple[Point, Point]] = field(default_factory=dict)
    rests: dict[str, list[Point]] = field(default_factory=dict)
    put_at: dict[int, Point] = field(default_factory=dict)


def _replay(plan: MergedPlan, start: WorldState, objects: set[str]) -> _Replay | None:
    """None when a step cannot be replayed in the plan's order."""
    state = start.copy()
    out = _Replay()
    for k, s in enumerate(plan.steps):
        if check_action(state, s.robot, s.action) is not None:
            return None
        here = (state.robots[s.robot].position[0], state.robots[s.robot].position[1])
        if s.action.skill is Skill.GoToObject:
            o = state.objects[s.action.target]
            holder = state.robots[o.held_by].position if o.held_by else (o.position[0], o.position[2])
            out.drives[k] = (here, (holder[0], holder[1]))
        moved = s.action.target in objects and s.action.skill in (Skill.PickupObject, Skill.PutObject)
        if moved and s.action.skill is Skill.PickupObject:
            o = state.objects[s.action.target]
            out.rests.setdefault(o.id, []).append((o.position[0], o.position[2]))
        apply_action(state, s.robot, s.action)
        if moved and s.action.skill is Skill.PutObject:
            o = state.objects[s.action.target]
            out.put_at[k] = (o.position[0], o.position[2])
            out.rests.setdefault(o.id, []).append(out.put_at[k])
    return out


def _drive(a: Point, b: Point, speed: float, floor_plan: str) -> float:
    """Free-flow seconds from ``a`` to ``b``, rounded down to the hundredth."""
    if a == b:
        return 0.0
    return math.floor(navigation_seconds(a, b, speed, floor_plan or None) * 100) / 100


def carry_bound(plan: MergedPlan, durations: Mapping[str, float], spots: Mapping[str, str],
                start: WorldState, floor: float = 0.0) -> tuple[float, str]:
    """The largest release of a put-down + the serial time after it at one spot + the
    least tail (see the module's docstring), and its object; (0, "") when no carry beats
    ``floor`` even on the plan's measured times (then nothing is replayed)."""
    found = carries(plan)
    if not found:
        return 0.0, ""
    jobs = _jobs(plan, durations)
    steps = plan.steps
    best, name = 0.0, ""
    todo = []
    for c in found:
        measured = sum(durations.get(steps[k].id, 0.0) for k in ([c.drive] if c.drive is not None else []) + c.steps)
        if _serial(c, steps, spots, jobs, measured) > max(floor, best) + 1e-9:
            todo.append(c)
    if not todo:
        return 0.0, ""
    replay = _replay(plan, start, {c.obj for c in todo})
    if replay is None:
        return 0.0, ""
    for c in todo:
        put = c.steps[-1]
        able = _able(start, plan, c)
        if not able or replay.rests[c.obj].count(replay.put_at[put]) > 1:
            continue  # put down where it also lies at another time: the work may be done then
        speed = max(start.robots[r].profile.speed for r in able)
        release = 0.0
        if c.drive is not None:
            goal = replay.drives[c.drive][1]
            release = min(_drive(start.robots[r].position, goal, start.robots[r].profile.speed, start.floor_plan)
                          for r in able)
        for k in c.steps:
            s = steps[k]
            release += (_drive(*replay.drives[k], speed, start.floor_plan) if s.action.skill is Skill.GoToObject
                        else durations.get(s.id, 0.0))
        value = _serial(c, steps, spots, jobs, release)
        if value > best + 1e-9:
            best, name = value, c.obj
    return best, name


def _able(start: WorldState, plan: MergedPlan, c: Carry) -> list[str]:
    """The robots that could do the carry: every skill of its steps, and the lift."""
    skills = {plan.steps[k].action.skill for k in c.steps}
    mass = start.objects[c.obj].mass if c.obj in start.objects else 0.0
    return [r for r in plan.robots if r in start.robots and start.robots[r].profile.mass_capacity >= mass
            and all(start.robots[r].profile.can(k) for k in skills)]


def _jobs(plan: MergedPlan, durations: Mapping[str, float]) -> dict[str, tuple[float, float, float]]:
    """Step id -> (seconds before it in its job, its own, after it in its job): a job is one
    robot's steps for one subtask, as the resource-aware bound counts them."""
    per: dict[tuple[str, str], list[str]] = {}
    for s in plan.steps:
        per.setdefault((s.subtask, s.robot), []).append(s.id)
    out: dict[str, tuple[float, float, float]] = {}
    for ids in per.values():
        total = sum(durations.get(i, 0.0) for i in ids)
        before = 0.0
        for i in ids:
            d = durations.get(i, 0.0)
            out[i] = (before, d, total - before - d)
            before += d
    return out


def _serial(c: Carry, steps: tuple[PlanStep, ...], spots: Mapping[str, str],
            jobs: Mapping[str, tuple[float, float, float]], release: float) -> float:
    """One machine per spot for the steps after the put-down: every one starts after
    ``release`` and after the steps before it in its job; max over spots and over the sets
    "every step with tail >= b" of max(release, least head) + their time + b (the
    one-machine relaxation: each step alone has its head and its tail)."""
    per: dict[str, list[tuple[float, float, float]]] = {}
    for k in c.after:
        s = steps[k]
        head, own, tail = jobs[s.id]
        per.setdefault(spots.get(s.id, c.obj), []).append((max(head, release), own, tail))
    best = 0.0
    for items in per.values():
        for b in sorted({t for _, _, t in items}):
            chosen = [i for i in items if i[2] >= b]
            best = max(best, min(h for h, _, _ in chosen) + sum(p for _, p, _ in chosen) + b)
    return best

