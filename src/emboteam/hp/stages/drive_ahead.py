"""The drive-ahead stage: drives that waited for another robot to bring their object go
to the place it is brought to instead (:mod:`emboteam.hp.drive_ahead`), the plan replayed
(the replay drives the rest of the way where the object is out of reach), merged and
simulated, and kept when its makespan is shorter. No planner call. Only for specs whose
subtasks are final and independent, as the other stages that rebuild a plan."""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.hp.drive_ahead import driven_ahead, retargets, waited
from emboteam.hp.merge import GroundedStep
from emboteam.hp.plan import MergedPlan
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.rebuilt import Rebuilt, adopted, replayed, shorter


def ahead(ctx: Context, plan: MergedPlan, sequence: Sequence[GroundedStep]) -> Rebuilt | None:
    """``plan`` (merged from ``sequence``) with its waiting drives driven ahead: the new
    plan and its sequence when it simulates shorter, else None."""
    if not ctx.independent or len(sequence) != len(plan.steps):
        return None
    targets = retargets(sequence, waited(plan))
    if not targets:
        return None
    first = min(targets)  # the steps before the first retargeted drive stay as they are
    what = f"driving ahead {len(targets)} drives"
    return shorter(replayed(ctx, driven_ahead(sequence, targets)[first:], what, head=sequence[:first]), plan, what)


def drive_ahead(ctx: Context, draft: Draft) -> Draft:
    """The draft with its waiting drives driven ahead, or the draft itself."""
    found = ahead(ctx, draft.plan, draft.record.sequence)
    if found is None:
        return draft
    return adopted(ctx, draft, found, f"drives that waited for their object went ahead to where it is "
                                      f"brought: makespan {draft.plan.makespan:.1f} -> {found.plan.makespan:.1f} s")
