"""Re-allocation from measured plans: the allocator balances *estimates* (navigation along
a subtask's objects plus its manipulation), and plans differ from them by tens of seconds
(a drawer to open first, a knife to fetch, a detour lama-first takes). Once a plan is made
and simulated, every cluster's seconds are known, and :func:`rebalance` proposes another
assignment; the planner plans once more with it when it promises a busiest robot at least
``1 - GAIN`` shorter, and keeps the plan with the shorter makespan in the simulator.

Two ways (``PlannerConfig.rebalance``):

- ``"cp-sat"`` (default): move at most ``MAX_MOVES`` clusters, as few as the best balance
  needs, chosen by OR-Tools CP-SAT (the best single move, found greedily, is its hint and
  its fallback, so it is never worse than greedy); the planner repeats this up to
  ``REBALANCE_PASSES`` times, and a proposal that does not shorten the plan is followed
  by the next best one without its moves (``exclude``). Few moves keep the other
  robots' plans (and their cache entries): measured seconds transfer to another robot only
  roughly (a cluster's first drive depends on where its robot comes from, and a robot's
  order of clusters changes), and a whole new assignment from them was longer than the
  first plan more often than not (docs/planning.md, "Makespan against the resource-aware
  bound").
- ``"lpt"``: every cluster again, longest first to the least loaded robot.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from emboteam.hp.plan import MergedPlan

if TYPE_CHECKING:
    from ortools.sat.python import cp_model

#: re-plan only when the proposal promises the busiest robot at most this share of its work
#: (0.95 when a proposal that did not pay off ended the re-allocation; with the next one
#: tried, smaller promises are worth a pass)
GAIN = 0.98
#: fewer clusters a robot could swap than this: no second pass (a task of two or three
#: conditions, as most of MACE-THOR's, rarely gains and would pay a second planning pass)
MIN_JOBS = 4
#: clusters one pass may move to another robot ("cp-sat")
MAX_MOVES = 2
#: CP-SAT's deterministic time limit (about seconds of one core)
CP_SAT_BUDGET = 0.05


@dataclass(frozen=True)
class Job:
    """One allocated cluster: its measured seconds, the robots that did it (the first is
    the one it moves from) and the robots that may take it."""

    id: str
    robots: tuple[str, ...]
    seconds: float
    #: robots able to do it alone (empty: a team, or named by the front end; it stays)
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


def finish_of(plan: MergedPlan, team: Sequence[str]) -> dict[str, float]:
    """When each robot ends its last step (work and waits)."""
    out = {r: 0.0 for r in team}
    for s in plan.steps:
        out[s.robot] = max(out.get(s.robot, 0.0), s.est_end)
    return out


def loads(jobs: Sequence[Job], team: Sequence[str], assignment: Mapping[str, str]) -> dict[str, float]:
    """Seconds per robot when the movable jobs go where ``assignment`` says (the others,
    and movable jobs it does not name, stay with their robots)."""
    out = {r: 0.0 for r in team}
    for j in jobs:
        where = (assignment[j.id],) if j.candidates and j.id in assignment else j.robots
        for r in where:
            out[r] = out.get(r, 0.0) + j.seconds / max(len(where), 1)
    return out


def best_move(jobs: Sequence[Job], team: Sequence[str], exclude: Collection[tuple[str, str]] = ()
              ) -> tuple[dict[str, str], float]:
    """The greedy proposal: the one move of a cluster off the busiest robot that leaves
    the busiest robot least work (none if no move helps). Returns the assignment of the
    movable jobs and the busiest robot's work under it."""
    current = {j.id: j.robots[0] for j in jobs if j.candidates}
    load = loads(jobs, team, current)
    best, best_max = dict(current), max(load.values(), default=0.0)
    top = max(load, key=lambda r: (load[r], r), default=None)
    for j in sorted(jobs, key=lambda j: j.id):
        if not j.candidates or current[j.id] != top:
            continue
        for r in j.candidates:
            if r == top or (j.id, r) in exclude:
                continue
            trial = {**current, j.id: r}
            m = max(loads(jobs, team, trial).values())
            if m < best_max - 1e-9:
                best, best_max = trial, m
    return best, best_max


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
           deterministic_seconds: float = CP_SAT_BUDGET, max_moves: int | None = None,
           exclude: Collection[tuple[str, str]] = ()) -> tuple[dict[str, str], float] | None:
    """The assignment minimising the busiest robot's work (jobs without candidates stay), by OR-Tools CP-SAT: one worker, a fixed seed and a *deterministic* time
    limit, so the answer does not depend on the machine's load; ``hint`` is its starting
    solution. ``max_moves``: at most that many jobs leave their first robot, and among the
    best balances the one with the fewest moves; ``exclude``: (job, robot) pairs not to
    propose (a job's own robot stays allowed). None when it finds nothing (no solution
    in the limit, or OR-Tools missing)."""
    try:
        from ortools.sat.python import cp_model
    except ImportError:  # pragma: no cover - ortools is a dependency
        return None
    model = cp_model.CpModel()
    fixed = _fixed_tenths(jobs, team)
    movable = sorted((j for j in jobs if j.candidates), key=lambda j: j.id)
    x = _choices(model, movable, hint, exclude)
    horizon = sum(fixed.values()) + sum(_tenths(j.seconds) for j in movable)
    busiest = model.new_int_var(0, horizon, "busiest")
    for r in sorted(fixed):
        model.add(busiest >= fixed[r] + sum(_tenths(j.seconds) * x[(j.id, r)]
                                            for j in movable if (j.id, r) in x))
    _objective(model, movable, x, busiest, max_moves)
    solver = cp_model.CpSolver()
    solver.parameters.num_workers = 1
    solver.parameters.random_seed = 0
    solver.parameters.max_deterministic_time = deterministic_seconds
    status = solver.solve(model)
    if status not in (cp_model.OPTIMAL, cp_model.FEASIBLE):
        return None
    out = {j.id: next(r for r in j.candidates if (j.id, r) in x and solver.value(x[(j.id, r)])) for j in movable}
    return out, solver.value(busiest) / _SCALE


#: CP-SAT works in integers: seconds in tenths
_SCALE = 10


def _tenths(seconds: float) -> int:
    return round(_SCALE * seconds)


def _fixed_tenths(jobs: Sequence[Job], team: Sequence[str]) -> dict[str, int]:
    """Each robot's work in the jobs that stay (no candidates: shared equally by the robots
    that did them), in tenths of seconds; every robot of ``team`` has an entry."""
    fixed = {r: 0 for r in team}
    for j in jobs:
        if not j.candidates:
            for r in j.robots:
                fixed[r] = fixed.get(r, 0) + round(_SCALE * j.seconds / max(len(j.robots), 1))
    return fixed


def _choices(model: cp_model.CpModel, movable: Sequence[Job], hint: Mapping[str, str],
             exclude: Collection[tuple[str, str]]) -> dict[tuple[str, str], cp_model.IntVar]:
    """One Boolean per (job, robot) it may go to, hinted from ``hint``, exactly one per job
    (an excluded pair has none, unless the robot is the job's own)."""
    x: dict[tuple[str, str], cp_model.IntVar] = {}
    for j in movable:
        for r in j.candidates:
            if (j.id, r) in exclude and r != j.robots[0]:
                continue
            x[(j.id, r)] = model.new_bool_var(f"{j.id}@{r}")
            model.add_hint(x[(j.id, r)], hint.get(j.id) == r)
        model.add_exactly_one(x[(j.id, r)] for r in j.candidates if (j.id, r) in x)
    return x


def _objective(model: cp_model.CpModel, movable: Sequence[Job], x: Mapping[tuple[str, str], cp_model.IntVar],
               busiest: cp_model.IntVar, max_moves: int | None) -> None:
    """Minimise the busiest robot's work; with ``max_moves``, at most that many clusters
    leave their robot, as few as the best balance needs (the moves break ties only)."""
    if max_moves is None:
        model.minimize(busiest)
        return
    stay = [x[(j.id, j.robots[0])] for j in movable if (j.id, j.robots[0]) in x]
    moved = len(movable) - sum(stay)
    model.add(moved <= max_moves)
    model.minimize(busiest * (len(movable) + 1) + moved)


def rebalance(jobs: Sequence[Job], team: Sequence[str], busiest: float,
              solver: str = "cp-sat", exclude: Collection[tuple[str, str]] = ()) -> dict[str, str] | None:
    """A robot for each movable cluster when that promises a busiest robot of at most
    ``GAIN`` x ``busiest`` seconds (else None: not worth another planning pass).
    ``solver``: "cp-sat" (at most ``MAX_MOVES`` moves, :func:`cp_sat`, with
    :func:`best_move` as hint and fallback: never worse than the greedy move) or "lpt"
    (:func:`lpt`, everything again). ``exclude``: (cluster, robot) moves not to propose
    (they were tried from this plan and did not pay off; "cp-sat" only)."""
    if len([j for j in jobs if j.candidates]) < MIN_JOBS:
        return None
    current = {j.id: j.robots[0] for j in jobs if j.candidates}
    now = loads(jobs, team, current)
    top = max(now, key=lambda r: (now[r], r), default=None)
    if sum(1 for r in current.values() if r == top) < 2:
        # the robot that ends last does one cluster: moved elsewhere, that cluster meets the
        # same spots and tools, and its waits go with it
        return None
    if solver == "lpt":
        assignment, best = lpt(jobs, team)
    else:
        assignment, best = best_move(jobs, team, exclude)
        exact = cp_sat(jobs, team, assignment, max_moves=MAX_MOVES, exclude=exclude)
        if exact is not None and exact[1] < best - 1e-9:
            assignment, best = exact
    if best > GAIN * busiest:
        return None
    return assignment
