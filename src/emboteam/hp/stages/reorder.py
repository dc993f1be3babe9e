"""The spot-order stage: move blocks of steps that waited at a shared spot ahead of the
steps that made them wait (:mod:`emboteam.hp.spot_order`), one at a time, each replayed,
merged and simulated; a move is kept when the makespan is shorter, and the search goes on
from it (at most ``spot_order.TRIES`` moves tried in all: a count, not a clock). Only for
specs whose subtasks are final and independent, as the split."""

from __future__ import annotations

import logging

from emboteam.hp import spot_order
from emboteam.hp.merge import GroundedStep
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.rebuilt import Rebuilt, simulated
from emboteam.hp.stages.replay import replay_reusing
from emboteam.pddl.domain import Universe
from emboteam.sim.rules import apply_action
from emboteam.world.checker import condition_holds

log = logging.getLogger(__name__)


def reorder(ctx: Context, draft: Draft) -> Draft:
    """The draft with blocks moved ahead at their spots, or the draft itself."""
    if not ctx.independent or len(draft.record.sequence) != len(draft.plan.steps):
        return draft
    plan, seq = draft.plan, draft.record.sequence
    universe = ctx.universe
    tried = 0
    while tried < spot_order.TRIES:
        options = spot_order.candidates(plan, spot_order.TRIES - tried)
        if not options:
            break
        for block, new_order in options:
            tried += 1
            moved = _moved(ctx, seq, block, new_order, universe)
            if moved is None:
                continue
            other, candidate = moved
            log.debug("moving %s: makespan %.1f -> %.1f", block, plan.makespan, other.makespan)
            if other.makespan < plan.makespan - 1e-6:
                ctx.notes.append(f"{block.robot}'s steps at {block.spot} moved ahead ({block.wait:.1f} s of "
                                 f"waiting): makespan {plan.makespan:.1f} -> {other.makespan:.1f} s")
                plan, seq = other, candidate
                break
        else:
            break
    draft.record.sequence = seq
    return Draft(plan, draft.record)


def _moved(ctx: Context, seq: list[GroundedStep], block: spot_order.Block, new_order: list[int],
           universe: Universe) -> Rebuilt | None:
    """The plan with ``block`` moved (the sequence in ``new_order``), or None when it no
    longer runs, misses the goal or fails in the simulator."""
    p = next(i for i, k in enumerate(new_order) if i != k)
    state = ctx.start.copy()
    for g in seq[:p]:
        apply_action(state, g.robot, g.action)
    grounded, why = replay_reusing(state, [seq[k] for k in new_order[p:]],
                                   {i for i, k in enumerate(new_order[p:]) if seq[k].robot == block.robot}, universe)
    if why is None and not all(condition_holds(c, state) for c in ctx.goal.conditions):
        why = "misses the goal"
    if why is not None:
        log.debug("moving %s fails: %s", block, why)
        return None
    return simulated(ctx, [*seq[:p], *grounded], f"moving {block}")
