"""The re-allocation stage: plan again with the clusters re-allocated from their measured
seconds (:mod:`emboteam.hp.rebalance`) when that promises the robot that ends last an
earlier end, or, when nothing does, the robot with the most work less of it; keep the
plan with the shorter makespan, and try again from it. A proposal that does not make the
plan shorter is not the end: its moves are excluded and the next best proposal for the
same plan is tried (at most ``REBALANCE_PASSES`` passes and ``REBALANCE_CALLS`` new
problems)."""

from __future__ import annotations

import logging
from collections.abc import Mapping

from emboteam.hp.rebalance import Job, finish_of, loads, measured_jobs, rebalance, work_of
from emboteam.hp.stages.context import Context, Draft, Fallback
from emboteam.hp.stages.decomposed import plan_decomposed
from emboteam.pddl.errors import PlanningError

log = logging.getLogger(__name__)

#: at most this many re-allocation passes (each a whole planning pass, kept when shorter;
#: the robots whose clusters stay get their plans from the cache), counting the proposals
#: that did not pay off
REBALANCE_PASSES = 8
#: no further pass once the passes have asked for this many problems not asked before in
#: this planning call (a pass of the 32-robot x 96-condition cell asks 10-20 new ones, of a
#: 2-4 robot cell 3-5: the robots that keep their clusters ask the same problems again, so
#: the budget buys more passes where the team is small). Counted in problems, not Fast
#: Downward processes, so that a warm or disk cache gives the same plan as a cold one
REBALANCE_CALLS = 32
#: a proposal that does not shorten the plan is not the end: the next best one without its
#: moves is tried from the same plan (measured seconds transfer only roughly: a robot's
#: other clusters change with its order of clusters; docs/planning.md)
REBALANCE_RETRY = True


def _rounded(xs: Mapping[str, float]) -> dict[str, float]:
    return {k: round(v, 1) for k, v in xs.items()}


def reallocate(ctx: Context, draft: Draft) -> Draft:
    """The draft re-planned from a better allocation, or the draft itself."""
    asked0 = len(ctx.solver.asked)
    tabu: set[tuple[str, str]] = set()  # moves that did not pay off from this plan
    plan, record, team = draft.plan, draft.record, ctx.team
    for _ in range(REBALANCE_PASSES):
        if len(ctx.solver.asked) - asked0 >= REBALANCE_CALLS:
            log.debug("rebalance: budget spent (%d problems)", len(ctx.solver.asked) - asked0)
            break
        jobs = measured_jobs(plan, record.cluster, record.assigned, record.candidates)
        # a robot's time is its work and its waits (for a spot, a tool, another robot):
        # the waits stay with it as a job that does not move, so the robot that ends
        # last is the one to relieve
        ends = finish_of(plan, team)
        work = work_of(plan)
        waits = [Job(f"wait:{r}", (r,), ends[r] - work.get(r, 0.0), ()) for r in team
                 if ends[r] - work.get(r, 0.0) > 1e-9]
        prefer = rebalance([*jobs, *waits], team, max(ends.values(), default=0.0), ctx.config.rebalance,
                           exclude=tabu)
        if prefer is None:
            # the robot that ends last cannot be relieved (it does one cluster and waits):
            # relieve the one with the most work, which may be what it waits for
            prefer = rebalance(jobs, team, max(work.values(), default=0.0), ctx.config.rebalance, exclude=tabu)
        if prefer is None:
            log.debug("rebalance: no proposal (ends %s, work %s)", _rounded(ends), _rounded(work))
            break
        moves = {(j.id, prefer[j.id]) for j in jobs if j.id in prefer and prefer[j.id] != j.robots[0]}
        if moves <= tabu:
            break  # nothing new to try ("lpt" proposes all again, ignoring the exclusions)
        again: list[str] = []
        try:
            other = plan_decomposed(ctx, prefer, again)
        except (Fallback, PlanningError):
            break
        log.debug("rebalance: moves %s, promised %s, makespan %.1f -> %.1f (work %s, %d problems)",
                  sorted(moves), _rounded(loads(jobs, team, prefer)), plan.makespan, other.plan.makespan,
                  _rounded(work), len(ctx.solver.asked) - asked0)
        if other.plan.makespan >= plan.makespan:
            if not REBALANCE_RETRY:
                break
            tabu |= moves
            continue
        ctx.notes[:] = [*again, f"re-allocated from the measured plans: makespan {plan.makespan:.1f} -> "
                        f"{other.plan.makespan:.1f} s"]
        plan, record = other.plan, other.record
        tabu = set()
    return Draft(plan, record)
