"""Interleave a round's accepted units by time, so the merge orders their conflicts the
way robots will meet them.

Units planned in one round are accepted one after another: each unit's plan is replayed
on the state the units before it leave. The merge then orders two robots' conflicting
steps (both take the knife, both use the microwave door) as they come in that sequence,
so whichever unit was accepted first uses the knife first even when its robot reaches
the knife at the end of a long plan, and the other robot, which wants it at once, waits
for all of that: the plans chain up and the makespan approaches the sum of the units.

Here the round's plans are replayed once more, together, as a list schedule: at each
point the step whose robot is free earliest (nominal durations) goes next, if it can run
on the state so far (the same checks and repairs as the unit-by-unit replay: go back
within reach, switch a running microwave off before opening it, skip what another robot
already did); a step that cannot run yet (another robot holds the knife) waits while the
others go on. The interleaved sequence is used only if every step ran and every goal of
the round, and every goal accepted before, holds at its end. When a goal does not (one
robot put the knife away, then another, interleaved, used it again), the units that act
on the objects of the unmet goals run after the others, one after another, and the rest
is interleaved; failing that too, the unit-by-unit sequence stays. Either way the merged
plan is validated in the simulator afterwards.
"""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.hp.merge import GroundedStep, SeqStep, StepFailure, advance, order
from emboteam.hp.rounds import already_done, preparations
from emboteam.pddl.domain import Universe
from emboteam.world.checker import check_condition, condition_holds
from emboteam.world.goals import Condition
from emboteam.world.state import WorldState

#: a round with more steps than this keeps the unit-by-unit order: replaying it again
#: costs a grounding per step (milliseconds each), more than it saved on the sweep's
#: largest cells (docs/planning.md)
MAX_STEPS = 150
#: re-replay only when the unit-by-unit order's critical path exceeds the busiest robot's
#: work by this factor: otherwise nobody waits enough to gain anything
MIN_WAITING = 1.1


def worth_it(steps: Sequence[GroundedStep]) -> bool:
    """Does the unit-by-unit order make robots wait (cheap: no grounding)?"""
    if len(steps) > MAX_STEPS:
        return False
    waits = order(steps, {}, "formal")
    finish: list[float] = []
    last: dict[str, int] = {}
    work: dict[str, float] = {}
    for j, s in enumerate(steps):
        ready = max([finish[i] for i in waits[j]] + ([finish[last[s.robot]]] if s.robot in last else [0.0]))
        finish.append(ready + s.seconds)
        last[s.robot] = j
        work[s.robot] = work.get(s.robot, 0.0) + s.seconds
    return max(finish, default=0.0) > MIN_WAITING * max(work.values(), default=0.0)


def interleave(base: WorldState, plans: Sequence[Sequence[SeqStep]], must_hold: Sequence[Condition],
               universe: Universe) -> tuple[list[GroundedStep], WorldState] | None:
    """The round's plans (each a unit's sequence, as planned) replayed together from
    ``base`` earliest-free-robot first: the grounded sequence and its final state, or
    None when some step never becomes runnable or a goal of ``must_hold`` does not hold
    at the end (also with the units acting on the unmet goals' objects put last)."""
    first = _schedule(base, plans, [], universe)
    if first is None:
        return None
    state = first[1]
    unmet = [c for c in must_hold if not condition_holds(c, state)]
    if not unmet:
        return first
    touched = {x for c in unmet for x in (c.subject.id, c.receptacle.id if c.receptacle else None) if x}
    touched |= {w for c in unmet for w in check_condition(c, base).witnesses}
    late = [k for k, steps in enumerate(plans)
            if any(s.action.target in touched or s.action.receptacle in touched for s in steps)]
    if not late or len(late) == len(plans):
        return None
    again = _schedule(base, [p for k, p in enumerate(plans) if k not in late], [plans[k] for k in late], universe)
    if again is None or not all(condition_holds(c, again[1]) for c in must_hold):
        return None
    return again


def _schedule(base: WorldState, plans: Sequence[Sequence[SeqStep]], tail: Sequence[Sequence[SeqStep]],
              universe: Universe) -> tuple[list[GroundedStep], WorldState] | None:
    """``plans`` interleaved earliest-free-robot first, then ``tail`` one after another."""
    state = base.copy()
    heads = [0] * len(plans)
    clock: dict[str, float] = {}
    out: list[GroundedStep] = []
    while True:
        live = [k for k in range(len(plans)) if heads[k] < len(plans[k])]
        if not live:
            break
        live.sort(key=lambda k: (clock.get(plans[k][heads[k]].robot, 0.0), k))
        for k in live:
            st = plans[k][heads[k]]
            if already_done(state, st.action):
                heads[k] += 1
                break
            try:
                for prep in preparations(state, st):
                    g = advance(state, SeqStep(st.robot, prep, st.subtask, st.group), len(out), universe=universe)
                    out.append(g)
                    clock[g.robot] = clock.get(g.robot, 0.0) + g.seconds
                g = advance(state, st, len(out), universe=universe)
            except StepFailure:
                continue  # not yet (another robot holds what it needs): let the others go on
            out.append(g)
            clock[g.robot] = clock.get(g.robot, 0.0) + g.seconds
            heads[k] += 1
            break
        else:
            return None  # nobody can go on: the unit-by-unit order stays
    for steps in tail:
        for st in steps:
            if already_done(state, st.action):
                continue
            try:
                for prep in preparations(state, st):
                    out.append(advance(state, SeqStep(st.robot, prep, st.subtask, st.group), len(out),
                                       universe=universe))
                out.append(advance(state, st, len(out), universe=universe))
            except StepFailure:
                return None
    return out, state
