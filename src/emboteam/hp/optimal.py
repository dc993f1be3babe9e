"""An exact reference for the schedule: an OR-Tools CP-SAT model of the whole task's
scheduling problem over a plan's grounded actions, solved to a proven optimum or to a
best bound with a gap (issue 28).

The model (:func:`build`): a *job* is one robot's steps for one subtask, in their order;
its *operations* are its manipulation steps (each at an interaction spot, with its
skill's duration), reached by driving between the places they happen (the plan's
GoToObject steps, whose seconds depend on who drives from where: :func:`travel`, the one
call a grid-based navigation model replaces). Decided by the solver:

- which robot does each job: any robot with every skill the job uses and the mass
  capacity for what it picks up (a job of a subtask several robots share, or of a robot
  that ends a job holding something, stays where it is);
- each robot's order of jobs (a circuit per robot, the drive from one job's last place to
  the next one's first on each arc, from the robot's start to its first job);
- when each operation starts: after the previous one of its job and the drive between
  them; after the steps it waits for in the plan (its causal order: what a step needs,
  what must not change before it is used, the subtask dependencies); one robot at a time
  at each spot (the order is the solver's) and on each object (a held one from its pickup
  to its release).

Minimised: the makespan. Redundant constraints give the bound its strength: each
robot's load (its jobs, each with its cheapest way in) and its whole route (its jobs
plus the drive on every arc of its circuit, in the LP with the circuits at
``linearization_level=2``), both before the makespan. The jobs keep the actions the
plan gave them (a fridge one job opens stays opened by that job) and their places (an
object another job moved is where the plan left it), so this is the optimum *for these actions in this causal order*: a tighter
reference than the resource-aware bound, exact where it proves optimality, and no bound
on plans with other actions. Solved with a fixed seed and a *deterministic* time limit
(one worker for ``fast``'s small models; CP-SAT's portfolio interleaved in fixed batches
for the reference and ``--schedule optimal``): the same answer on any machine. A wall-clock
limit far above it is only a safety net, raising :class:`ScheduleTimeoutError`; it is ours
(:class:`_NetSolver`), not CP-SAT's ``max_time_in_seconds``, which stops a search as soon as
the time so far plus the longest wait between two of its checks passes the limit: under
load an interleaved batch took 100 s, and CP-SAT stopped FloorPlan201 2 x 24 (goal seed 2)
at 126 s of a 150 s limit, after 4.2 of its 10 deterministic seconds, with a worse bound
and no sign of the wall clock (issue 28). The strong
model (``linearization=2``) also counts time in the greatest common divisor of all
durations and drives (a quarter second on the navigation grid), and posts a drive within
a job without its robot where every candidate drives as long (issue 28: FloorPlan1 4 x 16,
goal seeds 3 and 4, proven in 10 deterministic seconds, not before). Its domains end at
the hint's makespan, and robots no constraint tells apart (:func:`interchangeable`) take
groups in a fixed order: both exact, neither changes an optimum. Its portfolio is two
full-problem searches without large-neighbourhood search (:data:`PORTFOLIO`, a
:class:`Portfolio`, a setting of :func:`solve` and of the schedule stage's budget): the
cells left unproven were min-max routing problems whose proof is search, not the LP. Where it
ends unproven, :func:`solve` can go on with the route relaxation's bound
(:mod:`.optimal_bound`) and with branch-and-check one cap at a time (:mod:`.optimal_check`).
"""

from __future__ import annotations

import itertools
import math
import threading
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from ortools.sat.python import cp_model

from emboteam.hp.optimal_bound import RouteBound, Routing, route_bound
from emboteam.hp.optimal_carry import CarryLog
from emboteam.hp.optimal_check import CapCheck, check_cap
from emboteam.hp.optimal_problem import Job as Job
from emboteam.hp.optimal_problem import Op as Op
from emboteam.hp.optimal_problem import Point as Point
from emboteam.hp.optimal_problem import Problem as Problem
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.pddl.errors import PlannerLimitError
from emboteam.pfg.taskspec import TaskSpec
from emboteam.sim.durations import navigation_seconds
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.actions import Skill
from emboteam.world.robots import RobotProfile
from emboteam.world.state import WorldState

#: model times in hundredths of a second (each rounded down: see :func:`_t`)
SCALE = 100
#: CP-SAT's deterministic time limit for the reference (about seconds of one core)
REFERENCE_LIMIT = 10.0
#: no model when the robots' circuits would have more arcs than this (the 32-robot cells)
MAX_ARCS = 20_000
#: the wall-clock safety net of a solve, ``WALL_FLOOR + WALL_FACTOR * limit`` seconds: far
#: above what the deterministic limit takes on a loaded machine (10 deterministic s took up
#: to 27 s of wall time at load 15 on 2 cores, 126 s for 4.2 at load 24), so it only stops
#: a solve that has hung or starves, and then raises (:class:`_NetSolver`)
WALL_FLOOR = 30.0
WALL_FACTOR = 12.0
#: the strong search (``linearization=2``: the reference and ``--schedule optimal``): CP-SAT's
#: portfolio of strategies interleaved in fixed batches, deterministic for a fixed worker
#: count and batch size (``interleave_search``); it proved FloorPlan1 4 x 16 (goal seed 3)
#: in 4.1 deterministic s where one worker needed 29.6
PORTFOLIO_BATCH = 12


@dataclass(frozen=True)
class Portfolio:
    """The strong search: CP-SAT's full-problem searches (``subsolvers``, without
    large-neighbourhood search), one worker each, interleaved in fixed batches of
    ``batch`` tasks (``interleave_search``): deterministic for a fixed worker count and
    batch size, so the answer depends only on this setting and the deterministic limit.
    The deterministic limit counts the time of *every* search, so each takes its share of
    it from the others (issue 28, branch proof28e)."""

    searches: tuple[str, ...]
    batch: int = PORTFOLIO_BATCH

    @property
    def workers(self) -> int:
        return len(self.searches)


#: four full-problem searches (issue 28, branch proof28: with LNS and all eight, each of
#: these got about 2 of the 10 deterministic seconds, and FloorPlan1 4 x 24 seed 3 took
#: 18.3 s to prove; these four alone prove it in 8.0 s, and FloorPlan1 2 x 24 seed 1 in 11.9 s)
FOUR_SEARCHES = Portfolio(("default_lp", "max_lp", "no_lp", "quick_restart_no_lp"))
#: the default strong search: the LP search with CP-SAT's default linearization and the
#: search without LP, each with half the limit (issue 28, branch proof28f: on the 90 sweep
#: cells up to 8 x 24, goal seeds 0-4, 88 proven in 10 deterministic s where the four
#: searches proved 87, none lost, the same optima; FloorPlan201 4 x 24 seed 4 is no_lp's
#: proof, FloorPlan1 2 x 24 seed 1 default_lp's)
TWO_SEARCHES = Portfolio(("default_lp", "no_lp"))
PORTFOLIO = TWO_SEARCHES
PORTFOLIO_WORKERS = PORTFOLIO.workers


class ScheduleTimeoutError(PlannerLimitError):
    """CP-SAT hit its wall-clock safety net before its deterministic limit: its answer
    would depend on the machine's load, so there is none (issue 28: the same input gives
    the same plan on any machine)."""



def travel(profile: RobotProfile, a: Point, b: Point, floor_plan: str = "") -> float:
    """Seconds a robot of ``profile`` drives from ``a`` to ``b`` in ``floor_plan``: the
    scene's navigation model (:func:`emboteam.sim.durations.navigation_seconds`, the one
    call that knows how: along the floor plan's navigation grid; Manhattan without a floor
    plan), 0 when already there. Free-flow seconds: waits for traffic only make the simulated plan
    later, so the plan stays a solution of the model."""
    if a == b:
        return 0.0
    return navigation_seconds(a, b, profile.speed, floor_plan or None)


@dataclass(frozen=True)
class Reference:
    """What CP-SAT found: the best makespan, its bound, whether it is proven optimal, the
    robot of every step of a job (step id -> robot) and each operation's start (step id ->
    seconds)."""

    status: str
    makespan: float
    bound: float
    robots: Mapping[str, str]
    starts: Mapping[str, float]
    #: CP-SAT's deterministic seconds for the answer (the same on any machine)
    deterministic: float = 0.0

    @property
    def optimal(self) -> bool:
        return self.status == "optimal"

    @property
    def gap(self) -> float:
        return (self.makespan - self.bound) / self.makespan if self.makespan > 0 else 0.0


def problem_of(plan: MergedPlan, spec: TaskSpec, start: WorldState, carries: bool = True) -> Problem | None:
    """The jobs of ``plan`` (replayed on ``start`` in its step order for the places and
    the hands); None when the replay fails. ``carries=False`` leaves out the orders that
    keep an operation on a carried receptacle between its carries (:mod:`emboteam.hp.optimal_carry`):
    no longer an exact model, but a heuristic's (the CP-SAT stage replans the drives and
    simulates what it gets, so a put may cross a carry at the box's other place)."""
    replay = _Replay(start.copy())
    for s in plan.steps:
        if not replay.step(s):
            return None
    jobs = [j for j in replay.jobs if j.ops]
    profiles = {r: start.robots[r].profile for r in plan.robots}
    candidates = _groups(jobs, plan, profiles, fixed=replay.fixed(jobs, spec))
    starts = {r: (start.robots[r].position[0], start.robots[r].position[1]) for r in plan.robots}
    waits, drives = _precedences(plan, jobs)
    before, arrive = replay.carry_orders({j.ops[0].step for j in jobs}) if carries else (set(), set())
    return Problem(jobs, candidates, starts, profiles, waits, drives, replay.shared(), start.floor_plan,
                   sorted(before - arrive - set(waits)), sorted(arrive - set(drives)))


@dataclass
class _Replay:
    """A plan replayed step by step (:func:`problem_of`): the jobs it forms (a robot's
    steps until its hands are empty again), each robot's open job and pending drive,
    the spans of one robot on each object, and the carries' log for their orders."""

    state: WorldState
    jobs: list[Job] = field(default_factory=list)
    open_: dict[str, Job] = field(default_factory=dict)
    #: robot -> where its last drive went (for the next operation's goal)
    drive: dict[str, Point] = field(default_factory=dict)
    objects: dict[str, list[tuple[str, str]]] = field(default_factory=dict)
    #: robot -> (the object it holds, its pickup op)
    held: dict[str, tuple[str, str]] = field(default_factory=dict)
    log: CarryLog = field(default_factory=CarryLog)

    def step(self, s: PlanStep) -> bool:
        """Replay ``s`` into its robot's open job (a new one if none); False when the
        state does not allow it."""
        if check_action(self.state, s.robot, s.action) is not None:
            return False
        job = self.open_.get(s.robot)
        if job is None:
            job = self.open_[s.robot] = Job(f"{s.robot}#{len(self.jobs)}", s.robot, "")
            self.jobs.append(job)
        job.steps.append(s.id)
        job.subtasks.add(s.subtask)
        if s.action.skill is Skill.GoToObject:
            self.drive[s.robot] = _point(self.state, s.action.target)
            self.log.drive(self.state, s.robot, s.action.target)
            apply_action(self.state, s.robot, s.action)
            return True
        self._operate(job, s)
        apply_action(self.state, s.robot, s.action)
        holding = self.state.robots[s.robot].holding
        _track(s, holding, self.held, self.objects)
        if holding is None:
            del self.open_[s.robot]  # hands empty: any other job may follow
        return True

    def _operate(self, job: Job, s: PlanStep) -> None:
        """A manipulation step, before it is applied: an operation of ``job`` where its
        robot stands, reached by the pending drive if any."""
        self.log.op(self.state, s.robot, s.id, s.action)
        job.skills.add(s.action.skill)
        if s.action.skill is Skill.PickupObject:
            job.lift = max(job.lift, self.state.objects[s.action.target].mass)
        rp = (self.state.robots[s.robot].position[0], self.state.robots[s.robot].position[1])
        goal = self.drive.pop(s.robot, None)
        job.ops.append(Op(s.id, rp, s.resources[0] if s.resources else s.action.target,
                          s.est_end - s.est_start, goal is not None, goal if goal is not None else rp))

    def fixed(self, jobs: Sequence[Job], spec: TaskSpec) -> set[str]:
        """The jobs that stay with their robot: those still open when the plan ends (its
        hands full), and those of a subtask the spec gives to a robot (a joining robot
        given work, an LLM's allocation): only the planner's own choices are the model's
        to change."""
        assigned = {t.id for t in spec.subtasks if t.robot is not None}
        return {j.id for j in self.open_.values()} | {j.id for j in jobs if j.subtasks & assigned}

    def shared(self) -> dict[str, list[tuple[str, str]]]:
        """The objects several spans use (one robot at a time on each)."""
        return {o: spans for o, spans in self.objects.items() if len(spans) > 1}

    def carry_orders(self, first_ops: set[str]) -> tuple[set[tuple[str, str]], set[tuple[str, str]]]:
        """The carries' orders (:meth:`CarryLog.orders`): every object's spans between
        two places, and those still held when the plan ends."""
        carried: dict[str, list[tuple[str, str | None]]] = {
            o: [(a, b) for a, b in spans if a != b] for o, spans in self.objects.items()}
        for obj, pickup in self.held.values():
            carried.setdefault(obj, []).append((pickup, None))
        return self.log.orders(carried, first_ops)


def _point(state: WorldState, thing: str) -> Point:
    """Where a drive to ``thing`` goes: its point on the floor, or its holder's."""
    o = state.objects[thing]
    return state.robots[o.held_by].position if o.held_by else (o.position[0], o.position[2])


def _track(s: PlanStep, holding: str | None, held: dict[str, tuple[str, str]],
           objects: dict[str, list[tuple[str, str]]]) -> None:
    """Spans of one robot per object: a pickup opens one, the release closes it; an op on
    an object nobody holds is a span of its own."""
    if s.robot in held and holding != held[s.robot][0]:
        obj, first = held.pop(s.robot)
        objects.setdefault(obj, []).append((first, s.id))
        if holding is None:
            return
    if holding is not None and s.robot not in held:
        held[s.robot] = (holding, s.id)
    elif s.action.target not in {h for h, _ in held.values()}:
        objects.setdefault(s.action.target, []).append((s.id, s.id))


def _groups(jobs: Sequence[Job], plan: MergedPlan, profiles: Mapping[str, RobotProfile], fixed: set[str]
            ) -> dict[str, tuple[str, ...]]:
    """Join the jobs serving a subtask with the same robot into groups (they move
    together); the robots able to take each group: every skill and the mass capacity
    it needs. A group stays with its robot when its subtask has several robots or it
    ends with the robot's hands full."""
    parent = {j.id: j.id for j in jobs}

    def root(x: str) -> str:
        while parent[x] != x:
            x = parent[x]
        return x

    first: dict[tuple[str, str], str] = {}
    robots_of: dict[str, set[str]] = {}
    for j in jobs:
        for t in j.subtasks:
            robots_of.setdefault(t, set()).add(j.robot)
            other = first.setdefault((t, j.robot), j.id)
            parent[root(j.id)] = root(other)
    members: dict[str, list[Job]] = {}
    for j in jobs:
        j.group = root(j.id)
        members.setdefault(j.group, []).append(j)
    out: dict[str, tuple[str, ...]] = {}
    for g, js in members.items():
        robot = js[0].robot
        pinned = any(j.id in fixed or any(len(robots_of[t]) > 1 for t in j.subtasks) for j in js)
        skills = set().union(*(j.skills for j in js))
        lift = max(j.lift for j in js)
        out[g] = (robot,) if pinned else tuple(r for r in plan.robots if all(profiles[r].can(k) for k in skills)
                                              and profiles[r].mass_capacity >= lift)
        if robot not in out[g]:
            out[g] = (robot, *out[g])
    return out


def _precedences(plan: MergedPlan, jobs: Sequence[Job]) -> tuple[list[tuple[str, str]], list[tuple[str, str]]]:
    """The plan's waits, from operation to operation (a drive maps to the operation it
    leads to, as a consumer, or to the one before it, as a producer): every one of them,
    not only the subtask dependencies, since the model does not know which other orders
    the state allows (a box is closed after the vases go in: the other order fails);
    waits for a spot are not among them (the simulator makes those), the model decides
    them. So the reference is the best schedule of these actions in this causal order,
    by any capable robots."""
    op_after: dict[str, str] = {}
    op_before: dict[str, str] = {}
    for j in jobs:
        last: str | None = None
        pending: list[str] = []
        ops = {o.step for o in j.ops}
        for sid in j.steps:
            if sid in ops:
                for p in pending:
                    op_after[p] = sid
                pending = []
                op_after[sid] = op_before[sid] = sid
                last = sid
            else:
                pending.append(sid)
                if last is not None:
                    op_before[sid] = last
    out: set[tuple[str, str]] = set()
    drives: set[tuple[str, str]] = set()
    for s in plan.steps:
        for p in s.after:
            prod, cons = op_before.get(p), op_after.get(s.id)
            if prod is not None and cons is not None and prod != cons:
                (drives if s.action.skill is Skill.GoToObject else out).add((prod, cons))
    chain: dict[str, str] = {}
    for j in jobs:  # a group's jobs in their order
        if j.group in chain:
            out.add((chain[j.group], j.ops[0].step))
        chain[j.group] = j.ops[-1].step
    return sorted(out), sorted(drives - out)


def arcs(problem: Problem) -> int:
    """How many arc literals the robots' circuits would take (the model's size)."""
    per: dict[str, int] = {}
    for j in problem.jobs:
        for r in problem.candidates[j.group]:
            per[r] = per.get(r, 0) + 1
    return sum((n + 1) ** 2 for n in per.values())


def interchangeable(problem: Problem) -> list[list[str]]:
    """Classes (two or more, names sorted) of robots the model cannot tell apart: the same
    skills, mass capacity, speed and start, candidates for the same groups (so none has a
    group pinned to it)."""
    classes: dict[tuple[object, ...], list[str]] = {}
    for r in sorted(problem.profiles):
        p = problem.profiles[r]
        key = (p.skills, p.mass_capacity, p.speed, problem.starts[r],
               tuple(r in c for c in problem.candidates.values()))
        classes.setdefault(key, []).append(r)
    return [c for c in classes.values() if len(c) > 1]


def _t(seconds: float) -> int:
    """Hundredths of a second, rounded down: every duration and drive rounded down keeps the
    model a relaxation of the simulation (a lower bound stays one) and the plan's own
    schedule, its starts rounded down too, a solution of it (the hint)."""
    return math.floor(seconds * SCALE + 1e-6)


class _Model:
    """The CP-SAT model of a :class:`Problem` (see the module docstring)."""

    def __init__(self, problem: Problem, hint: MergedPlan | None, tight: bool = False, cap: bool = True,
                 symmetry: bool = True) -> None:
        self.p = problem
        #: robots no constraint tells apart (:func:`interchangeable`), ordered by
        #: :meth:`_break_symmetry` in the strong model
        self.classes = interchangeable(problem) if tight and symmetry else []
        #: the hint's robot -> the robot of its class that takes its work (see :meth:`_relabel`)
        self.rename = self._relabel(hint) if hint is not None else {}
        #: :meth:`_within`'s drives posted without a robot where every candidate agrees,
        #: and time counted in :attr:`unit`
        self.tight = tight
        self.travelled: dict[tuple[float, Point, Point], int] = {}
        #: hundredths of a second per tick of the model: 1, or with ``tight`` the greatest
        #: common divisor of every duration and drive (:meth:`_quantum`)
        self.unit = self._quantum() if tight else 1
        self.m = cp_model.CpModel()
        self.horizon = max(self._horizon(), self._u(hint.makespan) + 1 if hint is not None else 0)
        #: the domains end at the hint's makespan (:meth:`_hinted_end`)
        self.capped = tight and cap and hint is not None
        if self.capped and hint is not None:
            self.horizon = self._hinted_end(hint)
        self.x: dict[tuple[str, str], cp_model.IntVar] = {}
        self.start: dict[str, cp_model.IntVar] = {}
        self.end: dict[str, cp_model.IntVar] = {}
        self.size: dict[str, int] = {}
        #: the sizes of held objects' spans (size, first op, last op), hinted with the rest
        self.span_sizes: list[tuple[cp_model.IntVar, str, str]] = []
        #: (robot, from job, to job) -> arc literal ("" is the depot), and its drive
        self.arc: dict[tuple[str, str, str], cp_model.IntVar] = {}
        self.drive: dict[tuple[str, str, str], int] = {}
        #: op -> the ops its drive waits for (see :attr:`Problem.drive_waits`)
        self.drive_after: dict[str, list[str]] = {}
        for a, b in [*problem.drive_waits, *problem.carry_waits]:
            self.drive_after.setdefault(b, []).append(a)
        # the order in which variables and constraints are posted is the search's (CP-SAT's
        # answer under a deterministic limit depends on it): keep it when changing these
        self._assignments()
        spots = self._operations()
        self._orders(spots)
        self._circuits()
        self._loads()
        self._objective()
        self._routes()
        self._break_symmetry()
        self.m.minimize(self.makespan)
        if hint is not None:
            self._hint(hint)

    def _assignments(self) -> None:
        """One robot for each group, among its candidates."""
        for g, robots in self.p.candidates.items():
            for r in robots:
                self.x[(g, r)] = self.m.new_bool_var(f"x[{g},{r}]")
            self.m.add_exactly_one(self.x[(g, r)] for r in robots)

    def _operations(self) -> dict[str, list[cp_model.IntervalVar]]:
        """Every operation's start, end and interval; the intervals by spot."""
        spots: dict[str, list[cp_model.IntervalVar]] = {}
        for j in self.p.jobs:
            for o in j.ops:
                s = self.start[o.step] = self.m.new_int_var(0, self.horizon, f"s[{o.step}]")
                e = self.end[o.step] = self.m.new_int_var(0, self.horizon, f"e[{o.step}]")
                self.size[o.step] = self._u(o.seconds)
                spots.setdefault(o.spot, []).append(self.m.new_interval_var(s, self.size[o.step], e, f"i[{o.step}]"))
        return spots

    def _orders(self, spots: Mapping[str, list[cp_model.IntervalVar]]) -> None:
        """Each job's operations in order (:meth:`_within`), one robot at a time at a spot
        and on an object, and the plan's (and the carries') orders."""
        for j in self.p.jobs:
            self._within(j)
        for ivs in spots.values():
            if len(ivs) > 1:
                self.m.add_no_overlap(ivs)
        for obj, spans in self.p.objects.items():
            self.m.add_no_overlap([self._span(obj, a, b) for a, b in spans])
        for a, b in self.p.orders():
            self.m.add(self.start[b] >= self.end[a])

    def _objective(self) -> None:
        """The makespan: the last operation's end, and no robot's load after it."""
        self.makespan = self.m.new_int_var(0, self.horizon, "makespan")
        self.m.add_max_equality(self.makespan, [self.end[j.ops[-1].step] for j in self.p.jobs])
        for load in self.load_end.values():
            self.m.add(self.makespan >= load)

    def _relabel(self, plan: MergedPlan) -> dict[str, str]:
        """The hint's robots renamed within each class of interchangeable ones so that the
        hint keeps :meth:`_break_symmetry`'s order (the first of a class to take a group
        in :attr:`Problem.candidates`' order is its first robot, and so on)."""
        del plan  # the jobs carry the plan's robots
        robot_of = {j.group: j.robot for j in self.p.jobs}
        rename: dict[str, str] = {}
        for cls in self.classes:
            used = list(dict.fromkeys(robot_of[g] for g, c in self.p.candidates.items()
                                      if cls[0] in c and robot_of[g] in cls))
            used += [r for r in cls if r not in used]
            rename.update(zip(used, cls, strict=True))
        return rename

    def _break_symmetry(self) -> None:
        """Exact symmetry breaking (value precedence) among interchangeable robots
        r1, r2, ... of a class: r(l+1) takes a group only if r(l) takes an earlier one.
        Any schedule, its robots of a class renamed in the order they first take a group,
        satisfies it and keeps its makespan, so the optimum does not change; the search no
        longer proves the same bound once per permutation of the team."""
        for cls in self.classes:
            groups = [g for g, c in self.p.candidates.items() if cls[0] in c]
            for prev, r in itertools.pairwise(cls):
                for i, g in enumerate(groups):
                    earlier = [self.x[(h, prev)] for h in groups[:i]]
                    if earlier:
                        self.m.add_bool_or(earlier).only_enforce_if(self.x[(g, r)])
                    else:
                        self.m.add(self.x[(g, r)] == 0)

    def _hinted_end(self, plan: MergedPlan) -> int:
        """The hint's makespan in ticks, as :meth:`_hint` gives it: no better schedule ends
        later, so every start and end lies within it (an exact cut of the domains;
        :func:`solve` drops it when the hint is no solution after all)."""
        ops = {o.step: o for j in self.p.jobs for o in j.ops}
        return max(self._u(s.est_start) + self._u(ops[s.id].seconds) for s in plan.steps if s.id in ops)

    def _span(self, obj: str, first: str, last: str) -> cp_model.IntervalVar:
        if first == last:
            return self.m.new_interval_var(self.start[first], self.size[first], self.end[first], f"o[{obj},{first}]")
        size = self.m.new_int_var(0, self.horizon, "")
        self.span_sizes.append((size, first, last))
        return self.m.new_interval_var(self.start[first], size, self.end[last], f"o[{obj},{first}]")

    def _u(self, seconds: float) -> int:
        """``seconds`` in ticks of the model, rounded down (see :func:`_t`)."""
        return _t(seconds) // self.unit

    def _travel(self, profile: RobotProfile, a: Point, b: Point) -> int:
        """A drive in ticks of the model (:func:`travel`, each computed once)."""
        key = (profile.speed, a, b)
        if key not in self.travelled:
            self.travelled[key] = _t(travel(profile, a, b, self.p.floor_plan))
        return self.travelled[key] // self.unit

    def _quantum(self) -> int:
        """The greatest common divisor of every operation's and every possible drive's
        hundredths (25 when, as on the navigation grid, all are quarter seconds). Time in
        these ticks loses no schedule: with every duration and offset a multiple of it,
        any schedule's starts rounded down to multiples of it keep every constraint. And
        each step of the search's bound is a whole tick, so the proof that nothing
        shorter exists closes in far fewer steps."""
        self.unit = 1
        sizes = [_t(o.seconds) for j in self.p.jobs for o in j.ops]
        for r, profile in self.p.profiles.items():
            mine = [j for j in self.p.jobs if r in self.p.candidates[j.group]]
            for j in mine:
                sizes.append(self._travel(profile, self.p.starts[r], j.ops[0].goal))
                sizes += [self._travel(profile, a.place, b.goal) for a, b in zip(j.ops, j.ops[1:], strict=False)
                          if b.drive]
                sizes += [self._travel(profile, j.ops[-1].place, j2.ops[0].goal) for j2 in mine if j2 is not j]
        return math.gcd(*sizes) or 1

    def _horizon(self) -> int:
        slowest = min(p.speed for p in self.p.profiles.values())
        span = 0.0
        for j in self.p.jobs:
            span += sum(o.seconds for o in j.ops) + len(j.ops) * 30.0 / slowest + 30.0 / slowest
        return self._u(span) + 1

    def _within(self, j: Job) -> None:
        """A job's operations in order, the drives between them at the speed of its robot."""
        for prev, o in zip(j.ops, j.ops[1:], strict=False):
            if not o.drive:
                self.m.add(self.start[o.step] >= self.end[prev.step])
                continue
            drives = {r: self._travel(self.p.profiles[r], prev.place, o.goal) for r in self.p.candidates[j.group]}
            least = min(drives.values())
            for after in [prev.step, *self.drive_after.get(o.step, ())]:
                if self.tight:
                    self.m.add(self.start[o.step] >= self.end[after] + least)
                for r, d in drives.items():
                    if d > least or not self.tight:
                        self.m.add(self.start[o.step] >= self.end[after] + d).only_enforce_if(self.x[(j.group, r)])

    def _circuits(self) -> None:
        """Per robot: a circuit over a depot and the jobs it may take (a job it does not
        take is skipped by its own loop), with the drives on the arcs."""
        for r, profile in self.p.profiles.items():
            mine = [j for j in self.p.jobs if r in self.p.candidates[j.group]]
            idle = self.arc[(r, "", "")] = self.m.new_bool_var(f"idle[{r}]")
            arcs_: list[tuple[int, int, cp_model.LiteralT]] = [(0, 0, idle)]
            for k, j in enumerate(mine, 1):
                lit = self.x[(j.group, r)]
                arcs_.append((k, k, ~lit))
                first = self.arc[(r, "", j.id)] = self.m.new_bool_var("")
                arcs_.append((0, k, first))
                d0 = self.drive[(r, "", j.id)] = self._travel(profile, self.p.starts[r], j.ops[0].goal)
                self.m.add(self.start[j.ops[0].step] >= d0).only_enforce_if(first)
                for after in self.drive_after.get(j.ops[0].step, ()):
                    self.m.add(self.start[j.ops[0].step] >= self.end[after] + d0).only_enforce_if(first)
                last = self.arc[(r, j.id, "")] = self.m.new_bool_var("")
                arcs_.append((k, 0, last))
                for k2, j2 in enumerate(mine, 1):
                    if k2 == k:
                        continue
                    lit2 = self.arc[(r, j.id, j2.id)] = self.m.new_bool_var("")
                    arcs_.append((k, k2, lit2))
                    d = self.drive[(r, j.id, j2.id)] = self._travel(profile, j.ops[-1].place, j2.ops[0].goal)
                    for after in [j.ops[-1].step, *self.drive_after.get(j2.ops[0].step, ())]:
                        self.m.add(self.start[j2.ops[0].step] >= self.end[after] + d).only_enforce_if(lit2)
            self.m.add_circuit(arcs_)

    def _inner(self, profile: RobotProfile, j: Job) -> int:
        """A job's own seconds for a robot of ``profile``: its operations and the drives
        between them."""
        return sum(self._u(o.seconds) for o in j.ops) + sum(
            self._travel(profile, a.place, b.goal) for a, b in zip(j.ops, j.ops[1:], strict=False) if b.drive)

    def _loads(self) -> None:
        """Redundant, for the bound: a robot's jobs fit before the makespan, each with its
        operations, the drives within it and the shortest drive into it (from the robot's
        start or from the end of any other job it may do)."""
        self.load_end: dict[str, cp_model.LinearExprT] = {}
        entry: dict[tuple[str, str], int] = {}
        for (r, _, b), d in self.drive.items():
            if b:
                entry[(r, b)] = min(d, entry.get((r, b), d))
        for r, profile in self.p.profiles.items():
            terms = []
            for j in self.p.jobs:
                if r not in self.p.candidates[j.group]:
                    continue
                terms.append((self._inner(profile, j) + entry[(r, j.id)]) * self.x[(j.group, r)])
            if terms:
                self.load_end[r] = sum(terms)

    def _routes(self) -> None:
        """Redundant, for the bound (issue 28: the load bound alone left 2-robot cells at
        62-76 % of the best schedule): a robot's whole route fits before the makespan, its
        jobs' own seconds plus the drive on every arc of its circuit. Linear in the arc
        literals, so the LP relaxation of the circuits (``linearization_level=2``) prices
        the drives between jobs as an assignment would, instead of each job's cheapest
        way in."""
        for r, profile in self.p.profiles.items():
            terms: list[cp_model.LinearExprT] = [
                self._inner(profile, j) * self.x[(j.group, r)] for j in self.p.jobs if r in self.p.candidates[j.group]]
            terms += [d * self.arc[key] for key, d in self.drive.items() if key[0] == r and d]
            if terms:
                self.m.add(self.makespan >= sum(terms))

    def routing(self) -> Routing:
        """The routing part of the model, for :func:`emboteam.hp.optimal_bound.route_bound`."""
        inner = {(r, j.id): self._inner(profile, j) for r, profile in self.p.profiles.items()
                 for j in self.p.jobs if r in self.p.candidates[j.group]}
        heads: dict[str, int] = {}
        tails: dict[str, int] = {}
        for j in self.p.jobs:
            for r in self.p.candidates[j.group]:
                for o, head, tail in self._offsets(self.p.profiles[r], j):
                    heads[o] = min(head, heads.get(o, head))
                    tails[o] = min(tail, tails.get(o, tail))
        return Routing({key: self.drive.get(key, 0) for key in self.arc}, inner, dict(self.size), self.horizon,
                       heads, tails)

    def _offsets(self, profile: RobotProfile, j: Job) -> list[tuple[str, int, int]]:
        """Each operation of ``j`` for a robot of ``profile``: the least ticks from the
        job's first operation's start to its start, and from its end to the job's end
        (its operations and the drives between them; waits only add)."""
        steps = [self._u(j.ops[0].seconds)]
        for a, b in zip(j.ops, j.ops[1:], strict=False):
            steps += [self._travel(profile, a.place, b.goal) if b.drive else 0, self._u(b.seconds)]
        total = sum(steps)
        out = []
        for k, o in enumerate(j.ops):
            head = sum(steps[:2 * k])
            out.append((o.step, head, total - head - steps[2 * k]))
        return out

    def _hint(self, plan: MergedPlan) -> None:
        starts_of = {s.id: s.est_start for s in plan.steps}
        robot_of = {j.group: self.rename.get(j.robot, j.robot) for j in self.p.jobs}
        for (g, r), lit in self.x.items():
            self.m.add_hint(lit, r == robot_of[g])
        for s in plan.steps:
            if s.id in self.start:
                self.m.add_hint(self.start[s.id], self._u(s.est_start))
                self.m.add_hint(self.end[s.id], self._u(s.est_start) + self.size[s.id])
        for size, first, last in self.span_sizes:
            end = self._u(starts_of[last]) + self.size[last]
            self.m.add_hint(size, end - self._u(starts_of[first]))
        order: dict[str, list[str]] = {r: [] for r in self.p.profiles}
        for j in sorted(self.p.jobs, key=lambda j: starts_of[j.ops[0].step]):
            order[self.rename.get(j.robot, j.robot)].append(j.id)
        for (r, a, b), lit in self.arc.items():
            seq = ["", *order[r], ""] if order[r] else ["", ""]
            self.m.add_hint(lit, any(seq[i] == a and seq[i + 1] == b for i in range(len(seq) - 1)))
        self.m.add_hint(self.makespan, max(self._u(s.est_start) + self.size[s.id] for s in plan.steps
                                           if s.id in self.start))


def solve(problem: Problem, hint: MergedPlan | None = None, limit: float = REFERENCE_LIMIT,
          linearization: int = 2, symmetry: bool = True, bound_limit: float = 0.0,
          check_limit: float = 0.0, portfolio: Portfolio = PORTFOLIO) -> Reference:
    """The optimal schedule of ``problem`` (or the best found and a bound), CP-SAT with
    seed 0 and ``limit`` seconds of *deterministic* time. ``linearization=2`` puts the
    circuits and the route lengths into the LP (``_Model._routes``): what proves the
    8-robot, 32-goal cells in 10 s (their bound was 55-90 % of the optimum); with it come
    the tight model (:class:`_Model`'s ``tight``: the quantum, domains ending at the hint's
    makespan, ``symmetry`` breaking among interchangeable robots) and the interleaved
    ``portfolio`` (:class:`Portfolio`; default :data:`PORTFOLIO`). ``linearization=1`` (``fast``'s small stage)
    keeps one worker and the model its plans were made with. Raises
    :class:`ScheduleTimeoutError` when the wall-clock safety net (:data:`WALL_FLOOR`,
    :data:`WALL_FACTOR`) stops it. ``bound_limit`` > 0 (strong model only): where the
    search ends unproven, that many more deterministic seconds on the route relaxation
    (:mod:`emboteam.hp.optimal_bound`), whose bound, if higher, is the answer's (and a
    proof when it reaches the best schedule). ``check_limit`` > 0 (strong model only): where
    the bound is still below the best schedule, that many more deterministic seconds of
    branch-and-check (:mod:`emboteam.hp.optimal_check`), one cap at a time from the bound
    up: a cap nothing ends by raises the bound a tick, a schedule found at it is the
    answer (proven: nothing ends earlier)."""
    strong = linearization >= 2
    model, solver, status, capped = _solved(problem, hint, strong, limit, linearization, symmetry, portfolio)
    tick = model.unit / SCALE
    if status not in (cp_model.OPTIMAL, cp_model.FEASIBLE):
        name = "infeasible" if status == cp_model.INFEASIBLE else "unknown"
        return Reference(name, 0.0, solver.best_objective_bound * tick, {}, {}, capped + solver.deterministic_time)
    answer: cp_model.CpSolver | CapCheck = solver
    best, bound = round(solver.objective_value), round(solver.best_objective_bound)
    used = capped + solver.deterministic_time
    if status == cp_model.FEASIBLE and strong and bound_limit > 0:
        routes = _route_bound(model, bound_limit, _chosen(model, solver), portfolio)
        bound, used = max(bound, routes.ticks), used + routes.deterministic
    if bound < best and strong and check_limit > 0:
        bound, found, spent = _check_caps(model, bound, best, check_limit, portfolio)
        used += spent
        if found is not None:
            best, answer = bound, found
    proven = status == cp_model.OPTIMAL or bound >= best
    chosen = _chosen(model, answer)
    assignment = {sid: chosen[j.group] for j in problem.jobs for sid in j.steps}
    starts = {sid: answer.value(v) * tick for sid, v in model.start.items()}
    return Reference("optimal" if proven else "feasible", best * tick, min(bound, best) * tick, assignment, starts,
                     used)


def _solved(problem: Problem, hint: MergedPlan | None, strong: bool, limit: float, linearization: int,
            symmetry: bool, portfolio: Portfolio
            ) -> tuple[_Model, cp_model.CpSolver, cp_model.CpSolverStatus, float]:
    """:func:`solve`'s search: the model with its domains capped at the hint's makespan
    (strong model), and without the cap when the hint was no schedule after all (in what
    is left of ``limit``). The model, its solver, its status and the deterministic
    seconds of a capped solve that found nothing."""
    model = _Model(problem, hint, tight=strong, symmetry=symmetry)
    solver, status = _run(model, _solver(strong, limit, linearization, portfolio))
    capped = 0.0
    if status in (cp_model.INFEASIBLE, cp_model.UNKNOWN) and model.capped:
        capped = solver.deterministic_time
        model = _Model(problem, hint, tight=strong, cap=False, symmetry=symmetry)
        solver, status = _run(model, _solver(strong, max(limit - capped, 0.0), linearization, portfolio))
    return model, solver, status, capped


def _chosen(model: _Model, answer: cp_model.CpSolver | CapCheck) -> dict[str, str]:
    """The robot ``answer`` gives each group of ``model``."""
    return {g: next(r for r in robots if answer.value(model.x[(g, r)])) for g, robots in model.p.candidates.items()}


def _route_bound(model: _Model, limit: float, chosen: Mapping[str, str], portfolio: Portfolio) -> RouteBound:
    """:func:`emboteam.hp.optimal_bound.route_bound` on ``model``'s routes, with the strong
    search's deterministic portfolio and safety net, hinted with the robots ``chosen``
    for the groups."""
    hint = {(g, r): r == chosen[g] for g, r in model.x}
    return route_bound(model.p, model.routing(), _solver(True, limit, 2, portfolio), hint)


def _check_caps(model: _Model, bound: int, best: int, limit: float, portfolio: Portfolio
                ) -> tuple[int, CapCheck | None, float]:
    """Branch-and-check (:func:`emboteam.hp.optimal_check.check_cap`) at caps ``bound``,
    ``bound`` + 1, ... below ``best`` within ``limit`` deterministic seconds in all: the
    bound proven, the check that found a schedule ending by it (None if none was found)
    and the seconds spent."""
    used = 0.0
    full = (model.m, model.x, model.makespan)
    while bound < best and used < limit:
        answer = check_cap(model.p, model.routing(), full, bound, limit - used, lambda s: _solver(True, s, 2, portfolio))
        used += answer.deterministic
        if answer.verdict == "none":
            bound += 1
            continue
        if answer.verdict == "found":
            return bound, answer, used
        break
    return bound, None, used


def _run(model: _Model, solver: cp_model.CpSolver) -> tuple[cp_model.CpSolver, cp_model.CpSolverStatus]:
    """One CP-SAT solve of ``model`` with ``solver`` (see :func:`solve`); the safety net raises."""
    return solver, solver.solve(model.m)


def _solver(strong: bool, limit: float, linearization: int, portfolio: Portfolio = PORTFOLIO) -> cp_model.CpSolver:
    """A CP-SAT solver with seed 0, ``limit`` deterministic seconds, the wall-clock safety
    net (:class:`_NetSolver`), and the strong search's ``portfolio`` or one
    worker. No ``max_time_in_seconds``: CP-SAT's own wall-clock limit stops early by a
    margin that grows with the load and leaves no trace in its answer (module docstring)."""
    solver = _NetSolver(limit)
    solver.parameters.num_workers = portfolio.workers if strong else 1
    if strong:
        solver.parameters.interleave_search = True
        solver.parameters.interleave_batch_size = portfolio.batch
        solver.parameters.subsolvers.extend(portfolio.searches)
        solver.parameters.use_lns = False
    solver.parameters.random_seed = 0
    solver.parameters.max_deterministic_time = limit
    solver.parameters.linearization_level = linearization
    return solver


class _NetSolver(cp_model.CpSolver):
    """A CP-SAT solver whose every solve either ends on its own (its deterministic limit, a
    proof) or, stopped by the wall-clock safety net (``WALL_FLOOR + WALL_FACTOR * limit``
    seconds, a timer calling ``stop_search``), raises :class:`ScheduleTimeoutError`: the
    only stop that depends on the machine is one we make and know of, so none of its
    answers does (issue 28)."""

    def __init__(self, limit: float) -> None:
        super().__init__()
        self.limit = limit

    def solve(self, model: cp_model.CpModel,
              solution_callback: cp_model.CpSolverSolutionCallback | None = None) -> cp_model.CpSolverStatus:
        net = WALL_FLOOR + WALL_FACTOR * self.limit
        stopped = threading.Event()

        def stop() -> None:
            stopped.set()
            self.stop_search()

        timer = threading.Timer(net, stop)
        timer.daemon = True
        timer.start()
        try:
            status = super().solve(model, solution_callback)
        finally:
            timer.cancel()
        if stopped.is_set():
            raise ScheduleTimeoutError(f"CP-SAT did not finish {self.limit:g} deterministic s of search within its "
                                       f"{net:g} s wall-clock safety net (the machine is overloaded)")
        return status


def reference(plan: MergedPlan, spec: TaskSpec, start: WorldState, limit: float = REFERENCE_LIMIT,
              max_arcs: int = MAX_ARCS, linearization: int = 2, bound_limit: float = 0.0,
              carries: bool = True, check_limit: float = 0.0, portfolio: Portfolio = PORTFOLIO) -> Reference | None:
    """CP-SAT's schedule for ``plan``'s actions, hinted with the plan itself; None when
    the plan cannot be modelled (its replay fails) or the model is larger than
    ``max_arcs`` (:func:`arcs`). ``carries``: as :func:`problem_of` (False only for a
    heuristic that simulates what it gets)."""
    problem = problem_of(plan, spec, start, carries)
    if problem is None or not problem.jobs or arcs(problem) > max_arcs:
        return None
    return solve(problem, plan, limit, linearization=linearization, bound_limit=bound_limit, check_limit=check_limit,
                 portfolio=portfolio)
