"""The Behavior Tree Compiler: a merged multi-robot plan -> one py_trees tree.

Shape (the paper's, with the protocol nodes made explicit)::

    Parallel team  [SuccessOnAll, synchronise]
      IsolateBranch robot_i
        Sequence robot_i  [memory]
          Sequence <step>  [memory]                       one per plan step, in order
            Attempts                                      bounded core attempts
              Sequence action  [memory]
                Fallback Pre|Recover  [reactive]          = Fallback(Pre, Recover)
                  Sequence Pre  [reactive]                robot up, sync flags, spot held,
                                                          idle, PDDL literals, no pending fault
                  RecoverLoop Recover
                    Fallback recoveries  [memory]         one guarded subtree per strategy,
                                                          then GiveUp
                Act <core action>                         starts it, RUNNING until its outcome
                EffectsObserved Post                      observable effect literals
            SignalDone                                    producers only: the sync flag
            ReleaseSpots                                  the end of the robot's run at a spot

Memory semantics, chosen deliberately:

- A robot's sequence and each step's sequences keep memory: a completed step is never
  re-checked (another robot may legitimately undo its effect later: open, then close),
  and a running core action is never re-entered.
- ``Pre|Recover`` is reactive (no memory): while Recover runs, Pre is re-checked every
  tick, so a recovery stops as soon as the precondition holds by itself (another robot
  opened the fridge meanwhile). Pre includes "robot idle", so an action in flight is
  never pre-empted this way.
- The recovery selector keeps memory: once a recovery subtree has started it runs to
  its end even if the diagnosis changes under it; Pre is then re-checked.
- The root Parallel uses ``SuccessOnAll(synchronise=True)``: a finished branch is not
  ticked again (re-ticking a finished memory sequence would restart the robot's whole
  plan), and :class:`~emboteam.btc.nodes.IsolateBranch` turns a failed branch into a
  recorded SUCCESS, because py_trees' Parallel fails, and stops every running child, as
  soon as one child fails: one robot's failure must not stop the others' work.
"""

from __future__ import annotations

import uuid
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import py_trees
from py_trees.common import Access, Status

from emboteam.btc.blueprint import PlanBlueprint, StepBlueprint, blueprint
from emboteam.btc.config import BTConfig
from emboteam.btc.keys import failed_key, flag_key, lock_key
from emboteam.btc.nodes import (
    AcquireSpot,
    Act,
    Attempts,
    Backoff,
    ClearFault,
    Diagnosed,
    EffectsObserved,
    FlagSet,
    GiveUp,
    HoldsSpot,
    InReach,
    IsolateBranch,
    LiteralsHold,
    NoPendingFault,
    Port,
    RecoverLoop,
    ReleaseSpots,
    RobotIdle,
    RobotUp,
    SignalDone,
    WaitFlag,
    WaitIdle,
)
from emboteam.btc.recovery import Strategy, put_down_action
from emboteam.btc.runtime import Runtime, StepState
from emboteam.hp.plan import MergedPlan
from emboteam.world.actions import Action, Skill
from emboteam.world.state import WorldState

Behaviour = py_trees.behaviour.Behaviour


@dataclass
class CompiledTree:
    """A compiled plan: the py_trees root, its runtime and what the executor, the trace
    and the exporters need to find their way around it."""

    plan: MergedPlan
    blueprint: PlanBlueprint
    runtime: Runtime
    root: py_trees.composites.Parallel
    branches: dict[str, Behaviour]
    steps: dict[str, Behaviour]
    paths: dict[uuid.UUID, str] = field(default_factory=dict)
    robot_of: dict[uuid.UUID, str] = field(default_factory=dict)
    ticks: int = 0

    def tick(self, visit: Callable[[Behaviour], None] | None = None) -> Status:
        """Tick the tree once. (py_trees' ``BehaviourTree.tick`` also walks the whole tree
        after every tick for "full" visitors; with thousands of recovery nodes that walk
        would dominate, so the tree is ticked directly and only visited nodes are seen.)"""
        for node in self.root.tick():
            if visit is not None:
                visit(node)
        self.ticks += 1
        return self.root.status

    def halt(self) -> None:
        """Stop every running node (their actions in flight become orphans)."""
        if self.root.status == Status.RUNNING:
            self.root.stop(Status.INVALID)

    def close(self) -> None:
        self.halt()
        self.runtime.close()

    def nodes(self) -> Iterator[Behaviour]:
        yield from self.root.iterate()


def _register(runtime: Runtime, bp: PlanBlueprint) -> None:
    """Declare every robot's blackboard access (see :class:`~emboteam.btc.runtime.Board`)."""
    board = runtime.board
    plan = bp.plan
    for robot in plan.robots:
        board.register(robot, failed_key(robot), Access.EXCLUSIVE_WRITE)
    for s in bp.steps.values():
        if s.signals:
            board.register(s.robot, flag_key(s.id), Access.EXCLUSIVE_WRITE)
        for p in s.waits:
            producer = bp.steps[p]
            board.register(s.robot, flag_key(p), Access.READ)
            board.register(s.robot, failed_key(producer.robot), Access.READ)
        for spot in (*s.holds, *s.releases):
            board.register(s.robot, lock_key(spot), Access.WRITE)


class _StepBuilder:
    """Builds one step's subtree."""

    def __init__(self, runtime: Runtime, bp: PlanBlueprint, sb: StepBlueprint) -> None:
        self.rt = runtime
        self.bp = bp
        self.sb = sb
        self.robot = sb.robot
        self.ss = StepState(step=sb.id, robot=sb.robot)
        runtime.step_states[sb.id] = self.ss

    # -- helpers ---------------------------------------------------------------------
    def culprit(self) -> str | None:
        d = self.ss.diagnosis
        return d.obj if d is not None else None

    def _can(self, skill: Skill) -> bool:
        if not self.rt.attached:
            return True
        r = self.rt.state().robots.get(self.robot)
        return r is not None and r.profile.can(skill)

    def _on_culprit(self, skill: Skill) -> Callable[[], Action | None]:
        def choose() -> Action | None:
            obj = self.culprit()
            if obj is None or not self._can(skill):
                return None
            return Action(skill=skill, target=obj)
        return choose

    def _act_on_culprit(self, skill: Skill, strategy: Strategy) -> Act:
        return Act(f"{skill.value}(culprit)", self.rt, self.robot, self.ss, self._on_culprit(skill),
                   btcpp_id=skill.value, recovery=strategy,
                   ports=[Port("robot", self.robot, ref="robot"), Port("target", "culprit", ref="local")])

    def _near_culprit(self, strategy: Strategy) -> Behaviour:
        return py_trees.composites.Selector("near it", memory=True, children=[
            InReach("in reach", self.rt, self.robot, self.ss, self.culprit),
            self._act_on_culprit(Skill.GoToObject, strategy),
        ])

    def _guarded(self, name: str, strategy: Strategy, *body: Behaviour) -> Behaviour:
        guard = Diagnosed(f"diagnosed {strategy}", self.rt, self.robot, self.ss, strategy)
        return py_trees.composites.Sequence(name, memory=True, children=[guard, *body])

    def _clear(self) -> ClearFault:
        return ClearFault("fault handled", self.rt, self.robot, self.ss)

    # -- recovery subtrees ----------------------------------------------------------
    def strategy(self, st: Strategy) -> Behaviour:
        rt, robot, ss, sb = self.rt, self.robot, self.ss, self.sb
        if st is Strategy.WAIT_SYNC:
            return self._guarded("wait for sync", st, *[
                WaitFlag(f"wait {p}", rt, robot, ss, p, self.bp.steps[p].robot) for p in sb.waits])
        if st is Strategy.ACQUIRE_SPOT:
            return self._guarded("acquire spots", st, *[
                AcquireSpot(f"acquire {spot}", rt, robot, ss, spot) for spot in sb.holds])
        if st is Strategy.WAIT_IDLE:
            return self._guarded("wait until idle", st, WaitIdle("idle", rt, robot, ss))
        if st is Strategy.REAPPROACH:
            return self._guarded("re-approach", st, self._act_on_culprit(Skill.GoToObject, st),
                                 self._clear())
        if st is Strategy.OPEN:
            return self._guarded("open receptacle", st, self._near_culprit(st),
                                 self._act_on_culprit(Skill.OpenObject, st), self._clear())
        if st is Strategy.FREE_HAND:
            def put_down() -> Action | None:
                return put_down_action(rt.state(), robot,
                                       lambda spot: rt.spot_taken_by_other(robot, spot))
            act = Act("put down held object", rt, robot, ss, put_down, btcpp_id="PutDownHeld",
                      recovery=st, ports=[Port("robot", robot, ref="robot")])
            return self._guarded("free the hand", st, act, self._clear())
        if st is Strategy.REGRASP:
            return self._guarded("re-grasp", st, self._near_culprit(st),
                                 self._act_on_culprit(Skill.PickupObject, st), self._clear())
        if st in (Strategy.WAIT_SPOT, Strategy.WAIT_HOLDER):
            name = "wait for spot" if st is Strategy.WAIT_SPOT else "wait for holder"
            return self._guarded(name, st, Backoff("back off", rt, robot, ss, rt.config.wait_seconds),
                                 self._clear())
        if st is Strategy.RETRY:
            return self._guarded("retry", st, self._clear())
        raise AssertionError(st)

    # -- the step ---------------------------------------------------------------------
    def build(self) -> Behaviour:
        rt, robot, ss, sb = self.rt, self.robot, self.ss, self.sb
        action = sb.step.action
        pre: list[Behaviour] = [RobotUp("robot up", rt, robot, ss)]
        pre += [FlagSet(f"{p} done", rt, robot, ss, p, self.bp.steps[p].robot) for p in sb.waits]
        pre += [HoldsSpot(f"holds {spot}", rt, robot, ss, spot) for spot in sb.holds]
        pre.append(RobotIdle("idle", rt, robot, ss))
        if sb.pre:
            pre.append(LiteralsHold("pre literals", rt, robot, ss, sb.pre))
        pre.append(NoPendingFault("no pending fault", rt, robot, ss, action))
        recoveries = [self.strategy(st) for st in sb.strategies]
        recoveries.append(GiveUp("give up", rt, robot, ss, sb.strategies))
        recover = RecoverLoop("Recover", py_trees.composites.Selector("recoveries", memory=True,
                                                                      children=recoveries), rt, ss)
        pre_or_recover = py_trees.composites.Selector("Pre|Recover", memory=False, children=[
            py_trees.composites.Sequence("Pre", memory=False, children=pre), recover])
        ports = [Port("robot", robot, ref="robot"), Port("target", action.target, ref="target")]
        if action.receptacle is not None:
            ports.append(Port("receptacle", action.receptacle, ref="receptacle"))
        core = Act(str(action), rt, robot, ss, lambda: action, btcpp_id=action.skill.value,
                   ports=ports, post=sb.post)
        post = EffectsObserved("Post", rt, robot, ss, sb.post)
        attempt = py_trees.composites.Sequence("action", memory=True, children=[pre_or_recover, core, post])
        children: list[Behaviour] = [Attempts("attempts", attempt, rt, ss)]
        if sb.signals:
            children.append(SignalDone(f"signal {sb.id}", rt, robot, sb.id))
        if sb.releases:
            children.append(ReleaseSpots(f"release {', '.join(sb.releases)}", rt, robot, sb.releases))
        return py_trees.composites.Sequence(f"{sb.id} {action}", memory=True, children=children)


def compile_plan(plan: MergedPlan, runtime: Runtime | None = None, *, state: WorldState | None = None,
                 config: BTConfig | None = None) -> CompiledTree:
    """Compile a merged plan into a behavior tree bound to ``runtime`` (a runtime without
    environment, for export only, when ``None``). ``state`` is the world when execution
    starts (default: the runtime's environment's); it predicts interaction spots for
    steps without ``resources``. Raises :class:`~emboteam.btc.errors.PlanCompileError`."""
    rt = runtime if runtime is not None else Runtime(None, config=config)
    if state is None and rt.attached:
        state = rt.state()
    bp = blueprint(plan, state)
    _register(rt, bp)
    branches: dict[str, Behaviour] = {}
    steps: dict[str, Behaviour] = {}
    for robot in plan.robots:
        seq: list[Behaviour] = []
        for sb in bp.for_robot(robot):
            node = _StepBuilder(rt, bp, sb).build()
            steps[sb.id] = node
            seq.append(node)
        branch = py_trees.composites.Sequence(robot, memory=True, children=seq)
        branches[robot] = IsolateBranch(f"isolate {robot}", branch, rt, robot)
    root = py_trees.composites.Parallel(
        "team", policy=py_trees.common.ParallelPolicy.SuccessOnAll(synchronise=True),
        children=list(branches.values()))
    compiled = CompiledTree(plan=plan, blueprint=bp, runtime=rt, root=root, branches=branches,
                            steps=steps)
    _index(compiled)
    return compiled


def _index(compiled: CompiledTree) -> None:
    """Node paths (``team/isolate robot1/robot1/robot1.3 .../Pre``) and owning robots."""
    def walk(node: Behaviour, prefix: str, robot: str | None) -> None:
        path = f"{prefix}/{node.name}" if prefix else node.name
        compiled.paths[node.id] = path
        if robot is not None:
            compiled.robot_of[node.id] = robot
        for child in node.children:
            walk(child, path, robot)

    compiled.paths[compiled.root.id] = compiled.root.name
    for robot, branch in compiled.branches.items():
        walk(branch, compiled.root.name, robot)
