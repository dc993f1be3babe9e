"""A second lower bound on the optimal makespan of :mod:`emboteam.hp.optimal`'s model, from
the robots' routes alone (issue 28).

Where the full model ends unproven (FloorPlan1 2 x 24 seeds 3 and 4, FloorPlan201 4 x 24
seed 4), its search spends the deterministic time on the timing of the operations; its
bound stays at the LP's balanced split of the routes. This relaxation keeps only what
decides a route's length: which robot takes each group, each robot's circuit over its
jobs with the drive on every arc, each route (its jobs' own seconds plus the drives)
before the makespan, and the order the plan's waits impose on jobs of one robot
(positions along the circuit, Miller-Tucker-Zemlin style). Every schedule of the full
model satisfies all of it, so its optimum, and any bound CP-SAT proves on it, is a lower
bound of the full model's optimum; without the operations' times and the spots it is
small enough that CP-SAT proves its optimum where the full model's bound stalls.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from ortools.sat.python import cp_model

from emboteam.hp.optimal_problem import Problem


@dataclass(frozen=True)
class Routing:
    """The full model's routing part, in its ticks: every arc of every robot's circuit
    (robot, from job, to job; "" is the depot) with its drive, each candidate job's own
    ticks (its operations and the drives within it) per robot, the op sizes, and the
    horizon."""

    arcs: Mapping[tuple[str, str, str], int]
    inner: Mapping[tuple[str, str], int]
    sizes: Mapping[str, int]
    horizon: int
    #: op -> the least ticks from its job's first operation's start to its start, and from
    #: its end to the job's end, over the job's candidate robots (for :func:`relaxation`'s
    #: ``timed`` part)
    heads: Mapping[str, int] = field(default_factory=dict)
    tails: Mapping[str, int] = field(default_factory=dict)


@dataclass(frozen=True)
class RouteBound:
    """The relaxation's proven lower bound in ticks, whether CP-SAT proved it optimal for
    the relaxation, and the deterministic seconds it took."""

    ticks: int
    proven: bool
    deterministic: float


@dataclass
class Relaxation:
    """The route relaxation as a CP-SAT model (:func:`relaxation`): its (group, robot)
    assignment literals, every arc's literal (keys as :attr:`Routing.arcs`), each robot's
    route length, and the makespan."""

    m: cp_model.CpModel
    x: dict[tuple[str, str], cp_model.IntVar]
    arcs: dict[tuple[str, str, str], cp_model.IntVar]
    routes: dict[str, cp_model.LinearExprT]
    makespan: cp_model.IntVar


def relaxation(problem: Problem, routing: Routing, timed: bool = False) -> Relaxation:
    """The route relaxation (module docstring) of ``problem``, not yet minimised."""
    m = cp_model.CpModel()
    x = {(g, r): m.new_bool_var("") for g, robots in problem.candidates.items() for r in robots}
    for g, robots in problem.candidates.items():
        m.add_exactly_one(x[(g, r)] for r in robots)
    position = {j.id: m.new_int_var(1, len(problem.jobs), "") for j in problem.jobs}
    makespan = m.new_int_var(0, routing.horizon, "makespan")
    lits: dict[tuple[str, str, str], cp_model.IntVar] = {}
    routes: dict[str, cp_model.LinearExprT] = {}
    times = _Times(m, problem, routing, makespan) if timed else None
    for r in problem.profiles:
        mine = [j for j in problem.jobs if r in problem.candidates[j.group]]
        if not mine:
            continue
        node = {j.id: k for k, j in enumerate(mine, 1)} | {"": 0}
        circuit: list[tuple[int, int, cp_model.LiteralT]] = [(node[j.id], node[j.id], ~x[(j.group, r)]) for j in mine]
        route: list[cp_model.LinearExprT] = [routing.inner[(r, j.id)] * x[(j.group, r)] for j in mine]
        for (robot, a, b), drive in routing.arcs.items():
            if robot != r:
                continue
            lit = lits[(robot, a, b)] = m.new_bool_var("")
            circuit.append((node[a], node[b], lit))
            if drive:
                route.append(drive * lit)
            if b:  # the jobs' positions along the circuit
                m.add(position[b] == (position[a] + 1 if a else 1)).only_enforce_if(lit)
            if times is not None and b:
                times.arc(a, b, drive, lit)
        if times is not None:
            for j in mine:
                times.job(j.id, routing.inner[(r, j.id)], x[(j.group, r)])
        m.add_circuit(circuit)
        routes[r] = sum(route)
        m.add(makespan >= routes[r])
    _orders(m, problem, routing, x, position)
    if times is not None:
        times.waits()
    return Relaxation(m, x, lits, routes, makespan)


def route_bound(problem: Problem, routing: Routing, solver: cp_model.CpSolver,
                hint: Mapping[tuple[str, str], bool] | None = None, timed: bool = False) -> RouteBound:
    """CP-SAT on the route relaxation (module docstring) with ``solver`` (its parameters:
    the caller's deterministic limit and search); ``hint``: (group, robot) -> taken, the
    full model's best schedule, to start the search near the answer."""
    rel = relaxation(problem, routing, timed)
    rel.m.minimize(rel.makespan)
    if hint:
        for key, lit in rel.x.items():
            rel.m.add_hint(lit, hint.get(key, False))
    status = solver.solve(rel.m)
    if status == cp_model.INFEASIBLE:  # the horizon cut every route: nothing fits below it
        return RouteBound(routing.horizon + 1, True, solver.deterministic_time)
    return RouteBound(int(solver.best_objective_bound), status == cp_model.OPTIMAL, solver.deterministic_time)


def _orders(m: cp_model.CpModel, problem: Problem, routing: Routing, x: Mapping[tuple[str, str], cp_model.IntVar],
            position: Mapping[str, cp_model.IntVar]) -> None:
    """A job that waits for another's operation comes later on a robot that does both: its
    operation starts after the producer's ends, and a robot's jobs do not overlap. Only
    for producers of positive length (with zero seconds both could happen at one instant)."""
    job_of = {o.step: j for j in problem.jobs for o in j.ops}
    seen: set[tuple[str, str]] = set()
    for a, b in problem.orders():
        ja, jb = job_of[a], job_of[b]
        if ja.id == jb.id or routing.sizes[a] <= 0 or (ja.id, jb.id) in seen:
            continue
        seen.add((ja.id, jb.id))
        both = set(problem.candidates[ja.group]) & set(problem.candidates[jb.group])
        for r in sorted(both):
            enforce = [x[(ja.group, r)]] if ja.group == jb.group else [x[(ja.group, r)], x[(jb.group, r)]]
            m.add(position[jb.id] >= position[ja.id] + 1).only_enforce_if(enforce)


class _Times:
    """The timed part of the relaxation: each job's first operation's start and last
    operation's end, its robot's drives between jobs, and the plan's waits between jobs
    (a producer ends no earlier than its job's start plus its least head; a consumer's
    job ends no earlier than the producer's end plus the consumer and its least tail).
    Every schedule of the full model meets it (its operations in their jobs, spots and
    held objects left out); with it a route solution that the waits would push past the
    makespan is no solution, where the routes alone count only lengths."""

    def __init__(self, m: cp_model.CpModel, problem: Problem, routing: Routing, makespan: cp_model.IntVar) -> None:
        self.m, self.p, self.routing = m, problem, routing
        self.start = {j.id: m.new_int_var(0, routing.horizon, "") for j in problem.jobs}
        self.end = {j.id: m.new_int_var(0, routing.horizon, "") for j in problem.jobs}
        for v in self.end.values():
            m.add(makespan >= v)

    def arc(self, a: str, b: str, drive: int, lit: cp_model.IntVar) -> None:
        self.m.add(self.start[b] >= (self.end[a] + drive if a else drive)).only_enforce_if(lit)

    def job(self, job: str, inner: int, lit: cp_model.IntVar) -> None:
        self.m.add(self.end[job] >= self.start[job] + inner).only_enforce_if(lit)

    def waits(self) -> None:
        job_of = {o.step: j for j in self.p.jobs for o in j.ops}
        first = {j.ops[0].step for j in self.p.jobs}
        for a, b in self.p.orders():
            ja, jb = job_of[a], job_of[b]
            if ja.id == jb.id:
                continue
            ends = self.start[ja.id] + self.routing.heads[a] + self.routing.sizes[a]
            self.m.add(self.end[jb.id] >= ends + self.routing.sizes[b] + self.routing.tails[b])
            if b in first:
                self.m.add(self.start[jb.id] >= ends)
