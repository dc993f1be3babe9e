"""Re-allocation from measured plans: the allocator balances *estimates* (navigation along
a subtask's objects plus its manipulation), and plans differ from them by tens of seconds
(a drawer to open first, a knife to fetch, a detour lama-first takes). Once a plan is made
and simulated, every cluster's seconds are known; :func:`rebalance` assigns the clusters
again, longest first to the robot with the least measured work (LPT), and the planner
plans once more with that assignment when it promises a busiest robot at least
``GAIN`` shorter. The better plan (makespan in the simulator) is kept.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from emboteam.hp.plan import MergedPlan

#: re-plan only when the re-allocation promises the busiest robot this much less work
GAIN = 0.95
#: fewer clusters a robot could swap than this: no second pass (a task of two or three
#: conditions, as most of MACE-THOR's, rarely gains and would pay a second planning pass)
MIN_JOBS = 4
#: CP-SAT's deterministic time limit (about seconds of one core)
CP_SAT_BUDGET = 0.05


@dataclass(frozen=True)
class Job:
    """One allocated cluster: its measured seconds and the robots that may take it."""

    id: str
    robots: tuple[str, ...]
    seconds: float
    #: robots able to do it alone (empty: a team; it keeps ``robots``)
    candidates: tuple[str, ...]


def measured_jobs(plan: MergedPlan, cluster: Mapping[str, str], assigned: Mapping[str, tuple[str, ...]],
                  candidates: Mapping[str, tuple[str, ...]]) -> list[Job]:
    """The clusters of ``plan`` with the seconds their steps took in the simulation
    (``est_start``/``est_end``); ``cluster`` maps a subtask to its cluster's id,
    ``assigned`` a subtask to its robots, ``candidates`` a cluster to the robots able to
    do it alone."""
    seconds: dict[str, float] = {}
    robots: dict[str, tuple[str, ...]] = {}
    for s in plan.steps:
        c = cluster.get(s.subtask)
        if c is None:
            continue
        seconds[c] = seconds.get(c, 0.0) + (s.est_end - s.est_start)
        robots.setdefault(c, assigned.get(s.subtask, (s.robot,)))
    return [Job(c, robots[c], seconds[c], candidates.get(c, ())) for c in sorted(seconds)]


def work_of(plan: MergedPlan) -> dict[str, float]:
    out = {r: 0.0 for r in plan.robots}
    for s in plan.steps:
        out[s.robot] = out.get(s.robot, 0.0) + (s.est_end - s.est_start)
    return out


def lpt(jobs: Sequence[Job], team: Sequence[str]) -> tuple[dict[str, str], float]:
    """Longest job first to the least loaded candidate (ties: team order). Jobs without
    candidates (teams) keep their robots. Returns the assignment of the single-robot jobs
    and the busiest robot's work under it."""
    load = {r: 0.0 for r in team}
    for j in jobs:
        if not j.candidates:
            for r in j.robots:
                load[r] = load.get(r, 0.0) + j.seconds / max(len(j.robots), 1)
    rank = {r: i for i, r in enumerate(team)}
    out: dict[str, str] = {}
    for j in sorted((j for j in jobs if j.candidates), key=lambda j: (-j.seconds, j.id)):
        r = min(j.candidates, key=lambda x: (load.get(x, 0.0), rank.get(x, len(rank)), x))
        out[j.id] = r
        load[r] = load.get(r, 0.0) + j.seconds
    return out, max(load.values(), default=0.0)


def cp_sat(jobs: Sequence[Job], team: Sequence[str], hint: Mapping[str, str],
           deterministic_seconds: float = CP_SAT_BUDGET) -> tuple[dict[str, str], float] | None:
    """The assignment minimising the busiest robot's work (jobs without candidates keep
    their robots), by OR-Tools CP-SAT: one worker, a fixed seed and a *deterministic* time
    limit, so the answer does not depend on the machine's load; ``hint`` (the LPT
    assignment) is its starting solution. None when it proves nothing (no solution in the
    limit, or OR-Tools missing)."""
    try:
        from ortools.sat.python import cp_model
    except ImportError:  # pragma: no cover - ortools is a dependency
        return None
    scale = 10  # tenths of seconds
    model = cp_model.CpModel()
    fixed = {r: 0 for r in team}
    for j in jobs:
        if not j.candidates:
            for r in j.robots:
                fixed[r] = fixed.get(r, 0) + round(scale * j.seconds / max(len(j.robots), 1))
    movable = sorted((j for j in jobs if j.candidates), key=lambda j: j.id)
    x: dict[tuple[str, str], cp_model.IntVar] = {}
    for j in movable:
        for r in j.candidates:
            x[(j.id, r)] = model.new_bool_var(f"{j.id}@{r}")
            model.add_hint(x[(j.id, r)], hint.get(j.id) == r)
        model.add_exactly_one(x[(j.id, r)] for r in j.candidates)
    horizon = sum(fixed.values()) + sum(round(scale * j.seconds) for j in movable)
    busiest = model.new_int_var(0, horizon, "busiest")
    for r in sorted(fixed):
        model.add(busiest >= fixed[r] + sum(round(scale * j.seconds) * x[(j.id, r)]
                                            for j in movable if (j.id, r) in x))
    model.minimize(busiest)
    solver = cp_model.CpSolver()
    solver.parameters.num_workers = 1
    solver.parameters.random_seed = 0
    solver.parameters.max_deterministic_time = deterministic_seconds
    status = solver.solve(model)
    if status not in (cp_model.OPTIMAL, cp_model.FEASIBLE):
        return None
    out = {j.id: next(r for r in j.candidates if solver.value(x[(j.id, r)])) for j in movable}
    return out, solver.value(busiest) / scale


def rebalance(jobs: Sequence[Job], team: Sequence[str], busiest: float,
              solver: str = "cp-sat") -> dict[str, str] | None:
    """A new robot for each single-robot cluster when that promises a busiest robot of at
    most ``GAIN`` x ``busiest`` seconds (else None: not worth another planning pass).
    ``solver``: "lpt" (greedy) or "cp-sat" (:func:`cp_sat`, LPT as its hint; taken only
    where it beats LPT, so never worse than greedy)."""
    if len([j for j in jobs if j.candidates]) < MIN_JOBS:
        return None
    assignment, best = lpt(jobs, team)
    if solver == "cp-sat" and best > lower_bound(jobs, team) + 1e-9:
        exact = cp_sat(jobs, team, assignment)
        if exact is not None and exact[1] < best - 1e-9:
            assignment, best = exact
    if best > GAIN * busiest:
        return None
    return assignment


def lower_bound(jobs: Sequence[Job], team: Sequence[str]) -> float:
    """max(total work / robots, longest job): LPT at this bound is optimal already."""
    total = sum(j.seconds for j in jobs)
    return max(total / max(len(team), 1), max((j.seconds for j in jobs), default=0.0))
