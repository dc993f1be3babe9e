"""Scripted episodes for the report tests: a hand-written multi-robot plan driven through
the real :class:`emboteam.sim.Simulator`, recorded as the executor records a trace.

This is a *test fixture*, not an executor: the plan is written by hand and the "behavior
tree" is a fixed Sequence(Fallback(Pre, Recover), Core, Post) per step. Everything else is
real: the simulator decides durations, contention and (seeded) faults, the poses are
sampled from :meth:`Simulator.pose` along each navigation, and SR/GCR/Exec come from the
goal checker on the final simulated state. The report tests use it until
``emboteam.exec.executor`` produces real traces (and keep using it for deterministic
layouts and for the large-trace test).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from emboteam.exec.episode import ConditionOutcome, Episode
from emboteam.exec.trace import TraceEvent
from emboteam.hp.plan import MergedPlan, PlanStep, SyncPoint
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.sim.faults import FaultConfig
from emboteam.sim.simulator import Simulator
from emboteam.world.actions import Action, ActionOutcome, FailureReason, Skill
from emboteam.world.checker import check_goal
from emboteam.world.goals import Condition
from emboteam.world.navgrid import NavGrid
from emboteam.world.navigation import navigator
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

ROOT = "EmboTeam"
POSE_INTERVAL = 0.25
MAX_RETRIES = 3

G, OPEN, CLOSE, P, U = (Skill.GoToObject, Skill.OpenObject, Skill.CloseObject, Skill.PickupObject,
                        Skill.PutObject)


def _step(robot: str, n: int, skill: Skill, target: str, receptacle: str | None = None, *,
          subtask: str, after: tuple[str, ...] = ()) -> PlanStep:
    action = Action(skill=skill, target=target, receptacle=receptacle)
    resources = () if skill is Skill.GoToObject else (receptacle or target,)
    return PlanStep(id=f"{robot}.{n}", robot=robot, action=action, subtask=subtask, after=after,
                    resources=resources)


def fridge_taskspec() -> TaskSpec:
    def cond(text: str) -> tuple[Condition, ...]:
        return (Condition.parse(text),)

    return TaskSpec(
        instruction="Put the apple and the tomato in the fridge, slice the lettuce, switch "
                    "off the light, and close the fridge when everything is in.",
        subtasks=(
            Subtask(id="s1", description="put the apple in the fridge", robot="robot1",
                    goal=cond("inside(Apple, Fridge)")),
            Subtask(id="s2", description="put the tomato in the fridge", robot="robot2",
                    goal=cond("inside(Tomato, Fridge)")),
            Subtask(id="s3", description="slice the lettuce", robot="robot3",
                    goal=cond("sliced(Lettuce)")),
            Subtask(id="s4", description="switch off the light", robot="robot2",
                    goal=cond("off(LightSwitch)")),
            Subtask(id="s5", description="close the fridge", robot="robot3",
                    goal=cond("closed(Fridge)"), depends_on=("s1", "s2")),
        ),
    )


def fridge_plan() -> MergedPlan:
    """Three robots in FloorPlan1; robot2 and robot3 wait for robot1 at the fridge."""
    r1, r2, r3 = "robot1", "robot2", "robot3"
    steps = [
        _step(r1, 1, G, "Fridge_1", subtask="s1"),
        _step(r1, 2, OPEN, "Fridge_1", subtask="s1"),
        _step(r1, 3, G, "Apple_1", subtask="s1"),
        _step(r1, 4, P, "Apple_1", subtask="s1"),
        _step(r1, 5, G, "Fridge_1", subtask="s1"),
        _step(r1, 6, U, "Apple_1", "Fridge_1", subtask="s1"),
        _step(r2, 1, G, "Tomato_1", subtask="s2"),
        _step(r2, 2, P, "Tomato_1", subtask="s2"),
        _step(r2, 3, G, "Fridge_1", subtask="s2"),
        _step(r2, 4, U, "Tomato_1", "Fridge_1", subtask="s2", after=("robot1.2",)),
        _step(r2, 5, G, "LightSwitch_1", subtask="s4"),
        _step(r2, 6, Skill.SwitchOff, "LightSwitch_1", subtask="s4"),
        _step(r3, 1, G, "Drawer_9", subtask="s3"),
        _step(r3, 2, OPEN, "Drawer_9", subtask="s3"),
        _step(r3, 3, P, "Knife_1", subtask="s3"),
        _step(r3, 4, G, "Lettuce_1", subtask="s3"),
        _step(r3, 5, Skill.SliceObject, "Lettuce_1", subtask="s3"),
        _step(r3, 6, G, "Fridge_1", subtask="s5"),
        _step(r3, 7, CLOSE, "Fridge_1", subtask="s5", after=("robot1.6", "robot2.4")),
    ]
    sync = (
        SyncPoint(producer="robot1.2", consumer="robot2.4", reason="(is-open Fridge_1)"),
        SyncPoint(producer="robot1.6", consumer="robot3.7", reason="(in Apple_1 Fridge_1)"),
        SyncPoint(producer="robot2.4", consumer="robot3.7", reason="(in Tomato_1 Fridge_1)"),
    )
    return MergedPlan(robots=(r1, r2, r3), steps=tuple(steps), sync=sync)


def shuttle_plan(rounds: int) -> tuple[TaskSpec, MergedPlan]:
    """A long plan for the large-trace test: four robots carry objects between counters,
    ``rounds`` round trips each; robot2's k-th put waits for robot1's k-th put."""
    shuttles = {"robot1": "Apple_1", "robot2": "Tomato_1", "robot3": "Bread_1", "robot4": "Mug_1"}
    counters = ("CounterTop_1", "CounterTop_3")
    spec = TaskSpec(
        instruction=f"Carry the apple, tomato, bread and mug between the counters {rounds} times.",
        subtasks=tuple(
            Subtask(id=f"s{i}", description=f"shuttle {obj}", robot=robot,
                    goal=(Condition.parse(f"inside({obj}, CounterTop)"),))
            for i, (robot, obj) in enumerate(shuttles.items(), 1)
        ),
    )
    steps: list[PlanStep] = []
    sync: list[SyncPoint] = []
    for i, (robot, obj) in enumerate(shuttles.items(), 1):
        n = 0
        for k in range(rounds):
            dest = counters[(k + i) % 2]
            for skill, target, rec in ((G, obj, None), (P, obj, None), (G, dest, None), (U, obj, dest)):
                n += 1
                after: tuple[str, ...] = ()
                if robot == "robot2" and skill is U:
                    producer = f"robot1.{4 * (k + 1)}"
                    after = (producer,)
                    sync.append(SyncPoint(producer=producer, consumer=f"{robot}.{n}"))
                steps.append(_step(robot, n, skill, target, rec, subtask=f"s{i}", after=after))
    return spec, MergedPlan(robots=tuple(shuttles), steps=tuple(steps), sync=tuple(sync))


@dataclass
class _RobotRun:
    queue: list[PlanStep]
    step: PlanStep | None = None
    attempts: int = 0
    pending: list[tuple[Action, bool]] = field(default_factory=list)
    wake_at: float = 0.0
    finished: bool = False
    waiting_logged: bool = False


class ScriptedRecorder:
    """Runs a MergedPlan on the simulator and records TraceEvents the way the executor
    does (names of nodes: ``EmboTeam/<robot>/<step> <action>/<Pre|Recover|Core|Post>``)."""

    def __init__(self, plan: MergedPlan, floor_plan: str, team: str, *, seed: int,
                 faults: FaultConfig) -> None:
        self.plan = plan
        profiles = parse_team(team)
        self.sim = Simulator(load_scene(floor_plan), profiles, seed=seed, faults=faults)
        self.trace: list[TraceEvent] = []
        self.runs = {r: _RobotRun(queue=plan.for_robot(r)) for r in plan.robots}
        self.done: set[str] = set()
        self.outcomes: list[tuple[ActionOutcome, bool]] = []
        self._sim_events_seen = 0

    # ---- recording helpers -----------------------------------------------------------
    def emit(self, kind: str, robot: str | None = None, **data: object) -> None:
        self.trace.append(TraceEvent.model_validate(
            {"t": round(self.sim.now, 4), "kind": kind, "robot": robot, "data": data}))

    def node(self, robot: str, step: PlanStep | None, part: str | None, status: str) -> None:
        segments = [ROOT, robot]
        if step is not None:
            segments.append(f"{step.id} {step.action}")
        if part is not None:
            segments.append(part)
        self.emit("node", robot, node=segments[-1], path="/".join(segments), status=status)

    def pose(self, robot: str) -> None:
        x, z = self.sim.pose(robot)
        holding = self.sim.state.robots[robot].holding
        self.emit("pose", robot, x=round(x, 3), z=round(z, 3), holding=holding)

    # ---- the loop --------------------------------------------------------------------
    def run(self) -> None:
        self.emit("node", None, node=ROOT, path=ROOT, status="RUNNING")
        for robot in self.plan.robots:
            self.node(robot, None, None, "RUNNING")
            self.pose(robot)
        while True:
            for robot in self.plan.robots:
                self._dispatch(robot)
            if all(r.finished for r in self.runs.values()):
                break
            nxt = self._next_time()
            if nxt is None:
                break  # every remaining robot waits on a step that can no longer finish
            self._advance_to(nxt)
        self.emit("node", None, node=ROOT, path=ROOT,
                  status="SUCCESS" if len(self.done) == len(self.plan.steps) else "FAILURE")

    def _next_time(self) -> float | None:
        times = [t for t in [self.sim.next_event_time()] if t is not None]
        times += [r.wake_at for r in self.runs.values() if not r.finished and r.wake_at > self.sim.now]
        return min(times) if times else None

    def _advance_to(self, until: float) -> None:
        while self.sim.now < until - 1e-9:
            t = min(until, self.sim.now + POSE_INTERVAL)
            outcomes = self.sim.advance(t)
            self._record_sim_events()
            for robot in self.plan.robots:
                running = self.sim.running(robot)
                if running is not None and running.skill is Skill.GoToObject:
                    self.pose(robot)
            for outcome in outcomes:
                self._finish(outcome)

    def _record_sim_events(self) -> None:
        for ev in self.sim.events[self._sim_events_seen:]:
            self.trace.append(TraceEvent(t=ev.t, kind="sim", data={"kind": ev.kind, "detail": ev.detail}))
        self._sim_events_seen = len(self.sim.events)

    def _dispatch(self, robot: str) -> None:
        run = self.runs[robot]
        if run.finished or self.sim.busy(robot) or self.sim.now < run.wake_at - 1e-9:
            return
        if run.pending:
            action, recovery = run.pending.pop(0)
            self._start(robot, action, recovery)
            return
        if run.step is None:
            if not run.queue:
                run.finished = True
                self.node(robot, None, None, "SUCCESS")
                return
            step = run.queue[0]
            waiting = [d for d in step.after if d not in self.done]
            if waiting:
                if not run.waiting_logged:
                    self.emit("blackboard", robot, key=f"wait/{step.id}", value=waiting)
                    run.waiting_logged = True
                return
            run.waiting_logged = False
            run.queue.pop(0)
            run.step, run.attempts = step, 0
            self.node(robot, step, None, "RUNNING")
            self.node(robot, step, "Pre", "SUCCESS")
            self._start(robot, step.action, False)

    def _start(self, robot: str, action: Action, recovery: bool) -> None:
        step = self.runs[robot].step
        assert step is not None
        part = "Recover" if recovery and action != step.action else "Core"
        self.node(robot, step, part, "RUNNING")
        for res in step.resources:
            if action == step.action:
                self.emit("blackboard", robot, key=f"lock/{res}", value=robot)
        self.emit("action_start", robot, step=step.id, action=str(action), recovery=recovery)
        self.sim.start(robot, action)
        self.pose(robot)

    def _finish(self, outcome: ActionOutcome) -> None:
        robot = outcome.robot
        run = self.runs[robot]
        step = run.step
        assert step is not None
        recovery = bool(run.attempts) or outcome.action != step.action
        self.emit("action_end", robot, step=step.id, action=str(outcome.action),
                  success=outcome.success, reason=outcome.reason.value if outcome.reason else None,
                  message=outcome.message, recovery=recovery)
        self.outcomes.append((outcome, recovery))
        self.pose(robot)
        if outcome.action == step.action:
            for res in step.resources:
                self.emit("blackboard", robot, key=f"lock/{res}", value=None)
        part = "Recover" if outcome.action != step.action else "Core"
        self.node(robot, step, part, "SUCCESS" if outcome.success else "FAILURE")
        if outcome.action != step.action:
            return  # a recovery move ended; the core action is queued next
        if outcome.success:
            self.node(robot, step, "Post", "SUCCESS")
            self.node(robot, step, None, "SUCCESS")
            self.emit("blackboard", robot, key=f"done/{step.id}", value=True)
            self.done.add(step.id)
            run.step = None
            return
        run.attempts += 1
        reason = outcome.reason
        if run.attempts > MAX_RETRIES or reason is FailureReason.ROBOT_DOWN:
            self.node(robot, step, None, "FAILURE")
            self.node(robot, None, None, "FAILURE")
            run.finished = True
            return
        self.node(robot, step, "Recover", "RUNNING")
        if reason in (FailureReason.NOT_VISIBLE, FailureReason.NOT_REACHABLE):
            target = step.action.receptacle or step.action.target
            run.pending = [(Action(skill=Skill.GoToObject, target=target), True), (step.action, True)]
        elif reason is FailureReason.SPOT_BUSY:
            run.wake_at = self.sim.now + 1.0
            run.pending = [(step.action, True)]
        else:
            run.pending = [(step.action, True)]

    def episode(self, *, task: str, taskspec: TaskSpec, seed: int, faults: FaultConfig,
                fault_level: float) -> Episode:
        report = check_goal(taskspec.goal(), self.sim.state)
        n = len(self.outcomes)
        ok = sum(1 for o, _ in self.outcomes if o.success)
        makespan = max((o.end for o, _ in self.outcomes), default=0.0)
        return Episode(
            task=task, instruction=taskspec.instruction, floor_plan=self.sim.scene.floor_plan,
            robots=self.plan.robots, category="parallel", mode="full", frontend="oracle",
            seed=seed, faults=faults, fault_level=fault_level, success=report.success,
            gcr=report.gcr, exec=ok / n if n else 0.0, makespan=makespan, actions=n,
            failed_actions=n - ok, recoveries=sum(1 for _, rec in self.outcomes if rec),
            conditions=tuple(ConditionOutcome(condition=str(r.condition), holds=r.holds,
                                              satisfied=r.satisfied, required=r.required)
                             for r in report.results),
            taskspec=taskspec, plan=self.plan, trace=tuple(sorted(self.trace, key=lambda e: e.t)),
            plan_seconds=0.0,
        )


#: a seed under which FaultConfig.level(0.2) makes this plan fail and recover a few times
FRIDGE_SEED = 7


def scripted_fridge_episode(seed: int = FRIDGE_SEED, fault_level: float = 0.2) -> Episode:
    """The fridge task in FloorPlan1 for robots 1, 2, 3, with seeded faults."""
    faults = FaultConfig.level(fault_level)
    rec = ScriptedRecorder(fridge_plan(), "FloorPlan1", "1,2,3", seed=seed, faults=faults)
    rec.run()
    return rec.episode(task="fixture/scripted-fridge", taskspec=fridge_taskspec(), seed=seed,
                       faults=faults, fault_level=fault_level)


def scripted_shuttle_episode(rounds: int) -> Episode:
    """A large trace: four robots, ``rounds`` round trips each, no faults."""
    spec, plan = shuttle_plan(rounds)
    rec = ScriptedRecorder(plan, "FloorPlan1", "1,2,3,4", seed=0, faults=FaultConfig())
    rec.run()
    return rec.episode(task="fixture/scripted-shuttle", taskspec=spec, seed=0,
                       faults=FaultConfig(), fault_level=0.0)


# ---- the fixture's own checks: it must look like a real executor's trace ---------------

def test_scripted_episode_is_a_real_simulated_run() -> None:
    ep = scripted_fridge_episode()
    kinds = {e.kind for e in ep.trace}
    assert {"action_start", "action_end", "node", "blackboard", "pose"} <= kinds
    starts = [e for e in ep.trace if e.kind == "action_start"]
    ends = [e for e in ep.trace if e.kind == "action_end"]
    assert len(starts) == len(ends) == ep.actions
    assert ep.failed_actions >= 1 and ep.recoveries >= 1, "the seed must exercise recovery"
    assert ep.success and ep.gcr == 1.0
    times = [e.t for e in ep.trace]
    assert times == sorted(times)
    # poses move along navigations: robot1 ends on a pose of the fridge it went to last (a
    # grid cell within reach of it, no longer the fridge's own point)
    fridge = load_scene(1).get("Fridge_1").position
    last = [e for e in ep.trace if e.kind == "pose" and e.robot == "robot1"][-1]
    poses = navigator("FloorPlan1").poses_for((fridge[0], fridge[2]))
    assert (last.data["x"], last.data["z"]) in [NavGrid.point(p.cell) for p in poses]


def executed_fridge_episode(seed: int = FRIDGE_SEED, fault_level: float = 0.2,
                            faults: FaultConfig | None = None, *, linear: bool = False) -> Episode:
    """The same plan run by the real executor (``emboteam.exec.executor``): compiled
    behavior tree, blackboard protocol, recoveries, the executor's own trace; with
    ``linear``, by the no-BTC baseline (``emboteam.exec.linear``: no tree, no node events).
    ``faults`` overrides ``fault_level`` (breakdowns, moved objects)."""
    from emboteam.exec.executor import Executor, ExecutorSettings

    faults = faults if faults is not None else FaultConfig.level(fault_level)
    sim = Simulator(load_scene(1), parse_team("1,2,3"), seed=seed, faults=faults)
    spec, plan = fridge_taskspec(), fridge_plan()
    if linear:
        from emboteam.exec.linear import run_linear

        res = run_linear(sim, plan, spec.goal())
    else:
        res = Executor(sim, plan, spec.goal(), settings=ExecutorSettings(seed=seed)).run()
    assert res.report is not None
    return Episode(
        task="fixture/executed-fridge", instruction=spec.instruction, floor_plan="FloorPlan1",
        robots=plan.robots, category="parallel", mode="no-btc" if linear else "full", frontend="oracle", seed=seed,
        faults=faults, fault_level=fault_level, success=res.success, gcr=res.gcr, exec=res.exec_rate,
        makespan=res.makespan, actions=res.actions, failed_actions=res.failed_actions,
        recoveries=res.recoveries, replans=res.replans, error=res.error,
        conditions=tuple(ConditionOutcome(condition=str(r.condition), holds=r.holds,
                                          satisfied=r.satisfied, required=r.required)
                         for r in res.report.results),
        taskspec=spec, plan=plan, trace=res.trace,
    )
