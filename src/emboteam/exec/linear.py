"""Baseline executors without behavior trees, on the same environment, faults and trace
format as the reactive executor.

- :func:`run_linear`, the no-BTC ablation (and LaMMA-P's executor): the merged plan runs
  in order per robot, robots concurrently; a step whose cross-robot ``after`` producers
  have not ended yet is waited for (plain waiting: the producer's outcome does not
  matter), but nothing is checked before or after an action, nothing is recovered and
  nothing is replanned; a failed action is skipped and the robot goes on with its next.
- :func:`run_sequences`, SMART-LLM's executor: per-robot action lists run concurrently
  with no synchronisation and no checks at all.

Both run the whole plan and judge the goal at the end, as those systems do.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from emboteam.btc.blueprint import cross_robot_waits
from emboteam.exec.driver import Driver
from emboteam.exec.executor import ExecutionConfigError
from emboteam.exec.recorder import TraceRecorder
from emboteam.exec.result import ExecutionResult, StopReason
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.sim.faults import FaultConfig, FaultInjector, MessageFaults
from emboteam.world.actions import Action, ActionOutcome
from emboteam.world.checker import check_goal
from emboteam.world.environment import Environment
from emboteam.world.goals import Goal
from emboteam.world.robots import RobotProfile


def _check_team(env: Environment, robots: Sequence[str]) -> None:
    missing = sorted(set(robots) - set(env.observe().robots))
    if missing:
        raise ExecutionConfigError(f"the plan's robots {missing} are not in the team")


def run_linear(env: Environment, plan: MergedPlan, goal: Goal | None = None, *, time_limit: float = 600.0,
               pose_interval: float = 0.5, mode: str = "linear",
               joins: Sequence[tuple[RobotProfile, float]] = (), messages: MessageFaults | None = None,
               seed: int = 0) -> ExecutionResult:
    """Execute the merged plan linearly (see the module docstring).

    ``joins``: robots that enter the team mid-run; nothing replans, so they stay idle.
    ``messages``: with a flag delay, a robot learns that a producer step ended only that
    much later (the same seeded draw as the behavior trees' flags); there are no locks here
    to lose releases of."""
    if time_limit <= 0:
        raise ExecutionConfigError("time_limit must be positive")
    _check_team(env, plan.robots)
    recorder = TraceRecorder(env, nodes=False)
    driver = Driver(env, recorder, pose_interval=pose_interval)
    start, deadline = env.now, env.now + time_limit
    waits = cross_robot_waits(plan)
    queues = {r: list(plan.for_robot(r)) for r in plan.robots}
    running: dict[str, PlanStep] = {}
    ended: dict[str, float] = {}
    owner = {s.id: s.robot for s in plan.steps}
    pending_joins = sorted(joins, key=lambda j: j[1])
    joined: list[str] = []
    net = FaultInjector(FaultConfig(messages=messages or MessageFaults()), seed)
    late: set[tuple[str, str]] = set()
    network = {"lost_releases": 0, "lock_timeouts": 0, "late_reads": 0}
    outcomes: list[ActionOutcome] = []
    recorder.pull_sim_events()
    for r in env.observe().robots:
        recorder.pose(r, force=True)
    stop: StopReason = "plan_done"

    def known_at(producer: str, reader: str) -> float:
        """When ``reader`` learns that ``producer`` ended."""
        if owner.get(producer) == reader:
            return ended[producer]
        return ended[producer] + net.flag_delay(f"0|{producer}", reader)

    while True:
        while pending_joins and pending_joins[0][1] <= env.now + 1e-9:
            profile, _ = pending_joins.pop(0)
            env.add_robot(profile)
            joined.append(profile.name)
            recorder.pull_sim_events()
            recorder.pose(profile.name, force=True)
        wake: list[float] = []
        for robot in plan.robots:
            q = queues[robot]
            if robot in running or not q or env.busy(robot):
                continue
            step = q[0]
            if not all(p in ended for p in waits[step.id]):
                continue
            arrives = max([known_at(p, robot) for p in waits[step.id]] + [env.now])
            if arrives > env.now + 1e-9:
                wake.append(arrives)
                if (step.id, robot) not in late:
                    late.add((step.id, robot))
                    network["late_reads"] += 1
                    recorder.emit("network", robot, what="late_read", key=step.id, arrives=round(arrives, 6))
                continue
            q.pop(0)
            running[robot] = step
            recorder.emit("action_start", robot, step=step.id, action=str(step.action),
                          skill=step.action.skill.value, target=step.action.target,
                          receptacle=step.action.receptacle, spot=_spot(env, step.action),
                          recovery=False, strategy=None)
            env.start(robot, step.action)
        if not running and not wake:
            stop = "plan_done" if not any(queues.values()) else "stalled"
            break
        times = [x for x in (env.next_event_time(), *wake,
                             pending_joins[0][1] if pending_joins and running else None) if x is not None]
        if not times:
            stop = "stalled"
            break
        t = max(env.now, min(times))
        if t > deadline + 1e-9:
            driver.advance_to(deadline)
            stop = "time_limit"
            break
        for out in driver.advance_to(t):
            outcomes.append(out)
            step_or_none = running.get(out.robot)
            if step_or_none is not None and step_or_none.action == out.action:
                del running[out.robot]
                ended[step_or_none.id] = out.end
            recorder.emit("action_end", out.robot, step=step_or_none.id if step_or_none else None,
                          action=str(out.action), success=out.success,
                          reason=out.reason.value if out.reason else None, message=out.message,
                          recovery=False, start=out.start)
    for r in env.observe().robots:
        recorder.pose(r, force=True)
    state = env.observe()
    report = check_goal(goal, state) if goal is not None else None
    return ExecutionResult(
        mode=mode, success=bool(report and report.success), stop_reason=stop, report=report,
        makespan=round(env.now - start, 6),
        broken_robots=tuple(sorted(r for r, s in state.robots.items() if s.down)),
        joined_robots=tuple(joined), outcomes=tuple(outcomes), plans=(plan,), trace=tuple(recorder.events),
        network=network, wall_after_disturbance=recorder.wall_since_disturbance(),
    )


def _spot(env: Environment, action: Action) -> str | None:
    state = env.observe()
    obj = action.receptacle or action.target
    return state.spot_of(obj) if obj in state.objects else None


def sequences_plan(sequences: Mapping[str, Sequence[Action]]) -> MergedPlan:
    """Per-robot action lists as a plan without dependencies or literals."""
    steps = [PlanStep(id=f"{robot}.{i}", robot=robot, action=a, subtask="s1")
             for robot, acts in sequences.items() for i, a in enumerate(acts, 1)]
    return MergedPlan(robots=tuple(sequences), steps=tuple(steps))


def run_sequences(env: Environment, sequences: Mapping[str, Sequence[Action]], goal: Goal | None = None, *,
                  time_limit: float = 600.0, pose_interval: float = 0.5,
                  joins: Sequence[tuple[RobotProfile, float]] = ()) -> ExecutionResult:
    """SMART-LLM's execution: every robot runs its own list, no sync, no checks (so no
    message can be lost or late; a robot that joins stays idle)."""
    return run_linear(env, sequences_plan(sequences), goal, time_limit=time_limit,
                      pose_interval=pose_interval, mode="sequences", joins=joins)
