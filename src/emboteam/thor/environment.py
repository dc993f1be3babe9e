"""The AI2-THOR adapter: :class:`~emboteam.world.environment.Environment` on a live
``ai2thor.controller.Controller``.

Time is simulated as in the symbolic simulator: an action is checked when it starts,
runs for its duration from our duration model (a drive: the length of AI2-THOR's shortest
path at the robot's speed), and is carried out in AI2-THOR when it ends, so robots acting
at once see each other's effects in the same order they would in the simulator. What the
team model adds to AI2-THOR is checked before any controller call: a robot's skills, its
mass capacity, the knife slicing needs (docs/world.md), and a robot that is down. Every
other failure is AI2-THOR's own, read from ``lastActionSuccess`` and ``errorMessage``.
The state the executor observes is rebuilt from ``event.metadata`` after every step.
"""

from __future__ import annotations

import heapq
import itertools
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from emboteam.errors import UnknownObjectError, UnknownRobotError
from emboteam.sim.durations import FAILED_ACTION_SECONDS, MIN_NAVIGATION_SECONDS, action_seconds
from emboteam.sim.setup import StateChange
from emboteam.sim.simulator import RobotBusyError
from emboteam.thor.convert import Member, world_state
from emboteam.thor.errors import ThorTeamError
from emboteam.thor.ids import ThorIds
from emboteam.thor.setup import apply_setup
from emboteam.thor.skills import NavigationPlan, StepResult, ThorController, ThorSkills
from emboteam.world.actions import Action, ActionOutcome, FailureReason, Skill
from emboteam.world.catalogue import KNIVES
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
    navigation: NavigationPlan | None = field(compare=False, default=None)
    failure: StepResult | None = field(compare=False, default=None)


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
                 setup: Sequence[StateChange] = (), force_action: bool = True) -> None:
        self.controller = controller
        self.scene = scene
        self.ids = ThorIds(scene)
        self.skills = ThorSkills(controller, self.ids, force_action=force_action)
        self.team = [Member(p, i) for i, p in enumerate(team)]
        self._now = 0.0
        self._queue: list[_Pending] = []
        self._running: dict[str, _Pending] = {}
        self._seq = itertools.count()
        self._at: dict[str, str | None] = {}
        self._down: set[str] = set()
        self.outcomes: list[ActionOutcome] = []
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
        self.team.append(Member(profile, len(self.team)))
        self._refresh()

    def start(self, robot: str, action: Action) -> None:
        if robot not in self._state.robots:
            raise UnknownRobotError(f"no robot {robot!r} in the team")
        if robot in self._running:
            raise RobotBusyError(f"{robot} is busy with {self._running[robot].action}")
        state = self._state
        failure = team_precheck(state, robot, action)
        plan: NavigationPlan | None = None
        duration = FAILED_ACTION_SECONDS
        if failure is None and action.skill is Skill.GoToObject:
            planned = self._plan_drive(robot, action.target)
            if isinstance(planned, StepResult):
                failure = planned
            else:
                plan = planned
                speed = state.robots[robot].profile.speed
                duration = max(MIN_NAVIGATION_SECONDS, plan.length / speed)
        elif failure is None:
            duration = action_seconds(action.skill)
        pending = _Pending(self._now + duration, next(self._seq), robot, action, self._now, plan, failure)
        self._running[robot] = pending
        heapq.heappush(self._queue, pending)

    def advance(self, until: float) -> list[ActionOutcome]:
        done: list[ActionOutcome] = []
        while self._queue and self._queue[0].end <= until + 1e-9:
            pending = heapq.heappop(self._queue)
            self._now = max(self._now, pending.end)
            done.append(self._finish(pending))
        self._now = max(self._now, until)
        return done

    def pose(self, robot: str) -> tuple[float, float]:
        """Where a robot is now for the trace's floor map: along a drive in progress, the
        straight line from where it started to where it will stand (AI2-THOR itself only
        moves the agent when the drive ends)."""
        here = self._state.robots[robot].position
        run = self._running.get(robot)
        if run is None or run.navigation is None or run.end <= run.start:
            return here
        f = min(1.0, max(0.0, (self._now - run.start) / (run.end - run.start)))
        dest = run.navigation.destination
        return (here[0] + f * (float(dest["x"]) - here[0]), here[1] + f * (float(dest["z"]) - here[1]))

    # ---- internals --------------------------------------------------------------------
    def _agent_id(self, robot: str) -> int:
        return next(m.agent_id for m in self.team if m.name == robot)

    def _pose(self, robot: str) -> dict[str, float]:
        return dict(self._agents()[self._agent_id(robot)]["agent"]["position"])

    def _plan_drive(self, robot: str, target: str) -> NavigationPlan | StepResult:
        o = self._state.objects[target]
        if o.gone:
            return StepResult(False, R.ALREADY_SLICED, f"{o.id} was sliced; its pieces remain")
        x, y, z = o.position
        if o.held_by is not None:
            x, z = self._state.robots[o.held_by].position
        avoid = [self._pose(m.name) for m in self.team if m.name != robot]
        avoid += [p.navigation.destination for p in self._running.values() if p.navigation is not None]
        return self.skills.plan_navigation(self._agent_id(robot), self._pose(robot), dict(x=x, y=y, z=z), avoid)

    def _finish(self, pending: _Pending) -> ActionOutcome:
        robot, action = pending.robot, pending.action
        del self._running[robot]
        result = pending.failure
        if result is None:
            agent = self._agent_id(robot)
            try:
                if pending.navigation is not None:
                    result = self.skills.arrive(agent, pending.navigation)
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
        outcome = ActionOutcome(robot=robot, action=action, start=pending.start, end=pending.end,
                                success=result.success, reason=result.reason, message=result.message)
        self.outcomes.append(outcome)
        return outcome
