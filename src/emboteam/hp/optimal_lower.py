"""A cheap lower bound on the optimum of :mod:`emboteam.hp.optimal`'s model, without CP-SAT.

``fast``'s CP-SAT stage (:mod:`emboteam.hp.stages.schedule`) keeps CP-SAT's schedule only
when it is shorter than the plan. Building the model and solving it was about a quarter of
the planner's main thread on MACE-THOR (issue 28), and on most tasks it found nothing
shorter: the plan already ended when its longest chain of waits, or its busiest robot
or spot, allows. This bound shows that before any model is built; where it reaches the
plan's makespan, CP-SAT cannot find anything shorter and the stage is skipped, with the
same plan as before.

Every term holds for every schedule of the model (each constraint it reads is one of
:class:`emboteam.hp.optimal._Model`'s, loosened): so the bound is never above the model's
optimum, for any of its options (``tight`` or not, with or without the carries' orders).
Times are the model's hundredths of a second (each duration and drive rounded down).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from graphlib import CycleError, TopologicalSorter

from emboteam.hp.optimal import _t, travel
from emboteam.hp.optimal_problem import Job, Point, Problem


@dataclass
class _Drives:
    """The least drives of the model, in hundredths: within a job (from one operation's
    place to the next one's goal) and into a job (from a candidate robot's start or from
    the end of another job it may take), each over the job's candidate robots."""

    problem: Problem
    _memo: dict[tuple[str, Point, Point], int] = field(default_factory=dict)

    def one(self, robot: str, a: Point, b: Point) -> int:
        key = (robot, a, b)
        if key not in self._memo:
            profile = self.problem.profiles[robot]
            self._memo[key] = _t(travel(profile, a, b, self.problem.floor_plan))
        return self._memo[key]

    def least(self, j: Job, a: Point, b: Point) -> int:
        """The shortest drive from ``a`` to ``b`` by any robot that may take ``j``."""
        return min(self.one(r, a, b) for r in self.problem.candidates[j.group])

    def into(self, j: Job, r: str) -> int:
        """The shortest way for ``r`` to reach ``j``'s first goal: from its start or from
        the last place of another job it may take (an arc of its circuit)."""
        goal = j.ops[0].goal
        ways = [self.one(r, self.problem.starts[r], goal)]
        ways += [self.one(r, o.ops[-1].place, goal) for o in self.problem.jobs
                 if o is not j and r in self.problem.candidates[o.group]]
        return min(ways)

    def onward(self, j: Job, r: str) -> int:
        """The shortest way for ``r`` to reach ``j``'s first goal from another job it may
        take (not from its start: ``r`` has done a job before ``j``)."""
        goal = j.ops[0].goal
        return min((self.one(r, o.ops[-1].place, goal) for o in self.problem.jobs
                    if o is not j and r in self.problem.candidates[o.group]), default=0)

    def inner(self, j: Job, r: str) -> int:
        """``j``'s own hundredths for ``r``: its operations and the drives between them."""
        return sum(_t(o.seconds) for o in j.ops) + sum(
            self.one(r, a.place, b.goal) for a, b in zip(j.ops, j.ops[1:], strict=False) if b.drive)


def lower_bound(problem: Problem) -> int | None:
    """A lower bound on the model's makespan in hundredths of a second: the longest chain
    of operations (:func:`chain_bound`), and the team's and each spot's work
    (:func:`load_bound`); None when the orders form a cycle (no schedule, nothing to
    bound)."""
    drives = _Drives(problem)
    chain = chain_bound(problem, drives)
    if chain is None:
        return None
    return max(chain, load_bound(problem, drives))


def _edges(problem: Problem, drives: _Drives) -> Iterator[tuple[str, str, int]]:
    """(a, b, gap): every schedule starts ``b`` at least ``gap`` after ``a`` ends. Within a
    job its operations in order with the drive between them, for the drive's waits too
    (the model's ``_within``; a first operation's drive is the one into the job); and
    every order of :meth:`Problem.orders` (:func:`_order_gap`)."""
    waits: dict[str, list[str]] = {}
    for a, b in [*problem.drive_waits, *problem.carry_waits]:
        waits.setdefault(b, []).append(a)
    for j in problem.jobs:
        if j.ops[0].step in waits:  # by whichever robot takes the job
            entry = min(drives.into(j, r) for r in problem.candidates[j.group])
            for a in waits[j.ops[0].step]:
                yield a, j.ops[0].step, entry
        for prev, o in zip(j.ops, j.ops[1:], strict=False):
            gap = drives.least(j, prev.place, o.goal) if o.drive else 0
            for a in [prev.step, *(waits.get(o.step, ()) if o.drive else ())]:
                yield a, o.step, gap
    job_of = {o.step: j for j in problem.jobs for o in j.ops}
    for a, b in problem.orders():
        yield a, b, _order_gap(problem, drives, job_of[a], job_of[b], a, b)


def _order_gap(problem: Problem, drives: _Drives, ja: Job, jb: Job, a: str, b: str) -> int:
    """The least gap of an order ``a`` -> ``b``: 0, or where ``b`` opens its job and both
    jobs go to one robot (one group, or both pinned to it), the drive into ``jb`` from
    another job: that robot did ``ja`` first (``a`` takes time, so ``jb`` comes after
    ``ja`` on its circuit), so it reaches ``jb`` from a job that ended after ``a``."""
    if ja is jb or jb.ops[0].step != b or _t(ja.ops[[o.step for o in ja.ops].index(a)].seconds) <= 0:
        return 0
    ca, cb = problem.candidates[ja.group], problem.candidates[jb.group]
    if ja.group != jb.group and not (len(ca) == len(cb) == 1 and ca == cb):
        return 0
    return min(drives.onward(jb, r) for r in cb)


#: passes of :func:`chain_bound` (each may raise the jobs' earliest starts; a count, so the
#: bound, and the stage's choice, is the same on any machine)
PASSES = 4


def chain_bound(problem: Problem, drives: _Drives) -> int | None:
    """The latest end of any operation when each starts as early as its waits allow (the
    longest path through :func:`_edges`), a job's first operation no earlier than its
    robot's way in: from its start, or from the end of the job before it on its circuit
    (each job's end as the last pass bounds it: a first pass from the drives alone, each
    pass never lower than the last); None on a cycle."""
    size = {o.step: _t(o.seconds) for j in problem.jobs for o in j.ops}
    after: dict[str, dict[str, int]] = {s: {} for s in size}
    for a, b, gap in _edges(problem, drives):
        after[b][a] = max(gap, after[b].get(a, gap))
    try:
        order = list(TopologicalSorter({b: set(preds) for b, preds in after.items()}).static_order())
    except CycleError:
        return None
    end: dict[str, int] = dict.fromkeys(size, 0)
    for _ in range(PASSES):
        earliest = {j.ops[0].step: _way_in(problem, drives, j, end) for j in problem.jobs}
        last = dict(end)
        for s in order:
            start = max([earliest.get(s, 0), *(end[a] + gap for a, gap in after[s].items())])
            end[s] = max(end[s], start + size[s])
        if end == last:
            break
    return max(end.values(), default=0)


def _way_in(problem: Problem, drives: _Drives, j: Job, end: dict[str, int]) -> int:
    """The earliest ``j``'s first operation may start: its robot (any candidate) drives
    there from its start, or from the last place of the job before it, which ends no
    earlier than ``end`` says."""
    goal = j.ops[0].goal
    ways = []
    for r in problem.candidates[j.group]:
        ways.append(drives.one(r, problem.starts[r], goal))
        ways += [end[o.ops[-1].step] + drives.one(r, o.ops[-1].place, goal) for o in problem.jobs
                 if o is not j and r in problem.candidates[o.group]]
    return min(ways)


def load_bound(problem: Problem, drives: _Drives) -> int:
    """The work that must fit before the makespan: each robot's pinned jobs (a group with
    one candidate), the whole team's work split evenly (each job at its cheapest robot,
    with its cheapest way in: the model's redundant loads), and each spot's operations
    (one robot at a time)."""
    pinned: dict[str, int] = {}
    total = 0
    for j in problem.jobs:
        cost = {r: drives.inner(j, r) + drives.into(j, r) for r in problem.candidates[j.group]}
        total += min(cost.values())
        if len(cost) == 1:
            (r, c), = cost.items()
            pinned[r] = pinned.get(r, 0) + c
    team = len({r for robots in problem.candidates.values() for r in robots}) or 1
    spots: dict[str, int] = {}
    for j in problem.jobs:
        for o in j.ops:
            spots[o.spot] = spots.get(o.spot, 0) + _t(o.seconds)
    return max([-(-total // team), *pinned.values(), *spots.values()])
