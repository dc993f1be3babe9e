"""The AI2-THOR adapter: :class:`~emboteam.world.environment.Environment` on a live
``ai2thor.controller.Controller``.

Time is simulated as in the symbolic simulator: an action is checked when it starts,
runs for its duration from our duration model, and is carried out in AI2-THOR when it
ends, so robots acting at once see each other's effects in the same order they would in
the simulator. Robots drive on the floor plan's navigation grid exactly as in the
simulator: the same reservations and space-time search (:class:`~emboteam.sim.traffic.Traffic`,
avoidance on), a blocked drive waiting and looking again every second; each step of the
path (``MoveAhead``/``RotateLeft``/``RotateRight``, or ``Teleport`` to the next cell:
:mod:`emboteam.thor.driving`) is sent when it ends, then the agent turns to face the
object. Robots start on their grid cells (the task's start cells), teleported there
before the episode. As in the simulator, when a drive looks again and still finds no way,
the robots parked on its shortest way that are idle (or wait for a way themselves and asked
later: a deadlock) step aside to the nearest free cell off it, their moves sent like a
drive's. What the
team model adds to AI2-THOR is checked before any controller call: a robot's skills, its
mass capacity, the knife slicing needs (docs/world.md), and a robot that is down. Every
other failure is AI2-THOR's own, read from ``lastActionSuccess`` and ``errorMessage``.
The state the executor observes is rebuilt from ``event.metadata`` after every step.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from emboteam.errors import UnknownObjectError, UnknownRobotError
from emboteam.sim.drives import DriveStep, drive_steps
from emboteam.sim.durations import (
    FAILED_ACTION_SECONDS,
    MIN_NAVIGATION_SECONDS,
    action_seconds,
    agent_action_seconds,
)
from emboteam.sim.setup import StateChange
from emboteam.sim.simulator import NAV_MAX_BLOCKED, NAV_RETRY_SECONDS, RobotBusyError
from emboteam.sim.traffic import Traffic
from emboteam.thor.convert import Member, world_state
from emboteam.thor.driving import ThorDriver, on_cell, step_mode
from emboteam.thor.errors import ThorSetupError, ThorTeamError
from emboteam.thor.ids import ThorIds
from emboteam.thor.setup import apply_setup
from emboteam.thor.skills import StepResult, ThorController, ThorSkills
from emboteam.world.actions import Action, ActionOutcome, FailureReason, Skill
from emboteam.world.catalogue import KNIVES
from emboteam.world.navgrid import NavGrid, heading_of_rotation
from emboteam.world.navigation import navigator
from emboteam.world.poses import Pose
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

R = FailureReason


@dataclass(order=True, slots=True)
class _Pending:
    end: float
    seq: int
    robot: str = field(compare=False)
    action: Action = field(compare=False)
    start: float = field(compare=False)
    failure: StepResult | None = field(compare=False, default=None)
    #: a drive: its target poses, the point it faces at the end, how often it was blocked,
    #: and whether it is waiting for a way (``end`` is then the time it looks again)
    goals: tuple[Pose, ...] = field(compare=False, default=())
    point: dict[str, float] | None = field(compare=False, default=None)
    blocked: int = field(compare=False, default=0)
    waiting: bool = field(compare=False, default=False)


@dataclass(order=True, slots=True)
class _Motion:
    """One drive step, sent to AI2-THOR at ``t`` (when the step ends)."""

    t: float
    seq: int
    robot: str = field(compare=False)
    step: DriveStep = field(compare=False)
    #: the drive it belongs to; None: the robot steps aside for another one
    drive: _Pending | None = field(compare=False)


def team_precheck(state: WorldState, robot: str, action: Action) -> StepResult | None:
    """What our team model forbids that AI2-THOR does not know about."""
    r = state.robots[robot]
    if r.down:
        return StepResult(False, R.ROBOT_DOWN, f"{robot} is down")
    if not r.profile.can(action.skill):
        return StepResult(False, R.MISSING_SKILL, f"{robot} cannot {action.skill.value}")
    for oid in (action.target, action.receptacle):
        if oid is not None and oid not in state.objects:
            return StepResult(False, R.UNKNOWN_OBJECT, f"no object {oid!r} in {state.floor_plan}")
    o = state.objects[action.target]
    if action.skill is Skill.PickupObject and o.mass > r.profile.mass_capacity:
        return StepResult(False, R.TOO_HEAVY, f"{o.id} weighs {o.mass:g} kg, {robot} lifts "
                          f"{r.profile.mass_capacity:g} kg")
    if action.skill is Skill.SliceObject:
        held = state.objects[r.holding].type if r.holding else None
        if held not in KNIVES:
            return StepResult(False, R.NO_KNIFE, f"{robot} must hold a Knife or ButterKnife to slice")
    if action.skill in (Skill.PutObject, Skill.ThrowObject, Skill.DropHandObject) and r.holding != o.id:
        if r.holding is None:
            return StepResult(False, R.HAND_EMPTY, f"{robot} holds nothing")
        return StepResult(False, R.NOT_HOLDING_TARGET, f"{robot} holds {r.holding}, not {o.id}")
    return None


class ThorEnvironment:
    """A team of robots acting in one AI2-THOR scene, one AI2-THOR agent per robot.

    ``agent_count``: agents to start (default: the team). AI2-THOR fixes the number at
    initialisation, so a robot that joins later takes one of the spare agents.
    """

    def __init__(self, controller: ThorController, scene: Scene, team: Sequence[RobotProfile], *,
                 setup: Sequence[StateChange] = (), force_action: bool = True,
                 starts: Mapping[str, tuple[float, float]] | None = None, steps: str | None = None) -> None:
        self.controller = controller
        self.scene = scene
        self.ids = ThorIds(scene)
        self.skills = ThorSkills(controller, self.ids, force_action=force_action)
        self.driver = ThorDriver(self.skills, step_mode(steps))
        self.team = [Member(p, i) for i, p in enumerate(team)]
        self.traffic = Traffic(navigator(scene.floor_plan), avoid=True)
        self._now = 0.0
        self._queue: list[_Pending] = []
        self._motion: list[_Motion] = []
        self._running: dict[str, _Pending] = {}
        self._seq = itertools.count()
        self._at: dict[str, str | None] = {}
        self._down: set[str] = set()
        self.outcomes: list[ActionOutcome] = []
        for m in self.team:
            start = (starts or {}).get(m.name) or scene.robot_start(m.agent_id)
            self._place(m, start)
        self._state = self._read(None)
        if setup:
            apply_setup(self.skills, setup, self._refresh)
        self.initial_state = self._refresh().copy()

    # ---- state ------------------------------------------------------------------------
    def _agents(self) -> list[Any]:
        event = self.controller.last_event
        return [e.metadata for e in getattr(event, "events", [event])]

    def _read(self, previous: WorldState | None) -> WorldState:
        return world_state(self._agents(), self.scene, self.ids, self.team, previous=previous,
                           down=frozenset(self._down), at=self._at)

    def _refresh(self) -> WorldState:
        self._state = self._read(self._state)
        return self._state

    @property
    def state(self) -> WorldState:
        return self._state

    # ---- Environment protocol ---------------------------------------------------------
    @property
    def now(self) -> float:
        return self._now

    def observe(self) -> WorldState:
        return self._state

    def busy(self, robot: str) -> bool:
        return robot in self._running

    def next_event_time(self) -> float | None:
        return self._queue[0].end if self._queue else None

    def add_robot(self, profile: RobotProfile) -> None:
        if profile.name in self._state.robots:
            raise UnknownRobotError(f"a robot named {profile.name} is already in the team")
        agents = len(self._agents())
        if len(self.team) >= agents:
            raise ThorTeamError(f"{profile.name} cannot join: AI2-THOR was started with {agents} agent(s) "
                                f"and fixes agentCount at initialisation")
        member = Member(profile, len(self.team))
        self.team.append(member)
        pos = self._agents()[member.agent_id]["agent"]["position"]
        self._place(member, (float(pos["x"]), float(pos["z"])))
        self._refresh()

    def start(self, robot: str, action: Action) -> None:
        if robot not in self._state.robots:
            raise UnknownRobotError(f"no robot {robot!r} in the team")
        if robot in self._running:
            raise RobotBusyError(f"{robot} is busy with {self._running[robot].action}")
        failure = team_precheck(self._state, robot, action)
        if failure is None and action.skill is Skill.GoToObject:
            failure = self._start_drive(robot, action)
            if failure is None:
                return
        duration = action_seconds(action.skill) if failure is None else FAILED_ACTION_SECONDS
        self._push(_Pending(self._now + duration, next(self._seq), robot, action, self._now, failure))

    def advance(self, until: float) -> list[ActionOutcome]:
        done: list[ActionOutcome] = []
        while True:
            step_at = self._motion[0].t if self._motion else math.inf
            end_at = self._queue[0].end if self._queue else math.inf
            if min(step_at, end_at) > until + 1e-9:
                break
            self._now = max(self._now, min(step_at, end_at))
            if step_at <= end_at:  # a step ending with an action goes first
                self._send(heapq.heappop(self._motion))
                continue
            pending = heapq.heappop(self._queue)
            if pending.waiting:
                self._retry(pending)
            else:
                done.append(self._finish(pending))
        self._now = max(self._now, until)
        return done

    def pose(self, robot: str) -> tuple[float, float]:
        """Where a robot is now for the trace's floor map: along its grid path."""
        if robot not in self.traffic.paths:
            return self._state.robots[robot].position
        return self.traffic.point(robot, self._now)

    def nav_record(self) -> dict[str, object]:
        """The robots' motion so far, for the trace and its checker (as the simulator's)."""
        return self.traffic.record(self.scene.floor_plan, self._now)

    # ---- internals: the grid ----------------------------------------------------------
    def _agent_id(self, robot: str) -> int:
        return next(m.agent_id for m in self.team if m.name == robot)

    def _agent(self, robot: str) -> Any:
        return self._agents()[self._agent_id(robot)]

    def _place(self, member: Member, start: tuple[float, float]) -> None:
        """Put an agent on its grid cell (the nearest free one to ``start``), teleporting it
        there when AI2-THOR has it elsewhere or turned off the grid's headings."""
        agent = self._agents()[member.agent_id]["agent"]
        yaw = float(agent["rotation"]["y"])
        heading = heading_of_rotation(yaw)
        cell = self.traffic.place(member.name, self.traffic.nav.cell_of(start), self._now, heading)
        if on_cell(agent["position"], cell) and abs(yaw - 90 * heading) % 360 < 0.5:
            return
        x, z = NavGrid.point(cell)
        result, _ = self.skills.step(member.agent_id, "Teleport", position=dict(x=x, y=agent["position"]["y"], z=z),
                                     rotation=dict(x=0.0, y=90.0 * heading, z=0.0),
                                     horizon=float(agent.get("cameraHorizon", 0.0)), standing=True)
        if not result.success:
            raise ThorSetupError(f"cannot put {member.name} on its start cell ({x}, {z}): {result.message}")

    def _start_drive(self, robot: str, action: Action) -> StepResult | None:
        """Plan and launch a drive (or its wait for a way); a failure if it cannot start."""
        o = self._state.objects[action.target]
        if o.gone:
            return StepResult(False, R.ALREADY_SLICED, f"{o.id} was sliced; its pieces remain")
        x, y, z = o.position
        if o.held_by is not None:
            x, z = self._state.robots[o.held_by].position
        goals = self.traffic.nav.poses_for((x, z))
        if not goals:
            return StepResult(False, R.NOT_REACHABLE, f"no cell of {self.scene.floor_plan}'s navigation grid "
                              f"is within 1.5 m of {action.target}")
        drive = _Pending(self._now, next(self._seq), robot, action, self._now, goals=goals,
                         point=dict(x=x, y=y, z=z))
        self._plan(drive)
        return None

    def _plan(self, drive: _Pending, *, make_way: bool = False) -> None:
        """Reserve the drive's path and queue its steps, or wait and look again; with
        ``make_way`` (looking again), robots in the way are asked to step aside first."""
        robot = drive.robot
        dt = agent_action_seconds(self._state.robots[robot].profile.speed)
        heading = self._heading_at_end(robot)
        path = self.traffic.drive(robot, self._now, dt, drive.goals)
        if path is None and make_way:
            self._make_way(drive)
            path = self.traffic.drive(robot, self._now, dt, drive.goals)
        if path is None:
            drive.blocked += 1
            self.traffic.waits += 1
            if drive.blocked > NAV_MAX_BLOCKED:
                drive.failure = StepResult(False, R.NOT_REACHABLE,
                                           f"{robot} found no way to {drive.action.target} around the other robots")
                drive.waiting, drive.end = False, self._now
            else:
                drive.waiting, drive.end = True, self._now + NAV_RETRY_SECONDS
            self._push(drive)
            return
        steps = drive_steps(path, start=self._now, heading_before=heading)
        drive.waiting = False
        drive.end = max(path[-1].t, drive.start + MIN_NAVIGATION_SECONDS, self._now)
        for step in steps:
            heapq.heappush(self._motion, _Motion(step.end, next(self._seq), robot, step, drive))
        self._push(drive)

    def _retry(self, drive: _Pending) -> None:
        self.traffic.replans += 1
        self._plan(drive, make_way=True)

    def _heading_at_end(self, robot: str) -> int:
        """Where ``robot`` will face when a drive planned now sets off: at the end of the
        moves it is still making (stepping aside; the drive starts there), else as
        AI2-THOR has it now."""
        if self.traffic.end_time(robot) > self._now:
            return self.traffic.paths[robot][-1].heading
        return heading_of_rotation(float(self._agent(robot)["agent"]["rotation"]["y"]))

    def _make_way(self, drive: _Pending) -> None:
        """The simulator's rule (:meth:`emboteam.sim.simulator.Simulator._make_way`): each
        robot parked on the blocked robot's shortest way that is idle, or that waits for a
        way itself and started later, steps aside to the nearest free cell off that way
        (within reach of what it works on, when it can); a robot that is down stays, an
        obstacle. The moves are sent to AI2-THOR as they end, like a drive's."""
        way = self.traffic.way_of(drive.robot, self._now, drive.goals)
        for other in self.traffic.blockers(drive.robot, self._now, drive.goals):
            o = self._state.robots.get(other)
            if o is None or o.down or other in self._down:
                continue
            theirs = self._running.get(other)
            if theirs is not None and not (theirs.waiting and (theirs.start, other) > (drive.start, drive.robot)):
                continue
            near = None
            if o.at is not None and o.at in self._state.objects:
                p = self._state.objects[o.at].position
                near = (p[0], p[2])
            heading = self._heading_at_end(other)
            dt = agent_action_seconds(o.profile.speed)
            path = self.traffic.step_aside(other, self._now, dt, way, near)
            if path is None:
                continue
            for step in drive_steps(path, start=self._now, heading_before=heading):
                heapq.heappush(self._motion, _Motion(step.end, next(self._seq), other, step, None))

    def _send(self, motion: _Motion) -> None:
        drive = motion.drive
        if drive is not None and (drive.failure is not None or self._running.get(motion.robot) is not drive):
            return  # the drive already ended (a step before this one was refused)
        result = self.driver.send(self._agent_id(motion.robot), self._agent(motion.robot), motion.step)
        if result.success:
            return
        agent = self._agent(motion.robot)["agent"]
        here = self.traffic.nav.grid.nearest((float(agent["position"]["x"]), float(agent["position"]["z"])))
        self.traffic.halt(motion.robot, self._now, here, heading_of_rotation(float(agent["rotation"]["y"])))
        if drive is None:
            # a step aside AI2-THOR refused: the robot stays where it stands, and the rest of
            # the way aside is off, as is a drive planned to set off from its end
            self._motion = [m for m in self._motion if m.robot != motion.robot]
            heapq.heapify(self._motion)
            drive = self._running.get(motion.robot)
            if drive is None or drive.point is None or drive.waiting:
                self._refresh()
                return
        drive.failure = StepResult(False, result.reason or R.NOT_REACHABLE,
                                   f"AI2-THOR refused {motion.step.action} towards {drive.action.target}: "
                                   f"{result.message}")
        drive.end = self._now
        heapq.heapify(self._queue)
        self._refresh()

    def _push(self, pending: _Pending) -> None:
        self._running[pending.robot] = pending
        heapq.heappush(self._queue, pending)

    # ---- internals: ending actions ----------------------------------------------------
    def _finish(self, pending: _Pending) -> ActionOutcome:
        robot, action = pending.robot, pending.action
        del self._running[robot]
        result = pending.failure
        if result is None:
            agent = self._agent_id(robot)
            try:
                if pending.point is not None:
                    result = self.driver.face(agent, self._agent(robot), pending.point)
                    if result.success:
                        self._at[robot] = action.target
                else:
                    result = self.skills.interact(agent, action, self._state, robot)
            except UnknownObjectError as exc:
                result = StepResult(False, R.UNKNOWN_OBJECT, str(exc))
            state = self._refresh()
            if result.success and action.skill in (Skill.SwitchOn, Skill.PutObject):
                self.skills.run_water(agent, state)
                self._refresh()
        elif pending.point is not None:
            self._refresh()
        outcome = ActionOutcome(robot=robot, action=action, start=pending.start, end=pending.end,
                                success=result.success, reason=result.reason, message=result.message)
        self.outcomes.append(outcome)
        return outcome
