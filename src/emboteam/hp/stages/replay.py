"""Replaying steps on a symbolic state: a unit's plan from the state the others leave
(with the preparations another unit's changes call for), and a reordered or spliced
grounded sequence that grounds again only what the change can affect."""

from __future__ import annotations

from collections.abc import Callable, Sequence

from emboteam.hp import spot_order
from emboteam.hp.merge import GroundedStep, SeqStep, StepFailure, advance
from emboteam.hp.rounds import already_done, preparations
from emboteam.pddl.domain import Universe
from emboteam.sim.rules import apply_action
from emboteam.world.actions import Action
from emboteam.world.checker import condition_holds
from emboteam.world.goals import Goal
from emboteam.world.state import WorldState


def replay(trial: WorldState, steps: Sequence[SeqStep], universe: Universe,
           repair: Callable[[WorldState, SeqStep], list[Action]] | None = None
           ) -> tuple[list[GroundedStep], str | None]:
    """Run a unit's steps on ``trial`` (in place): grounded steps, or why they fail.
    ``repair``: more preparations, after :func:`preparations` (a reordering's)."""
    grounded: list[GroundedStep] = []
    try:
        for i, st in enumerate(steps):
            if already_done(trial, st.action):
                continue  # another unit opened (switched, ...) it first: nothing to do
            for prep in preparations(trial, st):
                # planned for a world another unit has changed since (the robot or the
                # object moved, the microwave was left running): a step first puts it right
                grounded.append(advance(trial, SeqStep(st.robot, prep, st.subtask, st.group), i,
                                        universe=universe))
            for prep in repair(trial, st) if repair is not None else ():
                grounded.append(advance(trial, SeqStep(st.robot, prep, st.subtask, st.group), i,
                                        universe=universe))
            grounded.append(advance(trial, st, i, universe=universe))
    except StepFailure as exc:
        return [], f"no longer runs: {exc}"
    return grounded, None


def replay_to_goal(start: WorldState, steps: Sequence[SeqStep], goal: Goal,
                   repair: Callable[[WorldState, SeqStep], list[Action]] | None = None,
                   head: Sequence[GroundedStep] = (), universe: Universe | None = None
                   ) -> tuple[list[GroundedStep], str | None]:
    """:func:`replay` of a whole rebuilt plan from a copy of ``start``: its grounded steps,
    or why it cannot stand (it no longer runs, or it ends without reaching ``goal``). The
    improvement stages that rebuild a plan in a new order (route, CP-SAT's schedule) share it.
    ``head``: the plan's first steps, already grounded from ``start`` by a replay and left
    as they were (a rebuild that changes only later steps): applied, not grounded again
    (replaying a replay's own steps grounds them as they are), ``steps`` after them.
    ``universe``: one made for ``start`` (:attr:`Context.universe`), whose groundings are
    reused where they hold."""
    state = start.copy()
    universe = universe if universe is not None else Universe(state.copy())
    for g in head:
        apply_action(state, g.robot, g.action)
    grounded, why = replay(state, steps, universe, repair)
    if why is None and not all(condition_holds(c, state) for c in goal.conditions):
        why = "misses the goal"
    return [*head, *grounded], why


def replay_reusing(state: WorldState, steps: Sequence[GroundedStep], fresh: set[int], universe: Universe,
                   changed: Sequence[GroundedStep] = ()) -> tuple[list[GroundedStep], str | None]:
    """Replay grounded steps in a new order on ``state`` (in place). The steps at
    ``fresh`` positions (those moved) are grounded again, with the repairs of
    :func:`replay` and :func:`emboteam.hp.spot_order.reopen`; so is every step that
    reads or writes a state variable a step grounded *differently* may have set (or
    updates one it wrote: two updates of a set commute). The others see the values
    they saw when they were grounded, so their grounding is kept and only applied;
    a step grounded again exactly as before sets the same values, so it sets nothing
    apart. A reordering of a 200-step plan grounds tens of steps, not all. ``changed``:
    steps taken out or put in before these (their variables are set apart too)."""
    written = {v for x in changed for v in x.footprint.writes}
    updated = {v for x in changed for v in x.footprint.updates}
    out: list[GroundedStep] = []
    for i, g in enumerate(steps):
        fp = g.footprint
        if i not in fresh:
            seen = fp.reads | fp.writes | {f"loc:{x}" for x in (g.action.target, g.action.receptacle) if x}
            if not seen & (written | updated) and not fp.updates & written:
                apply_action(state, g.robot, g.action)
                out.append(g)
                continue
        again, why = replay(state, [SeqStep(g.robot, g.action, g.subtask, g.group)], universe, spot_order.reopen)
        if why is not None:
            return [], why
        if again != [g]:
            for x in [g, *again]:
                written |= x.footprint.writes
                updated |= x.footprint.updates
        out += again
    return out, None
