"""The reactive multi-robot executor: ticks a compiled behavior tree against an
:class:`~emboteam.world.environment.Environment` in simulated time.

Loop: tick the tree until it is quiet at this instant (a tick that wrote a flag or
started an action is followed by another at the same time, so a consumer sees its
producer's flag without waiting for the next event); check the goal; then jump to the
next event (an action ending, a scheduled fault, a waiting node's timer, a robot
joining) and hand the environment's outcomes to the tree.

Stops on success (the goal checker holds), when the plan is finished or lost and no
replan is possible, when nothing can happen any more (stalled), or at the time or tick
limit. When a robot's branch gives up, when a robot joins, or when the plan ended with
the goal unmet, the executor lets the actions in flight finish, asks the replanner for a
plan from the current state with the robots still working, compiles it and goes on (at
most ``max_replans`` failure-driven replans; every join gets one). If replanning fails the
old tree simply continues: the other robots' work is not lost.

The replanner gets the *whole* goal, not only its unmet conditions (the trace's ``replan``
event lists those): a condition that holds now must still hold at the end, and a planner
that does not know about it may undo it on the way (a plan for "apple in the fridge" alone
opens the fridge that "fridge closed" needed shut). Conditions already met cost the
planner nothing.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from py_trees.common import Status
from pydantic import BaseModel, ConfigDict, Field

from emboteam.btc.compiler import CompiledTree, compile_plan
from emboteam.btc.config import BTConfig
from emboteam.btc.runtime import Runtime
from emboteam.errors import EmboTeamError
from emboteam.exec.driver import Driver
from emboteam.exec.recorder import TraceRecorder
from emboteam.exec.replan import Replanner
from emboteam.exec.result import ExecutionResult, StopReason
from emboteam.hp.plan import MergedPlan
from emboteam.pddl.errors import ImpossibleGoalError, MissingSkillError, UnsolvableSubtaskError
from emboteam.sim.faults import MessageFaults
from emboteam.world.actions import ActionOutcome
from emboteam.world.checker import GoalReport, check_goal
from emboteam.world.environment import Environment
from emboteam.world.goals import Goal
from emboteam.world.robots import RobotProfile, robot_profile

#: re-ticks at one simulated instant before time is forced to move on (a safety net:
#: every progress mark comes from a bounded protocol step)
MAX_TICKS_PER_INSTANT = 200


class ExecutionConfigError(EmboTeamError):
    """An executor configuration that cannot run (negative limits, a join in the past)."""


class UnsavableTaskError(EmboTeamError):
    """After a disturbance (a robot broke down, an object was moved) the planner proves the
    goal out of reach of the robots left: the run stops at once instead of running out the
    clock."""


#: planner errors that say the goal cannot be reached (not "the planner gave up")
UNREACHABLE_ERRORS: tuple[type[EmboTeamError], ...] = (ImpossibleGoalError, MissingSkillError,
                                                       UnsolvableSubtaskError)


class Join(BaseModel):
    """A robot that joins the team at a simulated time (CLI ``--join PROFILE@SECONDS``)."""

    model_config = ConfigDict(frozen=True)

    profile: RobotProfile
    at: float = Field(ge=0)

    @classmethod
    def parse(cls, text: str, team: Sequence[str] = ()) -> Join:
        """``"5@30"`` or ``"robot5@30.5"``: profile 5 joins after 30 s. A profile already in
        ``team`` joins under a suffixed name (``robot5b``), as ``parse_team`` names copies."""
        profile_text, sep, at_text = text.strip().rpartition("@")
        if not sep or not profile_text:
            raise ExecutionConfigError(f"--join takes PROFILE@SECONDS, e.g. 5@30, not {text!r}")
        try:
            at = float(at_text)
        except ValueError:
            raise ExecutionConfigError(f"--join {text!r}: {at_text!r} is not a number of seconds") from None
        if not 0 <= at < float("inf"):  # nan and inf too: a robot that never joins is a typo
            raise ExecutionConfigError(f"--join {text!r}: the time must be a number of seconds >= 0")
        profile = robot_profile(profile_text)
        taken = set(team)
        name, k = profile.name, 0
        while name in taken:
            k += 1
            name = f"{profile.name}{chr(ord('a') + k)}"
        if name != profile.name:
            profile = profile.model_copy(update={"name": name})
        return cls(profile=profile, at=at)


def parse_joins(texts: Sequence[str], team: Sequence[str]) -> list[Join]:
    """``--join`` values, each named apart from the team and from the joins before it
    (two copies of profile 5 joining a team with robot5: robot5b, robot5c)."""
    taken = list(team)
    joins = []
    for text in texts:
        j = Join.parse(text, taken)
        taken.append(j.profile.name)
        joins.append(j)
    return joins


@dataclass(frozen=True)
class ExecutorSettings:
    """How a run is bounded, seeded and recorded: everything of an execution that is not
    the environment, the plan, the goal, the replanner or the joining robots.

    ``finish_plan``: run the plan to its end even when the goal holds earlier (a plan with
    intermediate subtasks, "rinse the lettuce, then put it on the counter", must not stop
    because the final state happens to hold before the rinse). ``messages``: the
    blackboard's message faults (``--msg-loss``/``--msg-delay``), seeded by ``seed``."""

    time_limit: float = 600.0
    tick_limit: int = 200_000
    seed: int = 0
    config: BTConfig = field(default_factory=BTConfig)
    max_replans: int = 3
    pose_interval: float = 0.5
    record_nodes: bool = True
    finish_plan: bool = False
    messages: MessageFaults = field(default_factory=MessageFaults)


class Executor:
    """Run a merged plan as a behavior tree. See the module docstring."""

    def __init__(self, env: Environment, plan: MergedPlan, goal: Goal, *,
                 replanner: Replanner | None = None, joins: Sequence[Join | tuple[RobotProfile, float]] = (),
                 settings: ExecutorSettings | None = None) -> None:
        settings = settings or ExecutorSettings()
        time_limit, tick_limit, seed = settings.time_limit, settings.tick_limit, settings.seed
        max_replans, pose_interval = settings.max_replans, settings.pose_interval
        if time_limit <= 0 or tick_limit <= 0 or max_replans < 0 or pose_interval < 0:
            raise ExecutionConfigError("time_limit and tick_limit must be positive, max_replans and "
                                       "pose_interval non-negative")
        try:
            self.joins = sorted((j if isinstance(j, Join) else Join(profile=j[0], at=j[1]) for j in joins),
                                key=lambda j: j.at)
        except ValueError as exc:
            raise ExecutionConfigError(f"bad join: {exc}") from None
        self.env = env
        self.plan = plan
        self.goal = goal
        self.replanner = replanner
        self.time_limit = time_limit
        self.tick_limit = tick_limit
        #: recorded with the result; the executor itself draws nothing at random (faults
        #: are the environment's, seeded there)
        self.seed = seed
        self.config = settings.config
        self.max_replans = max_replans
        self.finish_plan = settings.finish_plan
        self.recorder = TraceRecorder(env, nodes=settings.record_nodes)
        self.driver = Driver(env, self.recorder, pose_interval=pose_interval)
        self.outcomes: list[ActionOutcome] = []
        self.ticks = 0
        self.replans = 0
        self.replan_attempts = 0
        self.plans: list[MergedPlan] = []
        self.failed_robots: set[str] = set()
        self.joined: list[str] = []
        self.recoveries = 0
        self.error: str | None = None
        self.replan_error: str | None = None
        self.messages = settings.messages
        #: lost releases, lock timeouts, late flag reads over every tree of the run
        self.network = {"lost_releases": 0, "lock_timeouts": 0, "late_reads": 0}
        #: set when the planner proves the goal unreachable after a disturbance
        self.unsavable: str | None = None

    # ---- the loop ----------------------------------------------------------------------
    def run(self) -> ExecutionResult:
        env = self.env
        start = env.now
        deadline = start + self.time_limit
        self.recorder.pull_sim_events()
        for r in env.observe().robots:
            self.recorder.pose(r, force=True)
        tree = self._compile(self.plan)
        self.plans.append(self.plan)
        handled_failures: set[str] = set()
        stop: StopReason
        try:
            while True:
                self._tick_until_quiet(tree)
                rt = tree.runtime
                self.failed_robots |= set(rt.branch_failures)
                if self._goal_holds() and (not self.finish_plan or tree.root.status == Status.SUCCESS):
                    stop = "success"
                    break
                if self.ticks >= self.tick_limit:
                    stop = "tick_limit"
                    break
                if self.unsavable is not None:
                    stop = "unsavable"
                    break
                if self.joins and self.joins[0].at <= env.now + 1e-9:
                    tree = self._join_due(tree)
                    continue
                fresh = set(rt.branch_failures) - handled_failures
                done = tree.root.status == Status.SUCCESS
                if fresh or done:
                    handled_failures |= fresh
                    reason = "goal unmet at the end of the plan" if done and not fresh else \
                        "; ".join(f"{r}: {rt.branch_failures[r]}" for r in sorted(fresh))
                    # a breakdown gets its own replan, as a join does: it is not the plan's fault
                    broken = any(self._is_down(r) for r in fresh)
                    drained_from = len(self.outcomes)
                    replaced = self._replan_if_possible(tree, reason, budgeted=not broken)
                    if replaced is not None:
                        tree, handled_failures = replaced, set()
                        continue
                    if self.unsavable is not None:
                        continue  # stops at the top of the loop
                    if self._goal_holds():
                        stop = "success"
                        break
                    if not done and len(self.outcomes) > drained_from:
                        continue  # actions ended while draining: the old tree reacts first
                    if done:
                        stop = "failed" if rt.branch_failures else "plan_done"
                        break
                next_t = self._next_time(tree)
                if next_t is None:
                    replaced = self._replan_if_possible(tree, "stalled: nothing left that can happen",
                                                        budgeted=True)
                    if replaced is not None:
                        tree, handled_failures = replaced, set()
                        continue
                    stop = "unsavable" if self.unsavable is not None else "stalled"
                    break
                if next_t > deadline + 1e-9:
                    self._advance(tree, deadline)
                    stop = "success" if self._goal_holds() else "time_limit"
                    break
                self._advance(tree, next_t)
        except EmboTeamError as exc:
            self.error = str(exc)
            stop = "error"
        finally:
            self._retire(tree)
        for r in env.observe().robots:
            self.recorder.pose(r, force=True)
        report = check_goal(self.goal, env.observe())
        state = env.observe()
        if not report.success and self.error is None:
            self.error = self.unsavable or self.replan_error
        return ExecutionResult(
            mode="bt", seed=self.seed, success=report.success, stop_reason=stop, report=report,
            makespan=round(env.now - start, 6), ticks=self.ticks, replans=self.replans,
            recoveries=self.recoveries, failed_robots=tuple(sorted(self.failed_robots)),
            broken_robots=tuple(sorted(r for r, s in state.robots.items() if s.down)),
            joined_robots=tuple(self.joined), outcomes=tuple(self.outcomes), plans=tuple(self.plans),
            error=self.error, trace=tuple(self.recorder.events), network=dict(self.network),
            wall_after_disturbance=self.recorder.wall_since_disturbance(),
        )

    # ---- pieces ------------------------------------------------------------------------
    def _retire(self, tree: CompiledTree) -> None:
        """Close a tree, keeping what its runtime counted."""
        rt = tree.runtime
        self.recoveries += rt.recoveries
        self.failed_robots |= set(rt.branch_failures)
        self.network["lost_releases"] += rt.lost_releases
        self.network["lock_timeouts"] += rt.lock_timeouts
        self.network["late_reads"] += rt.late_reads
        tree.close()

    def _is_down(self, robot: str) -> bool:
        r = self.env.observe().robots.get(robot)
        return r is not None and r.down

    def _compile(self, plan: MergedPlan) -> CompiledTree:
        runtime = Runtime(self.env, config=self.config, sink=self.recorder, plan_index=len(self.plans),
                          messages=self.messages, seed=self.seed)
        try:
            return compile_plan(plan, runtime)
        except BaseException:
            runtime.close()
            raise

    def _goal_holds(self) -> bool:
        return check_goal(self.goal, self.env.observe()).success

    def _tick_until_quiet(self, tree: CompiledTree) -> None:
        visit = self.recorder.node_visitor(tree.paths, tree.robot_of)
        rt = tree.runtime
        for _ in range(MAX_TICKS_PER_INSTANT):
            rt.progress = False
            tree.tick(visit)
            self.ticks += 1
            if not rt.progress or tree.root.status != Status.RUNNING or self.ticks >= self.tick_limit:
                return

    def _next_time(self, tree: CompiledTree) -> float | None:
        now = self.env.now
        times = [self.env.next_event_time(), tree.runtime.next_wakeup(now)]
        if self.joins:
            times.append(self.joins[0].at)
        future = [t for t in times if t is not None]
        return max(now, min(future)) if future else None

    def _advance(self, tree: CompiledTree, t: float) -> None:
        outcomes = self.driver.advance_to(t)
        self.outcomes.extend(outcomes)
        for out in tree.runtime.deliver(outcomes):
            self.recorder.emit("action_end", out.robot, step=None, action=str(out.action),
                               success=out.success, reason=out.reason.value if out.reason else None,
                               message=out.message, recovery=False, start=out.start)

    def _drain(self, tree: CompiledTree) -> None:
        """Let every action in flight end (nothing new starts: the tree is not ticked)."""
        while self.driver.anyone_busy():
            t = self.env.next_event_time()
            if t is None:
                return
            self._advance(tree, t)

    def _unmet(self) -> tuple[GoalReport, Goal]:
        report = check_goal(self.goal, self.env.observe())
        return report, Goal(conditions=tuple(report.unmet()))

    def _replan_if_possible(self, tree: CompiledTree, reason: str, *, budgeted: bool,
                            newcomers: Sequence[str] = ()) -> CompiledTree | None:
        """Drain, ask the replanner, compile; ``None`` (and the old tree goes on) when
        there is no replanner, the budget is spent or replanning failed."""
        if self.replanner is None or (budgeted and self.replan_attempts >= self.max_replans):
            return None
        self._drain(tree)
        report, unmet = self._unmet()
        if report.success:
            return None
        if budgeted:
            self.replan_attempts += 1
        state = self.env.observe()
        robots = [r for r, s in state.robots.items() if not s.down]
        data = {"reason": reason, "unmet": [str(c) for c in unmet.conditions], "robots": robots}
        if not robots:
            self.recorder.emit("replan", None, **data, error="no robot is left working")
            if self.recorder.disturbed:
                self.unsavable = f"{UnsavableTaskError.__name__}: no robot is left working"
            return None
        try:
            give_work = getattr(self.replanner, "giving_work_to", None)
            if newcomers and callable(give_work):  # a robot that joins must receive work
                plan = give_work(state.copy(), self.goal, robots, newcomers)
            else:
                plan = self.replanner(state.copy(), self.goal, robots)
            new_tree = self._compile(plan)
        except EmboTeamError as exc:
            self.recorder.emit("replan", None, **data, error=str(exc))
            self.replan_error = f"replanning failed: {exc}"
            if isinstance(exc, UNREACHABLE_ERRORS) and self.recorder.disturbed:
                self.unsavable = (f"{UnsavableTaskError.__name__}: the goal is out of reach of "
                                  f"{', '.join(robots)} after the disturbance: {exc}")
            return None
        self.recorder.emit("replan", None, **data, error=None, steps=len(plan.steps))
        self.replans += 1
        self.plans.append(plan)
        self._retire(tree)
        return new_tree

    def _join_due(self, tree: CompiledTree) -> CompiledTree:
        """Robots whose join time has come enter the team; a replan gives them work."""
        names = []
        while self.joins and self.joins[0].at <= self.env.now + 1e-9:
            profile = self.joins.pop(0).profile
            self.env.add_robot(profile)
            self.joined.append(profile.name)
            names.append(profile.name)
            self.recorder.pull_sim_events()
            self.recorder.pose(profile.name, force=True)
        if self.replanner is None:
            self.recorder.emit("replan", None, reason=f"{', '.join(names)} joined", unmet=[], robots=[],
                               error="no replanner: the new robot stays idle")
            return tree
        replaced = self._replan_if_possible(tree, f"{', '.join(names)} joined", budgeted=False, newcomers=names)
        return replaced if replaced is not None else tree
