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
from dataclasses import dataclass

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


@dataclass(frozen=True)
class RouteBound:
    """The relaxation's proven lower bound in ticks, whether CP-SAT proved it optimal for
    the relaxation, and the deterministic seconds it took."""

    ticks: int
    proven: bool
    deterministic: float


def route_bound(problem: Problem, routing: Routing, solver: cp_model.CpSolver,
                hint: Mapping[tuple[str, str], bool] | None = None) -> RouteBound:
    """CP-SAT on the route relaxation (module docstring) with ``solver`` (its parameters:
    the caller's deterministic limit and search); ``hint``: (group, robot) -> taken, the
    full model's best schedule, to start the search near the answer."""
    m = cp_model.CpModel()
    x = {(g, r): m.new_bool_var("") for g, robots in problem.candidates.items() for r in robots}
    for g, robots in problem.candidates.items():
        m.add_exactly_one(x[(g, r)] for r in robots)
    position = {j.id: m.new_int_var(1, len(problem.jobs), "") for j in problem.jobs}
    makespan = m.new_int_var(0, routing.horizon, "makespan")
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
            lit = m.new_bool_var("")
            circuit.append((node[a], node[b], lit))
            if drive:
                route.append(drive * lit)
            if b:  # the jobs' positions along the circuit
                m.add(position[b] == (position[a] + 1 if a else 1)).only_enforce_if(lit)
        m.add_circuit(circuit)
        m.add(makespan >= sum(route))
    _orders(m, problem, routing, x, position)
    m.minimize(makespan)
    if hint:
        for key, lit in x.items():
            m.add_hint(lit, hint.get(key, False))
    status = solver.solve(m)
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
