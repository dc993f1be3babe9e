"""Two robots on one long cluster, after the plan is validated.

Conditions on a common object are a cluster, planned by one robot (:mod:`emboteam.hp.rounds`):
apart, their plans would be made for an object the other changes. When one robot's cluster
is longer than the whole plan may be (FloorPlan1: ``hot(Egg)``, ``inside(Egg, Pan)``,
``cold(Pan_1)``, ``inside(Pan_1, CounterTop_3)``, 41.7 s of one robot against a bound of
24.5 s), no re-allocation helps: moved, the cluster takes as long. Planning the cluster for
two robots in one problem did not help either (lama-first minimises actions, and one robot
doing everything is as short as two), nor did allocating its subtasks apart (planned in
parallel from one state, they kept replanning each other).

Here the cluster is split *sequentially*, so it cannot replan itself: its subtasks are
parted in two, the first part planned for a lightly loaded helper from the state where the
cluster started, the second for the cluster's robot from the state the first part leaves
(the first part's goals protected). The merge's read/write deordering then lets the two
run side by side wherever they touch different things (the helper cools the pan while the
robot heats the egg). The planner splices the two plans in place of the robot's steps,
replays and simulates the whole plan, and keeps it only when its makespan is shorter.

A cluster of three or more blocks is parted among several robots (:func:`container_parts`,
``PlannerConfig.split_containers``): a pencil, a book and a statue put in a box and the
box put on a side table (FloorPlan201) is one robot's 24.2 s; the robot carries the box
while three helpers fetch the things, which they put in the box where it goes: 16.8 s.
The parts are planned one after the other, the container's first (:func:`container_first`).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Collection, Mapping, Sequence

from pydantic import BaseModel, ConfigDict

from emboteam.hp.merge import GroundedStep
from emboteam.hp.plan import MergedPlan
from emboteam.hp.validate import resource_bound

#: split a cluster only when its robot's seconds on it exceed by this factor what the
#: plan's steps need however they are spread (the largest of work / robots, the longest
#: subtask and the busiest spot's serial time: :func:`spread_floor`). The objects' serial
#: times are left out of it, since a split changes who carries what.
MIN_EXCESS = 1.15
#: partitions of a cluster tried (each costs two Fast Downward calls per order)
PARTITIONS = 1
#: at most this many parts (one robot each, one Fast Downward call each) in a split of a
#: cluster along its blocks (:func:`container_parts`)
MAX_PARTS = 4
#: in which orders the parts are tried (each order one Fast Downward call a part): "first",
#: the part that moves the container before the helpers' parts (the box carried while
#: the helpers fetch the things, which they put in it where it goes; FloorPlan201 seed 1,
#: 8 x 8: 24.2 -> 16.8 s); "last", after them (things put in the box where it stands,
#: then the box carried: the carrying waits for every put, 22.0 s). Trying both gained
#: one cell of the 150 measured (24.2 -> 23.0 s) for twice the calls
CONTAINER_ORDERS: tuple[str, ...] = ("first",)


class SplitTarget(BaseModel):
    """A cluster to split: the robot doing it, its helper, the cluster's subtasks with the
    robot's seconds on each, and where in the plan's step list its first step stands."""

    model_config = ConfigDict(frozen=True)

    robot: str
    helper: str
    members: tuple[str, ...]
    work: tuple[float, ...]
    first: int
    #: every able robot but ``robot``, the one that ends earliest first (``helper``)
    helpers: tuple[str, ...] = ()

    @property
    def seconds(self) -> float:
        return sum(self.work)


def find_target(plan: MergedPlan, cluster_of: Mapping[str, str], able: Callable[[str, Sequence[str]], bool],
                skip: Collection[str] = ()) -> SplitTarget | None:
    """The longest cluster one robot does, when it has at least two subtasks, its
    seconds exceed ``MIN_EXCESS`` x :func:`spread_floor` and another robot
    can do it. ``cluster_of`` maps a subtask to its cluster's id (members joined by
    ``+``); ``able(robot, members)``: can that robot do the whole cluster alone;
    clusters in ``skip`` were tried. The helper is the able robot that ends earliest."""
    work: dict[str, float] = {}
    ends: dict[str, float] = {}
    per: dict[tuple[str, str], dict[str, float]] = {}
    for s in plan.steps:
        d = s.est_end - s.est_start
        work[s.robot] = work.get(s.robot, 0.0) + d
        ends[s.robot] = max(ends.get(s.robot, 0.0), s.est_end)
        cid = cluster_of.get(s.subtask)
        if cid is not None and "+" in cid and cid not in skip:
            c = per.setdefault((s.robot, cid), {})
            c[s.subtask] = c.get(s.subtask, 0.0) + d
    floor = spread_floor(plan)
    if floor <= 0:
        return None
    for robot, cid in sorted(per, key=lambda k: (-sum(per[k].values()), k)):
        if sum(per[(robot, cid)].values()) <= MIN_EXCESS * floor:
            return None
        members = tuple(cid.split("+"))
        helpers = [r for r in plan.robots if r != robot and able(r, members)]
        if not helpers:
            continue
        helpers.sort(key=lambda r: (ends.get(r, 0.0), work.get(r, 0.0), r))
        first = next(i for i, s in enumerate(plan.steps) if s.robot == robot and s.subtask in members)
        return SplitTarget(robot=robot, helper=helpers[0], members=members,
                           work=tuple(per[(robot, cid)].get(m, 0.0) for m in members), first=first,
                           helpers=tuple(helpers))
    return None


def spread_floor(plan: MergedPlan) -> float:
    """max(work / robots, longest subtask of one robot, serial time at the busiest spot)
    over the plan's simulated step times."""
    b = resource_bound(plan, {s.id: s.est_end - s.est_start for s in plan.steps},
                       {s.id: s.resources[0] for s in plan.steps if s.resources})
    return max(b.work, b.subtask, b.spot)


def blocks(members: Sequence[str], subjects: Mapping[str, frozenset[str]]) -> list[tuple[str, ...]]:
    """The cluster's subtasks grouped by the objects they are about (their conditions'
    subjects, linked when they share one): ``hot(Egg)`` and ``inside(Egg, Pan)`` stay
    together, ``cold(Pan_1)`` goes with ``inside(Pan_1, CounterTop_3)``. Where every
    subtask is about one object, each subtask is a block."""
    home = {m: m for m in members}

    def root(m: str) -> str:
        while home[m] != m:
            m = home[m]
        return m

    owner: dict[str, str] = {}
    for m in members:
        for key in sorted(subjects.get(m, frozenset())):
            if key in owner:
                home[root(m)] = root(owner[key])
            else:
                owner[key] = m
    out: dict[str, list[str]] = {}
    for m in members:
        out.setdefault(root(m), []).append(m)
    if len(out) < 2:
        return [(m,) for m in members]
    return [tuple(b) for b in out.values()]


def partitions(target: SplitTarget, subjects: Mapping[str, frozenset[str]], limit: int = PARTITIONS
               ) -> list[tuple[tuple[str, ...], tuple[str, ...]]]:
    """Two-part splits of the cluster along its :func:`blocks`, most even (by the robot's
    measured seconds) first; each part non-empty."""
    seconds = dict(zip(target.members, target.work, strict=True))
    parts = blocks(target.members, subjects)
    out: list[tuple[float, tuple[str, ...], tuple[str, ...]]] = []
    rest = parts[1:]
    for k in range(len(rest) + 1):
        for chosen in itertools.combinations(rest, k):
            a = tuple(m for b in (parts[0], *chosen) for m in b)
            b = tuple(m for m in target.members if m not in a)
            if not b:
                continue
            sa, sb = sum(seconds[m] for m in a), sum(seconds[m] for m in b)
            out.append((max(sa, sb), a, b))
    out.sort(key=lambda x: (x[0], x[1]))
    return [(a, b) for _, a, b in out[:limit]]


def container_parts(target: SplitTarget, subjects: Mapping[str, frozenset[str]],
                    receptacles: Mapping[str, frozenset[str]], limit: int = MAX_PARTS) -> list[tuple[str, ...]]:
    """The cluster parted along its :func:`blocks`, one part per block, for a split among
    several robots: the helpers' parts first (longest first, by the robot's measured
    seconds), the robot's own part last. The last part is the block that moves the
    container: one whose subtasks are about an object other members put things in
    (``inside(Box_1, SideTable_3)`` when ``inside(Pencil_1, Box_1)`` is a member), or, when
    no block does, the longest. Beyond ``limit`` parts, the helpers' blocks are grouped
    (each into the part with the fewest seconds, longest first). Empty when the cluster
    has fewer than three blocks. ``subjects`` and ``receptacles``: the kinds of the objects
    each member's conditions are about and put things in."""
    seconds = dict(zip(target.members, target.work, strict=True))
    parts = blocks(target.members, subjects)
    if len(parts) < 3 or limit < 3:
        return []

    def length(b: Sequence[str]) -> float:
        return sum(seconds[m] for m in b)

    def moves_container(b: Sequence[str], m: str) -> bool:
        return moves(m, b, target.members, subjects, receptacles)

    movers = [b for b in parts if any(moves_container(b, m) for m in b)]
    last = max(movers or parts, key=lambda b: (length(b), [-target.members.index(m) for m in b]))
    rest = sorted((b for b in parts if b is not last),
                  key=lambda b: (-length(b), [target.members.index(m) for m in b]))
    bins: list[list[str]] = [[] for _ in range(min(len(rest), limit - 1))]
    for b in rest:
        into = min(range(len(bins)), key=lambda i: (length(bins[i]), i))
        bins[into].extend(b)
    helpers = sorted((tuple(b) for b in bins), key=lambda b: (-length(b), [target.members.index(m) for m in b]))
    return [*helpers, tuple(last)]


def moves(member: str, block: Sequence[str], members: Sequence[str], subjects: Mapping[str, frozenset[str]],
          receptacles: Mapping[str, frozenset[str]]) -> bool:
    """Does ``member`` (of ``block``) put somewhere an object other members (outside the
    block) put things in: ``inside(Box_1, SideTable_3)`` beside ``inside(Pencil_1, Box_1)``."""
    inside = frozenset(k for m in members if m not in block for k in receptacles.get(m, frozenset()))
    return bool(receptacles.get(member)) and bool(subjects.get(member, frozenset()) & inside)


def container_first(parts: Sequence[Sequence[str]], members: Sequence[str], subjects: Mapping[str, frozenset[str]],
                    receptacles: Mapping[str, frozenset[str]]) -> list[tuple[str, ...]]:
    """:func:`container_parts` planned the other way round: the container moved first (the
    robot's part), then the helpers' parts. The container block's other subtasks
    (``closed(Box_1)``) go with the last helper's part, after the things are in."""
    *helpers, last = parts
    moving = tuple(m for m in last if moves(m, last, members, subjects, receptacles))
    if not moving:
        return [tuple(last), *(tuple(h) for h in helpers)]
    rest = tuple(m for m in last if m not in moving)
    return [moving, *(tuple(h) for h in helpers[:-1]), (*helpers[-1], *rest)]


def splice(sequence: Sequence[GroundedStep], target: SplitTarget
           ) -> tuple[list[GroundedStep], list[GroundedStep], list[GroundedStep]]:
    """The plan's sequence (its steps, grounded, in the plan's order) before the cluster's
    first step, the robot's steps for the cluster from there on (they go), and the other
    steps after it (the new plans go in between)."""
    members = set(target.members)
    tail = sequence[target.first:]
    gone = [g for g in tail if g.robot == target.robot and g.subtask in members]
    rest = [g for g in tail if not (g.robot == target.robot and g.subtask in members)]
    return list(sequence[:target.first]), gone, rest
