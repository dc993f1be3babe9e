"""The eliminate stage over the whole accepted sequence: the steps the goal does not need
across units and rounds go (:func:`emboteam.hp.eliminate.eliminate_steps`): two robots
heat things in one microwave run where their plans, made apart, each ran it."""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.hp.eliminate import eliminate_steps
from emboteam.hp.merge import GroundedStep, SeqStep, StepFailure, advance
from emboteam.pddl.domain import Universe
from emboteam.pfg.taskspec import TaskSpec
from emboteam.sim.rules import apply_action
from emboteam.world.state import WorldState

#: elimination over the whole accepted sequence gives up a removal whose replay has not
#: rejoined the original within this many steps (docs/planning.md)
ELIMINATE_WINDOW = 40


def trimmed(accepted: Sequence[GroundedStep], spec: TaskSpec, start: WorldState, universe: Universe
            ) -> list[GroundedStep] | None:
    """The accepted sequence without the steps the goal does not need; None when nothing
    goes, when some subtask's goal is intermediate (the elimination keeps only what holds
    at the end) or the shorter sequence fails a PDDL precondition."""
    if any(not t.final for t in spec.subtasks) or len(accepted) < 2:
        return None
    kept, moved = eliminate_steps(start, [(g.robot, g.action) for g in accepted], spec.goal().conditions,
                                  window=ELIMINATE_WINDOW)
    if len(kept) == len(accepted):
        return None
    state = start.copy()
    steps: list[GroundedStep] = []
    try:
        for k in kept:
            g = accepted[k]
            if k in moved:  # may start from another state now: grounded again
                steps.append(advance(state, SeqStep(g.robot, g.action, g.subtask, g.group), len(steps),
                                     universe=universe))
            else:  # starts from the very state it was grounded in
                apply_action(state, g.robot, g.action)
                steps.append(g)
    except StepFailure:
        return None
    return steps
