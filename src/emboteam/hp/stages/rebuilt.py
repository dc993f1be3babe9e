"""A plan rebuilt by an improvement stage, and whether it replaces the draft.

The stages that rebuild a plan from a changed sequence (the route stage, drive ahead,
CP-SAT's schedule, the splits, the spot order) all do the same: replay the steps from the
start to the goal, merge and simulate them (the subtasks are final and independent: no
dependency waits), and keep the result only when its makespan is shorter. Written once
here, so that every stage rejects a rebuild for the same reasons and compares makespans
the same way.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from typing import NamedTuple

from emboteam.hp.merge import GroundedStep, SeqStep
from emboteam.hp.plan import MergedPlan
from emboteam.hp.stages.context import Context, Draft, Invalid
from emboteam.hp.stages.merge import finish_independent
from emboteam.hp.stages.replay import replay_to_goal
from emboteam.world.actions import Action
from emboteam.world.state import WorldState

log = logging.getLogger(__name__)

#: makespans closer than this are equal (the simulator's times are sums of floats)
EPS = 1e-6


class Rebuilt(NamedTuple):
    """A rebuilt plan and the grounded sequence it was merged from."""

    plan: MergedPlan
    sequence: list[GroundedStep]


def simulated(ctx: Context, sequence: list[GroundedStep], what: str) -> Rebuilt | None:
    """``sequence`` merged and simulated, or None when it fails in the simulator."""
    try:
        return Rebuilt(finish_independent(ctx, sequence), sequence)
    except Invalid as exc:
        log.debug("%s fails in the simulator: %s", what, exc)
        return None


def replayed(ctx: Context, steps: Sequence[SeqStep], what: str,
             repair: Callable[[WorldState, SeqStep], list[Action]] | None = None,
             head: Sequence[GroundedStep] = ()) -> Rebuilt | None:
    """``steps`` replayed from the start (after ``head``, see :func:`replay_to_goal`),
    merged and simulated; None when they no longer run, miss the goal or fail in the
    simulator."""
    grounded, why = replay_to_goal(ctx.start, steps, ctx.goal, repair, head, ctx.universe)
    if why is not None:
        log.debug("%s does not replay: %s", what, why)
        return None
    return simulated(ctx, grounded, what)


def shorter(found: Rebuilt | None, than: MergedPlan, what: str) -> Rebuilt | None:
    """``found`` when its makespan is shorter than ``than``'s, else None."""
    if found is None:
        return None
    log.debug("%s: makespan %.2f -> %.2f", what, than.makespan, found.plan.makespan)
    return found if found.plan.makespan < than.makespan - EPS else None


def adopted(ctx: Context, draft: Draft, found: Rebuilt, note: str) -> Draft:
    """The draft made of ``found`` (its record's sequence replaced), ``note`` added to the
    plan's notes."""
    ctx.notes.append(note)
    draft.record.sequence = found.sequence
    return Draft(found.plan, draft.record)
