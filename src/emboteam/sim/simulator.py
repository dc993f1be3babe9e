"""The THOR-like symbolic simulator: several robots acting at once in simulated time.

An action is checked when it starts (a rejected action costs
:data:`~emboteam.sim.durations.FAILED_ACTION_SECONDS`), runs for its duration, and is
checked again when it ends, because other robots may have changed the world meanwhile;
its effects apply at the end. Interactions hold their object's *interaction spot* (see
:meth:`WorldState.spot_of`) for their whole duration: a second robot trying to interact at
the same spot gets ``spot_busy``. Every failure leaves the state unchanged.
"""

from __future__ import annotations

import heapq
import itertools
from collections.abc import Sequence
from dataclasses import dataclass, field

from pydantic import BaseModel, ConfigDict

from emboteam.errors import EmboTeamError, UnknownObjectError, UnknownRobotError
from emboteam.sim.durations import FAILED_ACTION_SECONDS, action_seconds, navigation_seconds
from emboteam.sim.faults import FaultConfig, FaultInjector, ObjectMove
from emboteam.sim.rules import Failure, apply_action, check_action
from emboteam.world.actions import Action, ActionOutcome, FailureReason, Skill
from emboteam.world.catalogue import load_catalogue
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import RobotState, WorldState


class RobotBusyError(EmboTeamError):
    """An action was started on a robot that is still executing one (a caller bug)."""


class SimEvent(BaseModel):
    """Something that happened outside the robots' actions (faults, arrivals)."""

    model_config = ConfigDict(frozen=True)

    t: float
    kind: str
    detail: str


@dataclass(slots=True)
class _Running:
    robot: str
    action: Action
    start: float
    end: float
    spot: str | None
    origin: tuple[float, float]
    destination: tuple[float, float]
    failure: Failure | None = None


@dataclass(order=True, slots=True)
class _Scheduled:
    t: float
    seq: int
    kind: str = field(compare=False)
    payload: object = field(compare=False)


class Simulator:
    """Implements :class:`emboteam.world.environment.Environment` on the symbolic state."""

    def __init__(self, scene: Scene, team: Sequence[RobotProfile], *, seed: int = 0,
                 faults: FaultConfig | None = None, state: WorldState | None = None) -> None:
        self.scene = scene
        self.state = state.copy() if state is not None else WorldState.from_scene(scene, team)
        self.faults = faults or FaultConfig()
        self.injector = FaultInjector(self.faults, seed)
        self._now = 0.0
        self._running: dict[str, _Running] = {}
        self._locks: dict[str, str] = {}
        self._queue: list[_Scheduled] = []
        self._seq = itertools.count()
        self._action_count: dict[str, int] = {}
        self._approaches: dict[str, int] = {}
        self._cleared: set[tuple[str, str]] = set()
        self._occluded_now: dict[str, set[str]] = {}
        self.outcomes: list[ActionOutcome] = []
        self.events: list[SimEvent] = []
        for b in self.faults.breakdowns:
            self._schedule(b.at, "breakdown", b.robot)
        #: (time, kind, detail, state right after) of every breakdown, join and move: the
        #: states a benchmark's ceiling plans from (exec/ceiling.py)
        self.disturbances: list[tuple[float, str, str, WorldState]] = []
        for m in self.faults.moves:
            for oid in (m.object, m.to):
                if oid is not None and not self._may_exist(oid):
                    raise UnknownObjectError(f"fault moves unknown object {oid!r} "
                                             f"({scene.floor_plan})")
            self._schedule(m.at, "move", m)

    # ---- Environment protocol --------------------------------------------------------
    @property
    def now(self) -> float:
        return self._now

    def observe(self) -> WorldState:
        return self.state

    def busy(self, robot: str) -> bool:
        return robot in self._running

    def add_robot(self, profile: RobotProfile) -> None:
        if profile.name in self.state.robots:
            raise UnknownRobotError(f"a robot named {profile.name} is already in the team")
        pos = self.scene.robot_start(len(self.state.robots))
        self.state.robots[profile.name] = RobotState(profile.name, profile, pos)
        self.events.append(SimEvent(t=self._now, kind="join", detail=profile.name))
        self.disturbances.append((self._now, "join", profile.name, self.state.copy()))

    def start(self, robot: str, action: Action) -> None:
        if robot not in self.state.robots:
            raise UnknownRobotError(f"no robot {robot!r} in the team")
        if robot in self._running:
            raise RobotBusyError(f"{robot} is busy with {self._running[robot].action}")
        r = self.state.robots[robot]
        k = self._action_count.get(robot, 0)
        self._action_count[robot] = k + 1
        origin = r.position
        failure = check_action(self.state, robot, action)
        spot = None
        if failure is None and action.skill is not Skill.GoToObject:
            spot = self.state.spot_of(action.receptacle or action.target)
            holder = self._locks.get(spot)
            if holder is not None and holder != robot:
                failure = Failure(FailureReason.SPOT_BUSY, f"{holder} is using {spot}")
            elif self._occluded(robot, action):
                failure = Failure(FailureReason.NOT_VISIBLE,
                                  f"{action.target} is occluded from {robot}: re-approach it")
        if failure is not None:
            self._launch(_Running(robot, action, self._now, self._now + FAILED_ACTION_SECONDS,
                                  None, origin, origin, failure))
            return
        if action.skill is Skill.GoToObject:
            o = self.state.objects[action.target]
            dest = (o.position[0], o.position[2])
            if o.held_by is not None:
                dest = self.state.robots[o.held_by].position
            # ``at`` and the position change when the drive ends (a failed drive changes
            # nothing); :meth:`pose` interpolates for observers meanwhile
            duration = navigation_seconds(origin, dest, r.profile.speed)
        else:
            dest = origin
            duration = action_seconds(action.skill)
        if spot is not None:
            self._locks[spot] = robot
        run = _Running(robot, action, self._now, self._now + duration, spot, origin, dest)
        if self.injector.action_fails(robot, k):
            run.failure = Failure(FailureReason.ACTUATION_FAULT,
                                  f"{action.skill.value} did not complete (injected fault)")
        self._launch(run)

    def next_event_time(self) -> float | None:
        return self._queue[0].t if self._queue else None

    def advance(self, until: float) -> list[ActionOutcome]:
        done: list[ActionOutcome] = []
        while self._queue and self._queue[0].t <= until + 1e-9:
            ev = heapq.heappop(self._queue)
            self._now = max(self._now, ev.t)
            if ev.kind == "end":
                assert isinstance(ev.payload, _Running)
                outcome = self._finish(ev.payload)
                if outcome is not None:
                    done.append(outcome)
            elif ev.kind == "breakdown":
                assert isinstance(ev.payload, str)
                outcome = self._break_down(ev.payload)
                if outcome is not None:
                    done.append(outcome)
            elif ev.kind == "move":
                assert isinstance(ev.payload, ObjectMove)
                self._move_object(ev.payload)
        self._now = max(self._now, until)
        return done

    # ---- conveniences ----------------------------------------------------------------
    def execute(self, robot: str, action: Action) -> ActionOutcome:
        """Start an action and let time pass until it ends (other robots' actions, and
        scheduled faults, progress meanwhile)."""
        self.start(robot, action)
        while True:
            t = self.next_event_time()
            assert t is not None, "a started action always has an end event"
            for outcome in self.advance(t):
                if outcome.robot == robot:
                    return outcome

    def run_until_idle(self) -> list[ActionOutcome]:
        done: list[ActionOutcome] = []
        while self._running:
            t = self.next_event_time()
            assert t is not None
            done.extend(self.advance(t))
        return done

    def pose(self, robot: str) -> tuple[float, float]:
        """Where a robot is now, interpolated along a navigation in progress."""
        run = self._running.get(robot)
        if run is None or run.action.skill is not Skill.GoToObject or run.end <= run.start:
            return self.state.robots[robot].position
        f = min(1.0, max(0.0, (self._now - run.start) / (run.end - run.start)))
        (x0, z0), (x1, z1) = run.origin, run.destination
        return (x0 + f * (x1 - x0), z0 + f * (z1 - z0))

    def running(self, robot: str) -> Action | None:
        run = self._running.get(robot)
        return run.action if run else None

    @property
    def locks(self) -> dict[str, str]:
        """Interaction spots in use: spot -> robot."""
        return dict(self._locks)

    # ---- internals -------------------------------------------------------------------
    def _may_exist(self, object_id: str) -> bool:
        """An object of the state, or a slice piece one of them may be cut into."""
        if object_id in self.state.objects:
            return True
        whole, sep, _ = object_id.partition("_Slice_")
        return bool(sep) and whole in self.state.objects

    def _schedule(self, t: float, kind: str, payload: object) -> None:
        heapq.heappush(self._queue, _Scheduled(t, next(self._seq), kind, payload))

    def _launch(self, run: _Running) -> None:
        self._running[run.robot] = run
        self._schedule(run.end, "end", run)

    def _occluded(self, robot: str, action: Action) -> bool:
        """Occlusion is drawn once per approach; it lasts until the robot's next
        GoToObject ends, after which that target is never occluded for it again."""
        if action.skill in (Skill.ThrowObject, Skill.DropHandObject):
            return False
        target = action.receptacle or action.target
        hidden = self._occluded_now.setdefault(robot, set())
        if target in hidden:
            return True
        if (robot, target) in self._cleared:
            return False
        if self.injector.occluded(robot, self._approaches.get(robot, 0), target):
            hidden.add(target)
            self.events.append(SimEvent(t=self._now, kind="occlusion", detail=f"{target} for {robot}"))
            return True
        return False

    def _finish(self, run: _Running) -> ActionOutcome | None:
        if self._running.get(run.robot) is not run:
            return None  # ended earlier (robot broke down)
        del self._running[run.robot]
        if run.spot is not None and self._locks.get(run.spot) == run.robot:
            del self._locks[run.spot]
        failure = run.failure
        if failure is None:
            failure = check_action(self.state, run.robot, run.action)
        if failure is None:
            apply_action(self.state, run.robot, run.action)
            if run.action.skill is Skill.GoToObject:
                self._arrive(run)
                self._approaches[run.robot] = self._approaches.get(run.robot, 0) + 1
                for target in self._occluded_now.pop(run.robot, set()):
                    self._cleared.add((run.robot, target))
        elif run.action.skill is Skill.GoToObject and failure.reason is FailureReason.ACTUATION_FAULT:
            r = self.state.robots[run.robot]
            r.position = run.origin  # navigation aborted: back where it started
        outcome = ActionOutcome(
            robot=run.robot, action=run.action, start=run.start, end=run.end,
            success=failure is None, reason=failure.reason if failure else None,
            message=failure.message if failure else "",
        )
        self.outcomes.append(outcome)
        return outcome

    def _arrive(self, run: _Running) -> None:
        """A drive ends where it was headed when it started: if someone moved the target
        meanwhile, the robot arrives at the old place and is not at the object."""
        r = self.state.robots[run.robot]
        if r.position == run.destination:
            return
        r.position = run.destination
        r.at = run.action.target if self.state.in_reach(run.robot, run.action.target) else None
        if r.holding is not None:
            self.state.attach_to_robot(r.holding, run.robot)

    def _break_down(self, robot: str) -> ActionOutcome | None:
        r = self.state.robots.get(robot)
        if r is None or r.down:
            return None
        r.position = self.pose(robot)  # a robot that breaks down mid-drive stops there
        r.down = True
        self.events.append(SimEvent(t=self._now, kind="breakdown", detail=robot))
        run = self._running.pop(robot, None)
        if r.holding is not None:
            held, r.holding = r.holding, None
            floors = list(self.state.of_type("Floor"))
            self.state.move_object(held, floors[0].id if floors else None,
                                   position=(r.position[0], 0.0, r.position[1]))
            self.events.append(SimEvent(t=self._now, kind="drop", detail=f"{robot} dropped {held}"))
        self.disturbances.append((self._now, "breakdown", robot, self.state.copy()))
        if run is None:
            return None
        if run.spot is not None and self._locks.get(run.spot) == robot:
            del self._locks[run.spot]
        outcome = ActionOutcome(robot=robot, action=run.action, start=run.start, end=self._now,
                                success=False, reason=FailureReason.ROBOT_DOWN,
                                message=f"{robot} broke down")
        self.outcomes.append(outcome)
        return outcome

    def _move_object(self, move: ObjectMove) -> None:
        oid = move.object if move.object is not None else self._draw_moved(move)
        o = self.state.objects.get(oid) if oid is not None else None
        if (o is None or o.held_by is not None or o.gone
                or (move.to is not None and move.to not in self.state.objects)):
            self.events.append(SimEvent(t=self._now, kind="move-skipped", detail=oid or "nothing movable"))
            return
        cat = load_catalogue()
        to = move.to
        if to is None:
            options = sorted(
                r.id for r in self.state.objects.values()
                if r.has("receptacle") and r.id != o.id and r.id != o.parent and not r.gone
                and r.held_by is None and cat.can_place(o.type, r.type)
                and (move.into_closed or r.type not in cat.must_be_open or r.is_open)
                # not the bowl in a shut fridge, unless the mover may open things
                and (move.into_closed or self.state.enclosing_closed(r.id) is None)
                and o.id not in self.state.ancestors(r.id)
            )
            if not options:
                self.events.append(SimEvent(t=self._now, kind="move-skipped", detail=f"{o.id}: nowhere to put it"))
                return
            to = self.injector.choice(f"move|{o.id}|{move.at}|{move.draw}", options)
        self.state.move_object(o.id, to)
        closed = self.state.enclosing_closed(o.id)
        self.events.append(SimEvent(t=self._now, kind="moved",
                                    detail=f"{o.id} -> {to}" + (f" (closed {closed})" if closed else "")))
        self.disturbances.append((self._now, "moved", f"{o.id} -> {to}", self.state.copy()))

    def _draw_moved(self, move: ObjectMove) -> str | None:
        """The object a ``random`` move takes: one of the candidates that exists now, lies
        somewhere (not held, not gone) and is not already where the draw would put it."""
        options = sorted(c for c in move.candidates
                         if c in self.state.objects and self.state.objects[c].held_by is None
                         and not self.state.objects[c].gone)
        return self.injector.choice(f"moved|{move.at}|{move.draw}", options) if options else None
