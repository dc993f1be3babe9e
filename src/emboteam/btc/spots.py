"""Interaction spots and the lock plan: which spots each step must hold, and when a robot
releases them.

A spot is where a robot stands to interact with an object (``WorldState.spot_of``: the
fridge for an apple in the fridge). The simulator rejects a second robot interacting at a
busy spot; the compiled tree avoids that by locking spots on the blackboard:

- a *run* is a maximal sequence of one robot's consecutive steps at the same spots; the
  robot acquires the run's spots before the run's first step (before driving there, when
  that first step is a GoToObject) and releases them after its last step;
- a step that waits for another robot starts a new run, so a robot never waits for a
  sync flag while holding a spot; a run made only of drives holds nothing (the robot
  drives to a spot whose work must first wait, and reserves it after the wait);
- a step holding several spots acquires them in sorted order (ordered acquisition), and
  a robot holds at most one run's spots at a time.

Together: every wait for a spot is on a robot that waits for nothing itself, so the lock
protocol cannot deadlock.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.actions import Skill
from emboteam.world.state import WorldState


def _interaction_spot(state: WorldState, step: PlanStep) -> tuple[str, ...]:
    obj = step.action.receptacle or step.action.target
    if obj not in state.objects:
        return ()
    return (state.spot_of(obj),)


def predicted_spots(plan: MergedPlan, state: WorldState | None) -> dict[str, tuple[str, ...]]:
    """The spots each interaction step holds: the planner's ``resources`` when it gave
    them, else predicted by replaying the plan on a copy of the initial state with the
    simulator's rules (the spot of an apple changes once it is in the fridge). Drives
    (GoToObject) get nothing here; :func:`lock_plan` gives them the spot they drive to.

    Uses the symbolic rules only as a prediction for plans that lack resources; at run
    time the environment has the last word (a mismatch shows up as ``spot_busy`` and is
    recovered by waiting).
    """
    spots: dict[str, tuple[str, ...]] = {}
    world = state.copy() if state is not None else None
    for step in plan.steps:
        if step.action.skill is Skill.GoToObject:
            spots[step.id] = ()
        elif step.resources:
            spots[step.id] = tuple(sorted(set(step.resources)))
        elif world is not None:
            spots[step.id] = _interaction_spot(world, step)
        else:
            spots[step.id] = ()
        if world is not None and step.robot in world.robots and all(
                o in world.objects for o in (step.action.target, step.action.receptacle) if o) \
                and check_action(world, step.robot, step.action) is None:
            apply_action(world, step.robot, step.action)
    return spots


@dataclass(frozen=True)
class LockPlan:
    """Per step: the spots it must hold while it runs, and those it releases after."""

    holds: Mapping[str, tuple[str, ...]]
    releases: Mapping[str, tuple[str, ...]]


def _effective_spots(steps: Sequence[PlanStep],
                     spots: Mapping[str, tuple[str, ...]]) -> dict[str, tuple[str, ...]]:
    """A drive takes the spots of the interaction it leads to."""
    eff: dict[str, tuple[str, ...]] = {}
    upcoming: tuple[str, ...] = ()
    for step in reversed(steps):
        if step.action.skill is Skill.GoToObject:
            eff[step.id] = upcoming
        else:
            eff[step.id] = spots.get(step.id, ())
            upcoming = eff[step.id]
    return eff


def _runs(steps: Sequence[PlanStep], eff: Mapping[str, tuple[str, ...]],
          waits: Mapping[str, tuple[str, ...]]) -> list[list[PlanStep]]:
    """Split one robot's steps into runs: consecutive steps at the same spots, a new run
    at every step that waits for another robot."""
    runs: list[list[PlanStep]] = []
    for step in steps:
        s = eff[step.id]
        if runs and s and eff[runs[-1][-1].id] == s and not waits.get(step.id):
            runs[-1].append(step)
        else:
            runs.append([step])
    return runs


def lock_plan(plan: MergedPlan, spots: Mapping[str, tuple[str, ...]],
              waits: Mapping[str, tuple[str, ...]]) -> LockPlan:
    """Which spots each step holds and releases, from the predicted spots and each
    step's cross-robot waits."""
    holds: dict[str, tuple[str, ...]] = {}
    releases: dict[str, tuple[str, ...]] = {}
    for robot in plan.robots:
        steps = plan.for_robot(robot)
        eff = _effective_spots(steps, spots)
        for run in _runs(steps, eff, waits):
            run_spots = eff[run[0].id]
            only_drives = all(s.action.skill is Skill.GoToObject for s in run)
            for s in run:
                holds[s.id] = () if only_drives else run_spots
                releases[s.id] = ()
            if run_spots and not only_drives:
                releases[run[-1].id] = run_spots
    return LockPlan(holds=holds, releases=releases)
