"""The grid paths a plan's drives take, for exports: each GoToObject step of a merged plan
as the agent actions the simulator drives for it.

The plan is run once in the simulator with avoidance on, no faults (the plan's own
validation replay, :func:`emboteam.hp.validate.simulate`, in a simulator that keeps the
robots' paths), so each drive is the path the simulator would take, with the waits that
avoiding the other robots costs where they are known in advance. A run with faults or
re-plans drives differently; this is the nominal drive.
"""

from __future__ import annotations

from dataclasses import dataclass

from emboteam.hp.plan import MergedPlan
from emboteam.hp.validate import simulate
from emboteam.sim.drives import EPS, DriveStep, cells_text, drive_steps, steps_text
from emboteam.sim.simulator import Simulator
from emboteam.sim.traffic import Step
from emboteam.world.actions import Skill
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


@dataclass(frozen=True)
class PlannedDrive:
    """One GoToObject step's path: the timed states and the agent actions between them."""

    step_id: str
    states: tuple[Step, ...]
    steps: tuple[DriveStep, ...]

    @property
    def cells(self) -> str:
        return cells_text(self.states)

    @property
    def moves(self) -> str:
        return steps_text(self.steps)


def planned_drives(plan: MergedPlan, state: WorldState) -> dict[str, PlannedDrive]:
    """Step id -> its drive, for every GoToObject step the nominal run reached."""
    sim = Simulator(load_scene(state.floor_plan), [], state=state, avoidance=True)
    timing = simulate(plan, state, sim=sim)
    out: dict[str, PlannedDrive] = {}
    for step in plan.steps:
        if step.action.skill is not Skill.GoToObject or step.id not in timing.times:
            continue
        t0, t1 = timing.times[step.id]
        path = sim.traffic.paths.get(step.robot, [])
        before = [s for s in path if s.t < t0 - EPS]
        during = tuple(s for s in path if t0 - EPS <= s.t <= t1 + EPS)
        if not during:  # it never left its cell (already at a pose): it stands where it stood
            during = (Step(t0, before[-1].cell, before[-1].heading),) if before else ()
        heading = before[-1].heading if before else None
        out[step.id] = PlannedDrive(step.id, during, tuple(drive_steps(during, start=t0, end=t1,
                                                                        heading_before=heading)))
    return out
