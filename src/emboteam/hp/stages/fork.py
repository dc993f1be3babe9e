"""The critical cluster split in two, tried beside the plan as it is.

Splitting a robot's long cluster in two (:func:`~emboteam.hp.stages.split.split_clusters`)
before the other improvements shortens some plans a lot and lengthens others once the
later stages have run (FloorPlan1, goal seed 1: 8 x 32 27.25 -> 17.0 s, but 32 x 32 18.0 ->
18.25 s: the route stage finds less after the split), so it is off as a stage of its own.
Here, when the longest cluster one robot does is far above the team's mean load, the
improvements run twice: on the plan as it is (first, so that plan is the one made without
this stage), and on the plan with the cluster split; the shorter final plan is kept. A tie
keeps the first. Only for plans of at most :data:`MAX_STEPS` steps: the second pass doubles
the improvements' cost, and on the large plans the split did not win (FloorPlan1 32 x 128,
goal seed 2: 62.75 s as it is, 92.5 s split, both after the improvements).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from emboteam.hp import cluster_split
from emboteam.hp.stages.context import Context, Draft, Fallback, Record
from emboteam.hp.stages.route import ROUTE_STEPS
from emboteam.hp.stages.split import able_of, split_clusters

#: split only a cluster whose robot's seconds on it exceed this factor x the team's mean
#: load (the plan's work / the team's robots)
LOAD_EXCESS = 1.3
#: only plans of at most this many steps (the route stage's small plans)
MAX_STEPS = ROUTE_STEPS

Stage = Callable[[Context, Draft], Draft]


def worth_splitting(ctx: Context, draft: Draft) -> bool:
    """Is the longest cluster one robot does more than ``LOAD_EXCESS`` x the team's mean
    load, on a plan of at most ``MAX_STEPS`` steps whose subtasks are final and independent."""
    plan = draft.plan
    if not ctx.independent or len(plan.steps) > MAX_STEPS or not ctx.team:
        return False
    target = cluster_split.find_target(plan, draft.record.cluster, able_of(ctx))
    if target is None:
        return False
    mean = sum(s.est_end - s.est_start for s in plan.steps) / len(ctx.team)
    return target.seconds > LOAD_EXCESS * mean


def improved(ctx: Context, draft: Draft, stages: Sequence[Stage]) -> Draft:
    """``draft`` through ``stages``; and, when :func:`worth_splitting`, its critical
    cluster split in two and that plan through ``stages`` too: the shorter of the two (the
    notes of the one kept)."""
    other = _copy(draft) if worth_splitting(ctx, draft) else None
    before = list(ctx.notes)
    kept = _through(ctx, draft, stages)
    if other is None:
        return kept
    notes = list(ctx.notes)  # the stages may rewrite the notes (re-allocation does)
    ctx.notes[:] = before
    try:
        split = split_clusters(ctx, other)
        tried = _through(ctx, split, stages) if split.plan is not other.plan else None
    except Fallback:  # the split's plan could not be improved: the plan as it is stands
        tried = None
    if tried is not None and tried.plan.makespan < kept.plan.makespan - 1e-6:
        ctx.notes.append(f"the longest cluster split in two before the improvements: makespan "
                         f"{kept.plan.makespan:.1f} -> {tried.plan.makespan:.1f} s")
        return tried
    ctx.notes[:] = notes
    return kept


def _through(ctx: Context, draft: Draft, stages: Sequence[Stage]) -> Draft:
    for stage in stages:
        draft = stage(ctx, draft)
    return draft


def _copy(draft: Draft) -> Draft:
    """The draft with its own record (the stages replace the record's sequence)."""
    r = draft.record
    return Draft(draft.plan, Record(dict(r.cluster), dict(r.assigned), dict(r.candidates), list(r.sequence)))
