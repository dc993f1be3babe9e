"""Branch-and-check at a cap: is there a schedule of :mod:`emboteam.hp.optimal`'s model
that ends by a given makespan? (issue 28)

Where the full model ends unproven one or two ticks above the route bound
(:mod:`emboteam.hp.optimal_bound`), the question left is one cap at a time: does any
schedule end by the bound? A *master* proposes an assignment of the groups to robots: the
route relaxation with its timed part (each job's start and end, the drives between a
robot's jobs, the plan's waits between jobs; ``relaxation(..., timed=True)``) capped at
the makespan. The *check* is the full model with that assignment fixed and the same cap
(the spots, the held objects, every operation's time: only the robots' orders are left to
it). A schedule found is one that ends by the cap; an assignment the check refutes is cut
from the master (a no-good on the groups with a choice) and the master asked again; a
master with no solution left proves that nothing ends by the cap. Exact: every schedule
ending by the cap meets the master with its own assignment, so no cut removes it. Every
solve runs on deterministic time out of one budget; when it runs out the answer is
``unknown``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from ortools.sat.python import cp_model

from emboteam.hp.optimal_bound import Routing, relaxation
from emboteam.hp.optimal_problem import Problem

#: (the full model, its assignment literals (group, robot), its makespan) for the check
Full = tuple[cp_model.CpModel, Mapping[tuple[str, str], cp_model.IntVar], cp_model.IntVar]


@dataclass
class CapCheck:
    """The answer at one cap: ``found`` (a schedule ends by it: the check's solver and
    model, to read it from), ``none`` (no schedule does) or ``unknown`` (the budget ran
    out); the deterministic seconds spent and the assignments the check refuted."""

    verdict: str
    deterministic: float = 0.0
    refuted: int = 0
    solver: cp_model.CpSolver | None = field(default=None, repr=False)
    model: cp_model.CpModel | None = field(default=None, repr=False)

    def value(self, var: cp_model.IntVar) -> int:
        """``var`` (of the full model) in the schedule found."""
        assert self.solver is not None and self.model is not None, "no schedule found"
        return int(self.solver.value(self.model.get_int_var_from_proto_index(var.index)))


def check_cap(problem: Problem, routing: Routing, full: Full, cap: int, limit: float,
              make_solver: Callable[[float], cp_model.CpSolver]) -> CapCheck:
    """Branch-and-check (module docstring) at ``cap`` ticks with ``limit`` deterministic
    seconds in all; ``make_solver(seconds)``: a deterministic solver with that limit."""
    master = relaxation(problem, routing, timed=True)
    master.m.add(master.makespan <= cap)
    chosen = {key: lit for key, lit in master.x.items() if len(problem.candidates[key[0]]) > 1}
    out = CapCheck("unknown")
    while out.deterministic < limit:
        solver = make_solver(limit - out.deterministic)
        status = solver.solve(master.m)
        out.deterministic += solver.deterministic_time
        if status == cp_model.INFEASIBLE:
            out.verdict = "none"
            return out
        if status not in (cp_model.OPTIMAL, cp_model.FEASIBLE) or out.deterministic >= limit:
            return out
        taken = {key for key, lit in master.x.items() if solver.value(lit)}
        check = _fixed(full, taken, cap)
        checker = make_solver(limit - out.deterministic)
        status = checker.solve(check)
        out.deterministic += checker.deterministic_time
        if status in (cp_model.OPTIMAL, cp_model.FEASIBLE):
            out.verdict, out.solver, out.model = "found", checker, check
            return out
        if status != cp_model.INFEASIBLE:
            return out
        out.refuted += 1
        master.m.add_bool_or([~lit for key, lit in chosen.items() if key in taken])
    return out


def _fixed(full: Full, taken: set[tuple[str, str]], cap: int) -> cp_model.CpModel:
    """The full model with the assignment ``taken`` fixed and the makespan capped, as a
    question of feasibility (no objective: any schedule by the cap answers it)."""
    model, x, makespan = full
    check = model.clone()
    check.clear_objective()  # type: ignore[no-untyped-call]
    for key, lit in x.items():
        check.add(check.get_int_var_from_proto_index(lit.index) == int(key in taken))
    check.add(check.get_int_var_from_proto_index(makespan.index) <= cap)
    return check
