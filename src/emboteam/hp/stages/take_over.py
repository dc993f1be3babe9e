"""The take-over stage: a switch or a door other robots waited for is done by one of them
(:mod:`emboteam.hp.take_over`), the plan replayed (the replay drives the robot within reach
where it must), merged and simulated, and kept when its makespan is shorter; then the next
one, from the plan kept. No planner call; at most :data:`TRIES` rebuilds (a count, never
seconds). Only for specs whose subtasks are final and independent, as the other stages
that rebuild a plan."""

from __future__ import annotations

import logging

from emboteam.hp.merge import GroundedStep
from emboteam.hp.plan import MergedPlan
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.rebuilt import Rebuilt, adopted, shorter, simulated
from emboteam.hp.stages.replay import replay_reusing
from emboteam.hp.take_over import candidates, taken_over
from emboteam.sim.rules import apply_action
from emboteam.world.checker import condition_holds

log = logging.getLogger(__name__)

#: rebuilds one planning call may try (each a replay, a merge and a simulation)
TRIES = 3
#: waiting robots tried per step (the ones free earliest)
ROBOTS_PER_STEP = 1


def _tried(ctx: Context, plan: MergedPlan, sequence: list[GroundedStep], index: int, robot: str
           ) -> Rebuilt | None:
    """The plan with step ``index`` done by ``robot``, when it simulates shorter. The
    steps before it are applied as they are; from it on, only what reads or writes what
    the change touches is grounded again (:func:`replay_reusing`)."""
    state = ctx.start.copy()
    for g in sequence[:index]:
        apply_action(state, g.robot, g.action)
    tail = [taken_over(sequence, index, robot), *sequence[index + 1:]]
    grounded, why = replay_reusing(state, tail, {0}, ctx.universe, [sequence[index]])
    if why is None and not all(condition_holds(c, state) for c in ctx.goal.conditions):
        why = "misses the goal"
    if why is not None:
        log.debug("%s taking over step %d fails: %s", robot, index, why)
        return None
    what = f"{robot} taking over step {index}"
    return shorter(simulated(ctx, [*sequence[:index], *grounded], what), plan, what)


def take_over(ctx: Context, draft: Draft) -> Draft:
    """The draft with the toggles others waited for done by a waiting robot (each kept
    when shorter), or the draft itself."""
    plan, sequence = draft.plan, draft.record.sequence
    if not ctx.independent or len(sequence) != len(plan.steps):
        return draft
    tries, skip = 0, set()
    while tries < TRIES:
        todo = [c for c in candidates(plan) if str(plan.steps[c.index].action) not in skip]
        if not todo:
            break
        c = todo[0]
        skip.add(str(plan.steps[c.index].action))
        for robot in c.robots[:ROBOTS_PER_STEP]:
            tries += 1
            found = _tried(ctx, plan, sequence, c.index, robot)
            if found is not None:
                step = plan.steps[c.index]
                draft = adopted(ctx, draft, found, f"{robot} did {step.action} itself instead of waiting for "
                                f"{step.robot}: makespan {plan.makespan:.1f} -> {found.plan.makespan:.1f} s")
                plan, sequence = draft.plan, draft.record.sequence
                break
    return draft
