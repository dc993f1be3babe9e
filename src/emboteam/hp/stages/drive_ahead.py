"""The drive-ahead stage: drives that waited for another robot to bring their object go
to the place it is brought to instead (:mod:`emboteam.hp.drive_ahead`), the plan replayed
(the replay drives the rest of the way where the object is out of reach), merged and
simulated, and kept when its makespan is shorter. No planner call. Only for specs whose
subtasks are final and independent, as the other stages that rebuild a plan."""

from __future__ import annotations

import logging
from collections.abc import Sequence

from emboteam.hp.drive_ahead import driven_ahead, retargets, waited
from emboteam.hp.merge import GroundedStep
from emboteam.hp.plan import MergedPlan
from emboteam.hp.stages.context import Context, Draft, Invalid
from emboteam.hp.stages.merge import finish_independent
from emboteam.hp.stages.replay import replay_to_goal

log = logging.getLogger(__name__)


def ahead(ctx: Context, plan: MergedPlan, sequence: Sequence[GroundedStep]
          ) -> tuple[MergedPlan, list[GroundedStep]] | None:
    """``plan`` (merged from ``sequence``) with its waiting drives driven ahead: the new
    plan and its sequence when it simulates shorter, else None."""
    if not ctx.independent or len(sequence) != len(plan.steps):
        return None
    targets = retargets(sequence, waited(plan))
    if not targets:
        return None
    first = min(targets)  # the steps before the first retargeted drive stay as they are
    grounded, why = replay_to_goal(ctx.start, driven_ahead(sequence, targets)[first:], ctx.spec.goal(),
                                   head=sequence[:first])
    if why is not None:
        log.debug("driving ahead fails: %s", why)
        return None
    try:
        other = finish_independent(ctx, grounded)
    except Invalid as exc:
        log.debug("driving ahead fails in the simulator: %s", exc)
        return None
    log.debug("driving ahead %d drives: makespan %.2f -> %.2f", len(targets), plan.makespan, other.makespan)
    return (other, grounded) if other.makespan < plan.makespan - 1e-6 else None


def drive_ahead(ctx: Context, draft: Draft) -> Draft:
    """The draft with its waiting drives driven ahead, or the draft itself."""
    found = ahead(ctx, draft.plan, draft.record.sequence)
    if found is None:
        return draft
    plan, sequence = found
    draft.record.sequence = sequence
    ctx.notes.append(f"drives that waited for their object went ahead to where it is brought: "
                     f"makespan {draft.plan.makespan:.1f} -> {plan.makespan:.1f} s")
    return Draft(plan, draft.record)
