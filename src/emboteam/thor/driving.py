"""A grid drive's steps as AI2-THOR controller actions.

The AI2-THOR environment drives the same grid paths as the simulator
(:mod:`emboteam.sim.traffic`, :mod:`emboteam.sim.drives`), one agent action at a time, each
sent when the simulated action ends. Two ways to move the agent, chosen with
``EMBOTEAM_THOR_STEPS`` (or the environment's ``steps`` argument):

- ``moves`` (default): ``MoveAhead`` (0.25 m), ``RotateRight``/``RotateLeft`` by the degrees
  that bring the agent's yaw to the step's heading (90°, or what lines it up after it last
  faced an object at an angle), as AI2-THOR's own agent moves;
- ``teleport``: ``Teleport`` to each next cell and heading, for builds or scenes where the
  AI2-THOR 2.1 grid does not match 5.x physics everywhere.

A wait sends nothing (the agent stands). At the end of the drive the agent turns to face
the object exactly and tilts its camera to it (``facing``). A step AI2-THOR refuses ends
the drive with AI2-THOR's message.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from typing import Any

from emboteam.sim.drives import LEFT, MOVE, RIGHT, WAIT, DriveStep
from emboteam.thor.errors import ThorTeamError
from emboteam.thor.skills import StepResult, ThorSkills, facing
from emboteam.world.actions import Skill
from emboteam.world.navgrid import GRID, NavGrid

STEP_MODES = ("moves", "teleport")
#: below this many degrees a turn or tilt is not sent
ANGLE_TOLERANCE = 0.5


def step_mode(wanted: str | None = None) -> str:
    """``wanted``, else ``EMBOTEAM_THOR_STEPS``, else ``moves``; a typed error for others."""
    mode = wanted or os.environ.get("EMBOTEAM_THOR_STEPS") or "moves"
    if mode not in STEP_MODES:
        raise ThorTeamError(f"unknown AI2-THOR step mode {mode!r} (EMBOTEAM_THOR_STEPS: "
                            f"{' or '.join(STEP_MODES)})")
    return mode


def turn_degrees(yaw_now: float, yaw_wanted: float) -> float:
    """Signed degrees (positive: RotateRight) from ``yaw_now`` to ``yaw_wanted``, in (-180, 180]."""
    d = (yaw_wanted - yaw_now) % 360.0
    return d - 360.0 if d > 180.0 else d


class ThorDriver:
    """Sends drive steps and the final facing of one team's agents."""

    def __init__(self, skills: ThorSkills, mode: str) -> None:
        self.skills = skills
        self.mode = mode

    def send(self, agent_id: int, agent: Mapping[str, Any], step: DriveStep) -> StepResult:
        """Carry out one drive step; ``agent`` is the agent's metadata before it."""
        if step.action == WAIT:
            return StepResult(True)
        if self.mode == "teleport":
            return self._teleport(agent_id, agent, step)
        if step.action == MOVE:
            return self._do(agent_id, MOVE, moveMagnitude=GRID)
        if step.action not in (LEFT, RIGHT):
            raise ValueError(f"not a drive step: {step.action}")
        return self._turn(agent_id, agent, float(step.yaw))

    def face(self, agent_id: int, agent: Mapping[str, Any], target: Mapping[str, float]) -> StepResult:
        """Turn and tilt to look at ``target`` from where the agent stands."""
        pos = agent["agent"]["position"]
        yaw, horizon = facing(pos, target)
        if self.mode == "teleport":
            return self._do(agent_id, "Teleport", position=dict(pos), rotation=dict(x=0.0, y=yaw, z=0.0),
                            horizon=horizon, standing=True)
        result = self._turn(agent_id, agent, yaw)
        tilt = horizon - float(agent["agent"].get("cameraHorizon", 0.0))
        if result.success and abs(tilt) >= ANGLE_TOLERANCE:
            result = self._do(agent_id, "LookDown" if tilt > 0 else "LookUp", degrees=round(abs(tilt), 1))
        return result

    # ---- internals --------------------------------------------------------------------
    def _do(self, agent_id: int, action: str, **args: Any) -> StepResult:
        result, _ = self.skills.step(agent_id, action, Skill.GoToObject, **args)
        return result

    def _turn(self, agent_id: int, agent: Mapping[str, Any], yaw: float) -> StepResult:
        d = turn_degrees(float(agent["agent"]["rotation"]["y"]), yaw)
        if abs(d) < ANGLE_TOLERANCE:
            return StepResult(True)
        return self._do(agent_id, RIGHT if d > 0 else LEFT, degrees=round(abs(d), 1))

    def _teleport(self, agent_id: int, agent: Mapping[str, Any], step: DriveStep) -> StepResult:
        x, z = NavGrid.point(step.cell)
        y = float(agent["agent"]["position"]["y"])
        return self._do(agent_id, "Teleport", position=dict(x=x, y=y, z=z),
                        rotation=dict(x=0.0, y=float(step.yaw), z=0.0),
                        horizon=float(agent["agent"].get("cameraHorizon", 0.0)), standing=True)


def on_cell(position: Mapping[str, float], cell: tuple[int, int]) -> bool:
    """Whether an agent position is a cell's centre (within a centimetre)."""
    x, z = NavGrid.point(cell)
    return math.hypot(float(position["x"]) - x, float(position["z"]) - z) < 0.01
