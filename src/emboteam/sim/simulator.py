"""The THOR-like symbolic simulator: several robots acting at once in simulated time.

An action is checked when it starts (a rejected action costs
:data:`~emboteam.sim.durations.FAILED_ACTION_SECONDS`), runs for its duration, and is
checked again when it ends, because other robots may have changed the world meanwhile;
its effects apply at the end. Interactions hold their object's *interaction spot* (see
:meth:`WorldState.spot_of`) for their whole duration: a second robot trying to interact at
the same spot gets ``spot_busy``. Every failure leaves the state unchanged.

Robots drive on the floor plan's navigation grid, one cell each (:mod:`emboteam.sim.traffic`):
a GoToObject plans a timed path to one of the target's interaction poses around the other
robots' reservations, waits while robots block the way (asking idle ones to step aside),
and re-plans when a robot breaks down across its path. That is ``avoidance=True``, which the
environment of every episode uses (``environments.make_environment``); the default,
``avoidance=False``, drives shortest paths through everyone: the planner's nominal model,
with which it validates plans (hp/validate.py), and the benchmark's ``no-avoidance``
ablation, where the trace checker counts the collisions.
"""

from __future__ import annotations

import heapq
import itertools
from collections.abc import Sequence
from dataclasses import dataclass, field

from pydantic import BaseModel, ConfigDict

from emboteam.errors import EmboTeamError, UnknownObjectError, UnknownRobotError
from emboteam.sim.durations import (
    FAILED_ACTION_SECONDS,
    MIN_NAVIGATION_SECONDS,
    action_seconds,
    agent_action_seconds,
    navigation_seconds,
)
from emboteam.sim.faults import FaultConfig, FaultInjector, ObjectMove
from emboteam.sim.rules import Failure, apply_action, check_action
from emboteam.sim.traffic import Step, Traffic
from emboteam.world.actions import Action, ActionOutcome, FailureReason, Skill
from emboteam.world.catalogue import load_catalogue
from emboteam.world.navgrid import NavGrid
from emboteam.world.navigation import navigator
from emboteam.world.poses import Pose
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
    #: a drive's candidate interaction poses, and how often it found its way blocked
    goals: tuple[Pose, ...] = ()
    blocked: int = 0


@dataclass(order=True, slots=True)
class _Scheduled:
    t: float
    seq: int
    kind: str = field(compare=False)
    payload: object = field(compare=False)


#: a blocked drive looks again after this many seconds
NAV_RETRY_SECONDS = 1.0
#: a drive blocked this many times in a row (a broken robot walls the target off) fails
#: ``not_reachable``; the behavior tree's recovery or a replan takes over
NAV_MAX_BLOCKED = 30


class Simulator:
    """Implements :class:`emboteam.world.environment.Environment` on the symbolic state."""

    def __init__(self, scene: Scene, team: Sequence[RobotProfile], *, seed: int = 0,
                 faults: FaultConfig | None = None, state: WorldState | None = None,
                 avoidance: bool = False) -> None:
        self.scene = scene
        self.state = state.copy() if state is not None else WorldState.from_scene(scene, team)
        self.traffic = Traffic(navigator(scene.floor_plan), avoid=avoidance)
        self.faults = faults or FaultConfig()
        self.injector = FaultInjector(self.faults, seed)
        self._now = 0.0
        for name in sorted(self.state.robots, key=lambda n: self.state.robots[n].down, reverse=True):
            self._place(name)
            if self.state.robots[name].down:
                self.traffic.stop(name, self._now)  # broken before the run: a wall from the start
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
        self._place(profile.name)
        self.events.append(SimEvent(t=self._now, kind="join", detail=profile.name))
        self.disturbances.append((self._now, "join", profile.name, self._snapshot()))

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
            point = (o.position[0], o.position[2])
            if o.held_by is not None:
                point = self.state.robots[o.held_by].position
            goals = self.traffic.nav.poses_for(point)
            if not goals:
                self._launch(_Running(robot, action, self._now, self._now + FAILED_ACTION_SECONDS, None,
                                      origin, origin, Failure(FailureReason.NOT_REACHABLE,
                                      f"no cell of {self.scene.floor_plan}'s navigation grid is within "
                                      f"1.5 m of {action.target}")))
                return
            # ``at`` and the position change when the drive ends (a failed drive changes
            # nothing); :meth:`pose` follows the path for observers meanwhile
            if self.injector.action_fails(robot, k):
                # the drive aborts and the robot ends where it started, after the time the
                # drive would have taken (its cell stays reserved: it never left it)
                failure = Failure(FailureReason.ACTUATION_FAULT,
                                  f"{action.skill.value} did not complete (injected fault)")
                seconds = navigation_seconds(origin, point, r.profile.speed, self.scene.floor_plan)
                self._launch(_Running(robot, action, self._now, self._now + seconds, None, origin, origin,
                                      failure))
                return
            self._drive(_Running(robot, action, self._now, self._now, None, origin, origin, goals=goals))
            return
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

    def _place(self, robot: str) -> None:
        """Put a robot on its grid cell (the nearest free one)."""
        r = self.state.robots[robot]
        cell = self.traffic.place(robot, self.traffic.nav.cell_of(r.position), self._now)
        r.position = NavGrid.point(cell)

    def _dt(self, robot: str) -> float:
        return agent_action_seconds(self.state.robots[robot].profile.speed)

    def _drive(self, run: _Running) -> None:
        """Plan a drive and launch it, or wait and look again when the way is blocked."""
        path = self.traffic.drive(run.robot, self._now, self._dt(run.robot), run.goals)
        if path is None:  # robots stand in the only way: idle ones step aside at once
            self._make_way(run)
            path = self.traffic.drive(run.robot, self._now, self._dt(run.robot), run.goals)
            self.traffic.replans += 1
        if path is None:
            self._blocked(run)
            return
        run.end = max(path[-1].t, run.start + MIN_NAVIGATION_SECONDS)
        run.destination = NavGrid.point(path[-1].cell)
        self._launch(run)

    def _blocked(self, run: _Running) -> None:
        walls = self.traffic.walled_off(run.robot, self._now, run.goals)
        if walls:  # waiting cannot help: broken robots stand in the only way, for good
            self._running.pop(run.robot, None)
            run.end = self._now
            run.failure = Failure(FailureReason.NOT_REACHABLE,
                                  f"{', '.join(walls)} broke down in the only way from {run.robot} to "
                                  f"{run.action.target}")
            self._launch(run)
            return
        run.blocked += 1
        self.traffic.waits += 1
        self._running[run.robot] = run
        if run.blocked > NAV_MAX_BLOCKED:
            del self._running[run.robot]
            run.end = self._now
            run.failure = Failure(FailureReason.NOT_REACHABLE,
                                  f"{run.robot} found no way to {run.action.target} around the other robots")
            self._launch(run)
            return
        self.events.append(SimEvent(t=self._now, kind="nav-wait", detail=f"{run.robot} -> {run.action.target}"))
        self._schedule(self._now + NAV_RETRY_SECONDS, "nav-retry", run)

    def _retry(self, run: _Running) -> None:
        """A blocked drive looks again; robots in its way that are idle, or that are
        themselves waiting for a way and started later (a deadlock), step aside."""
        if self._running.get(run.robot) is not run:
            return
        self.traffic.replans += 1
        path = self.traffic.drive(run.robot, self._now, self._dt(run.robot), run.goals)
        if path is None:
            self._make_way(run)
            path = self.traffic.drive(run.robot, self._now, self._dt(run.robot), run.goals)
        if path is None:
            self._blocked(run)
            return
        run.end = max(path[-1].t, self._now + FAILED_ACTION_SECONDS)
        run.destination = NavGrid.point(path[-1].cell)
        self.events.append(SimEvent(t=self._now, kind="nav-replan", detail=f"{run.robot} -> {run.action.target}"))
        self._launch(run)

    def _make_way(self, run: _Running) -> None:
        way = self.traffic.way_of(run.robot, self._now, run.goals)
        for other in self.traffic.blockers(run.robot, self._now, run.goals):
            o = self.state.robots.get(other)
            if o is None or o.down:
                continue  # a broken robot is an obstacle
            theirs = self._running.get(other)
            waiting = theirs is not None and theirs.end == float("inf")
            if theirs is not None and not (waiting and (theirs.start, other) > (run.start, run.robot)):
                continue
            near = None
            if o.at is not None and o.at in self.state.objects:
                p = self.state.objects[o.at].position
                near = (p[0], p[2])
            path = self.traffic.step_aside(other, self._now, self._dt(other), way, near)
            if path is not None:
                self.events.append(SimEvent(t=self._now, kind="nav-yield",
                                            detail=f"{other} makes way for {run.robot}"))
                self._schedule(path[-1].t, "yield-end", (other, path[-1]))

    def _yielded(self, robot: str, step: Step) -> None:
        """A robot that stepped aside is at its new cell (unless it set off since)."""
        r = self.state.robots[robot]
        if robot in self._running or r.down:
            return
        r.position = NavGrid.point(step.cell)
        if r.at is not None and not self.state.in_reach(robot, r.at):
            r.at = None
        if r.holding is not None:
            self.state.attach_to_robot(r.holding, robot)

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
            elif ev.kind == "nav-retry":
                assert isinstance(ev.payload, _Running)
                self._retry(ev.payload)
            elif ev.kind == "yield-end":
                assert isinstance(ev.payload, tuple)
                who, where = ev.payload
                self._yielded(who, where)
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
        """Where a robot is now, interpolated along its path on the grid."""
        if robot not in self.traffic.paths:
            return self.state.robots[robot].position
        return self.traffic.point(robot, self._now)

    def _snapshot(self) -> WorldState:
        """The state now, for the disturbance record (the benchmark's ceiling plans from
        it): a robot in the middle of a drive stands on the grid cell it has reached, not
        where its drive began (the state moves it only when the drive ends)."""
        snap = self.state.copy()
        for name, run in self._running.items():
            r = snap.robots.get(name)
            if r is None or r.down or not run.goals or name not in self.traffic.paths:
                continue
            here = NavGrid.point(self.traffic.cell(name, self._now).cell)
            if here != r.position:
                r.position = here
                if r.at is not None and r.at in snap.objects and not snap.in_reach(name, r.at):
                    r.at = None
                if r.holding is not None:
                    snap.attach_to_robot(r.holding, name)
        return snap

    def running(self, robot: str) -> Action | None:
        run = self._running.get(robot)
        return run.action if run else None

    def nav_record(self) -> dict[str, object]:
        """The robots' motion so far, for the trace (``nav`` event) and its checker: start
        cells, every MoveAhead begun before now, and the traffic counters."""
        return self.traffic.record(self.scene.floor_plan, self._now)

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
        elif run.action.skill is Skill.GoToObject and run.goals and run.destination != run.origin:
            # the drive happened (the grid keeps its cells) but it did not end at the object
            r = self.state.robots[run.robot]
            r.position = run.destination
            r.at = None
            if r.holding is not None:
                self.state.attach_to_robot(r.holding, run.robot)
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
        stop = self.traffic.stop(robot, self._now)  # mid-drive: it stops at the cell it entered
        r.position = NavGrid.point(stop.cell)
        r.down = True
        self._reroute_around(robot, stop)
        self.events.append(SimEvent(t=self._now, kind="breakdown", detail=robot))
        run = self._running.pop(robot, None)
        if r.holding is not None:
            held, r.holding = r.holding, None
            floors = list(self.state.of_type("Floor"))
            self.state.move_object(held, floors[0].id if floors else None,
                                   position=(r.position[0], 0.0, r.position[1]))
            self.events.append(SimEvent(t=self._now, kind="drop", detail=f"{robot} dropped {held}"))
        self.disturbances.append((self._now, "breakdown", robot, self._snapshot()))
        if run is None:
            return None
        if run.spot is not None and self._locks.get(run.spot) == robot:
            del self._locks[run.spot]
        outcome = ActionOutcome(robot=robot, action=run.action, start=run.start, end=self._now,
                                success=False, reason=FailureReason.ROBOT_DOWN,
                                message=f"{robot} broke down")
        self.outcomes.append(outcome)
        return outcome

    def _reroute_around(self, broken: str, stop: Step) -> None:
        """Drives whose reserved way crosses a robot that broke down re-plan from where
        they are (or wait, if it walls them off)."""
        for other in self.traffic.crossing(stop.cell, self._now, broken):
            run = self._running.get(other)
            if run is None or not run.goals or run.end == float("inf"):
                continue
            fresh = _Running(run.robot, run.action, run.start, run.end, None, run.origin, run.destination,
                             run.failure, run.goals, run.blocked)
            path = self.traffic.replan(other, self._now, self._dt(other), run.goals)
            self.events.append(SimEvent(t=self._now, kind="nav-replan", detail=f"{other} around {broken}"))
            if path is None:
                self._blocked(fresh)
                continue
            fresh.end = max(path[-1].t, self._now)
            fresh.destination = NavGrid.point(path[-1].cell)
            self._launch(fresh)

    def _move_object(self, move: ObjectMove) -> None:
        oid = move.object if move.object is not None else self._draw_moved(move)
        o = self.state.objects.get(oid) if oid is not None else None
        if (o is None or o.held_by is not None or o.gone
                or (move.to is not None and move.to not in self.state.objects)):
            self.events.append(SimEvent(t=self._now, kind="move-skipped", detail=oid or "nothing movable"))
            return
        to = move.to
        if to is None:
            options = self._move_destinations(o.id, into_closed=move.into_closed)
            if not options:
                self.events.append(SimEvent(t=self._now, kind="move-skipped", detail=f"{o.id}: nowhere to put it"))
                return
            to = self.injector.choice(f"move|{o.id}|{move.at}|{move.draw}", options)
        self.state.move_object(o.id, to)
        closed = self.state.enclosing_closed(o.id)
        self.events.append(SimEvent(t=self._now, kind="moved",
                                    detail=f"{o.id} -> {to}" + (f" (closed {closed})" if closed else "")))
        self.disturbances.append((self._now, "moved", f"{o.id} -> {to}", self._snapshot()))

    def _move_destinations(self, oid: str, *, into_closed: bool) -> list[str]:
        """Where a person may put ``oid``: receptacles it fits in, closed ones only with
        ``into_closed``, and only places the team left can get it back from (as a person
        tidying a home does): within reach of a grid cell no broken robot walls off, and
        shut inside something only when a working robot can open it."""
        cat = load_catalogue()
        o = self.state.objects[oid]
        working = [r for r in self.state.robots.values() if not r.down]
        opener = any(Skill.OpenObject in r.profile.skills for r in working)
        cells: set[tuple[int, int]] | None = None
        if self.traffic.down:
            cells = set().union(*(self.traffic.open_cells(r.name, self._now) for r in working
                                  if r.name in self.traffic.paths))
        out = []
        for r in self.state.objects.values():
            if (not r.has("receptacle") or r.id in (o.id, o.parent) or r.gone or r.held_by is not None
                    or not cat.can_place(o.type, r.type) or o.id in self.state.ancestors(r.id)):
                continue
            # shut after the move: a closed receptacle, or inside one (the bowl in a shut fridge)
            shut = (r.type in cat.must_be_open and not r.is_open) or self.state.enclosing_closed(r.id) is not None
            if shut and not (into_closed and opener):
                continue
            poses = self.traffic.nav.poses_for((r.position[0], r.position[2]))
            if poses and (cells is None or any(p.cell in cells for p in poses)):
                out.append(r.id)
        return sorted(out)

    def _draw_moved(self, move: ObjectMove) -> str | None:
        """The object a ``random`` move takes: one of the candidates that exists now, lies
        somewhere (not held, not gone) and is not already where the draw would put it."""
        options = sorted(c for c in move.candidates
                         if c in self.state.objects and self.state.objects[c].held_by is None
                         and not self.state.objects[c].gone)
        return self.injector.choice(f"moved|{move.at}|{move.draw}", options) if options else None
