"""The node types of compiled trees: py_trees behaviours over a :class:`Runtime`.

Leaves are conditions (never RUNNING) or actions; composites are py_trees' own. Every
leaf knows how it appears in a BehaviorTree.CPP export (:attr:`Leaf.BTCPP_ID`, its kind
and :meth:`Leaf.ports`), so the XML describes exactly the tree that runs.

A leaf reports progress to the runtime whenever its status changes, so the executor can
tick again at the same simulated instant (a flag written late in one tick wakes its
consumer in the next) and only advances time when the tree is quiet.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import ClassVar, Literal

import py_trees
from py_trees.common import Status

from emboteam.btc.keys import failed_key, flag_key, lock_key
from emboteam.btc.recovery import (
    ACTING,
    BACKOFFS,
    POST_NOT_OBSERVED,
    PROTOCOL,
    Diagnosis,
    Strategy,
    diagnose_failure,
    diagnose_literal,
    fatal,
)
from emboteam.btc.runtime import Runtime, StepState, Ticket
from emboteam.pddl import vocabulary
from emboteam.pddl.literal import Literal as PddlLiteral
from emboteam.world.actions import TRANSIENT_FAILURES, Action, FailureReason

PortRef = Literal["robot", "target", "receptacle", "key", "local"] | None


@dataclass(frozen=True)
class Port:
    """A BehaviorTree.CPP port of a node: ``ref`` says how the value is written inside a
    step's SubTree (``{robot}``, ``{target}``, ``{receptacle}``, a remapped blackboard
    key, a subtree-local entry, or a literal when ``None``)."""

    name: str
    value: str
    direction: Literal["input", "output", "inout"] = "input"
    ref: PortRef = None
    description: str = ""


def literals_text(lits: Sequence[PddlLiteral]) -> str:
    return "; ".join(str(lit) for lit in lits)


class Leaf(py_trees.behaviour.Behaviour):
    """A leaf acting for one robot."""

    BTCPP_KIND: ClassVar[str] = "Action"
    BTCPP_ID: ClassVar[str] = ""
    DESCRIPTION: ClassVar[str] = ""

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState | None = None) -> None:
        super().__init__(name)
        self.runtime = runtime
        self.robot = robot
        self.step = step
        self._last: Status | None = None

    @property
    def btcpp_id(self) -> str:
        return self.BTCPP_ID

    def update(self) -> Status:
        status = self.evaluate()
        if status != self._last:
            self._last = status
            self.runtime.mark_progress()
        return status

    def evaluate(self) -> Status:
        raise NotImplementedError

    def ports(self) -> list[Port]:
        return [Port("robot", self.robot, ref="robot")]

    def diagnose(self, diagnosis: Diagnosis) -> Status:
        """Record why Pre failed (read by the recovery guards) and fail."""
        if self.step is not None:
            self.step.diagnosis = diagnosis
        self.feedback_message = str(diagnosis) + (f": {diagnosis.why}" if diagnosis.why else "")
        return Status.FAILURE


# ---- Pre conditions -------------------------------------------------------------------

class RobotUp(Leaf):
    BTCPP_KIND = "Condition"
    BTCPP_ID = "RobotUp"
    DESCRIPTION = "the robot has not broken down"

    def evaluate(self) -> Status:
        r = self.runtime.state().robots.get(self.robot)
        if r is None or r.down:
            return self.diagnose(fatal(f"{self.robot} is down"))
        return Status.SUCCESS


class _ProducerFlag(Leaf):
    """A node about another robot's step: its done flag and whether its branch failed."""

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState, producer: str,
                 producer_robot: str) -> None:
        super().__init__(name, runtime, robot, step)
        self.producer = producer
        self.producer_robot = producer_robot

    def ports(self) -> list[Port]:
        return [Port("flag", flag_key(self.producer), ref="key"),
                Port("producer_failed", failed_key(self.producer_robot), ref="key")]


class FlagSet(_ProducerFlag):
    """A producer step of another robot has ended with its effects observed."""

    BTCPP_KIND = "Condition"
    BTCPP_ID = "FlagSet"
    DESCRIPTION = "a producer step's done flag is set (fails if the producer's branch failed)"

    def evaluate(self) -> Status:
        if self.runtime.flag_set(self.robot, self.producer):
            return Status.SUCCESS
        failed = self.runtime.branch_failed(self.producer_robot, reader=self.robot)
        if failed:
            return self.diagnose(fatal(f"dependency {self.producer} will not happen: "
                                       f"{self.producer_robot} failed ({failed})"))
        return self.diagnose(Diagnosis(Strategy.WAIT_SYNC, self.producer,
                                       f"waiting for {self.producer}"))


class HoldsSpot(Leaf):
    BTCPP_KIND = "Condition"
    BTCPP_ID = "HoldsSpot"
    DESCRIPTION = "the robot holds the interaction spot's lock"

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState, spot: str) -> None:
        super().__init__(name, runtime, robot, step)
        self.spot = spot

    def evaluate(self) -> Status:
        holder = self.runtime.holder(self.robot, self.spot)
        if holder == self.robot:
            return Status.SUCCESS
        who = f" (held by {holder})" if holder else ""
        return self.diagnose(Diagnosis(Strategy.ACQUIRE_SPOT, self.spot, f"needs spot {self.spot}{who}"))

    def ports(self) -> list[Port]:
        return [*super().ports(), Port("spot", self.spot),
                Port("holder", lock_key(self.spot), "inout", ref="key")]


class RobotIdle(Leaf):
    BTCPP_KIND = "Condition"
    BTCPP_ID = "RobotIdle"
    DESCRIPTION = "the robot is not finishing an interrupted action"

    def evaluate(self) -> Status:
        if self.runtime.busy(self.robot):
            return self.diagnose(Diagnosis(Strategy.WAIT_IDLE, None, f"{self.robot} is busy"))
        return Status.SUCCESS


class _LiteralCheck(Leaf):
    """A condition over some of a step's ground PDDL literals."""

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState,
                 literals: Sequence[PddlLiteral]) -> None:
        super().__init__(name, runtime, robot, step)
        self.literals = tuple(literals)


class LiteralsHold(_LiteralCheck):
    """The step's PDDL preconditions, evaluated on what the robot observes with the
    planner's own abstraction function (:func:`emboteam.pddl.vocabulary.evaluate`)."""

    BTCPP_KIND = "Condition"
    BTCPP_ID = "LiteralsHold"
    DESCRIPTION = "every ground PDDL literal holds on the observed state"

    def evaluate(self) -> Status:
        state = self.runtime.state()
        for lit in self.literals:
            if not vocabulary.evaluate(lit, state):
                return self.diagnose(diagnose_literal(lit, state, self.robot))
        return Status.SUCCESS

    def ports(self) -> list[Port]:
        return [*super().ports(), Port("literals", literals_text(self.literals))]


class NoPendingFault(Leaf):
    """The last core attempt's failure has been handled (a retry must not start blind)."""

    BTCPP_KIND = "Condition"
    BTCPP_ID = "NoPendingFault"
    DESCRIPTION = "the last attempt's failure has been recovered from"

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState, action: Action) -> None:
        super().__init__(name, runtime, robot, step)
        self.action = action

    def evaluate(self) -> Status:
        assert self.step is not None
        if self.step.fault is None:
            return Status.SUCCESS
        return self.diagnose(diagnose_failure(self.step.fault, self.action, self.runtime.state(),
                                              self.robot))

    def ports(self) -> list[Port]:
        return [Port("fault", "fault", ref="local")]


# ---- Post -----------------------------------------------------------------------------

class EffectsObserved(_LiteralCheck):
    """The step's observable effects hold after its core action."""

    BTCPP_KIND = "Condition"
    BTCPP_ID = "EffectsObserved"
    DESCRIPTION = "every observable effect literal holds on the observed state"

    def evaluate(self) -> Status:
        state = self.runtime.state()
        missing = [lit for lit in self.literals if not vocabulary.evaluate(lit, state)]
        if not missing:
            return Status.SUCCESS
        assert self.step is not None
        self.step.fault = POST_NOT_OBSERVED
        self.step.fault_message = "effects not observed: " + literals_text(missing)
        self.feedback_message = self.step.fault_message
        return Status.FAILURE

    def ports(self) -> list[Port]:
        return [*super().ports(), Port("literals", literals_text(self.literals)),
                Port("fault", "fault", "output", ref="local")]


# ---- actions on the environment ------------------------------------------------------

#: a recovery action failing for any other reason cannot be cured by trying it again
_RETRYABLE = frozenset({*TRANSIENT_FAILURES, FailureReason.HELD_BY_OTHER})


class Act(Leaf):
    """Start one action on the environment and wait for its outcome.

    As the core of a step: SUCCESS when the action succeeds, or when it fails but every
    observable effect already holds (another robot opened the fridge first: the step's
    purpose is met, Post confirms it); otherwise FAILURE with the typed reason left as
    the step's pending fault for Recover. As a recovery action: its failure is left to
    the recovery loop, and a non-transient one ends the step's recovery.
    """

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState,
                 choose: Callable[[], Action | None], *, btcpp_id: str, ports: Sequence[Port],
                 recovery: Strategy | None = None, post: Sequence[PddlLiteral] = ()) -> None:
        super().__init__(name, runtime, robot, step)
        self.choose = choose
        self._btcpp_id = btcpp_id
        self._ports = list(ports)
        self.recovery = recovery
        self.post = tuple(post)
        self.ticket: Ticket | None = None

    @property
    def btcpp_id(self) -> str:
        return self._btcpp_id  # one node id per skill: GoToObject, PickupObject, ...

    def initialise(self) -> None:
        self.ticket = None

    def evaluate(self) -> Status:
        assert self.step is not None
        if self.ticket is None:
            if self.runtime.busy(self.robot):
                return Status.RUNNING  # an interrupted action is still finishing
            action = self.choose()
            if action is None:
                self.step.fatal = self.step.fatal or f"{self.name}: {self.robot} cannot do it"
                return Status.FAILURE
            if self.recovery is not None:
                self.step.recoveries += 1
            self.ticket = self.runtime.start(self.robot, action, step=self.step.step,
                                             recovery=self.recovery.value if self.recovery else None)
            self.feedback_message = f"started {action}"
            return Status.RUNNING
        out = self.runtime.take(self.ticket)
        if out is None:
            return Status.RUNNING
        self.ticket = None
        if out.success:
            return Status.SUCCESS
        reason = out.reason.value if out.reason else "unknown"
        self.feedback_message = f"{out.action} failed: {reason}"
        if self.recovery is None:
            state = self.runtime.state()
            if self.post and all(vocabulary.evaluate(lit, state) for lit in self.post):
                self.feedback_message += " (its effects already hold)"
                return Status.SUCCESS
            self.step.fault = reason
            self.step.fault_message = out.message
            return Status.FAILURE
        self.step.last_error = f"recovery {out.action} failed: {reason} {out.message}".strip()
        if out.reason not in _RETRYABLE:
            self.step.fatal = self.step.last_error
        return Status.FAILURE

    def terminate(self, new_status: Status) -> None:
        if new_status == Status.INVALID and self.ticket is not None:
            self.runtime.orphan(self.ticket)
            self.ticket = None

    def ports(self) -> list[Port]:
        return self._ports


# ---- protocol and recovery leaves -----------------------------------------------------

class Diagnosed(Leaf):
    """Guard of one recovery subtree: Pre's diagnosis calls for this strategy and its
    budget is not spent. Records the start of the recovery in the trace."""

    BTCPP_KIND = "Condition"
    BTCPP_ID = "Diagnosed"
    DESCRIPTION = "Pre's diagnosis calls for this recovery and its budget is not spent"

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState, strategy: Strategy) -> None:
        super().__init__(name, runtime, robot, step)
        self.strategy = strategy

    def evaluate(self) -> Status:
        assert self.step is not None
        d = self.step.diagnosis
        if d is None or d.strategy is not self.strategy or not within_budget(self.runtime, self.step,
                                                                             self.strategy):
            return Status.FAILURE
        if self.strategy not in PROTOCOL:
            self.runtime.recoveries += 1
            self.runtime.emit("recovery", self.robot, step=self.step.step, strategy=self.strategy.value,
                                   object=d.obj, why=d.why, fault=self.step.fault)
        return Status.SUCCESS

    def ports(self) -> list[Port]:
        return [Port("diagnosis", "diagnosis", ref="local"), Port("strategy", self.strategy.value)]


def within_budget(runtime: Runtime, step: StepState, strategy: Strategy) -> bool:
    cfg = runtime.config
    if strategy in ACTING:
        return step.recoveries < cfg.max_recoveries
    if strategy in BACKOFFS:
        return step.waits < cfg.max_waits
    return True


class GiveUp(Leaf):
    """Last child of the recovery selector: when no recovery applies (or its budget is
    spent) the step is lost; when the applicable one merely failed, try again later."""

    BTCPP_ID = "GiveUp"
    DESCRIPTION = "ends the step when no recovery applies or its budget is spent"

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState,
                 strategies: Sequence[Strategy]) -> None:
        super().__init__(name, runtime, robot, step)
        self.strategies = frozenset(strategies)

    def evaluate(self) -> Status:
        assert self.step is not None
        d = self.step.diagnosis
        if d is None:
            return Status.FAILURE
        if d.strategy is None:
            self.step.fatal = self.step.fatal or d.why
        elif d.strategy not in self.strategies:
            self.step.fatal = self.step.fatal or f"no {d.strategy} recovery here: {d.why}"
        elif not within_budget(self.runtime, self.step, d.strategy):
            self.step.fatal = self.step.fatal or f"{d.strategy} budget spent: {d.why}"
        if self.step.fatal:
            self.runtime.emit("recovery", self.robot, step=self.step.step,
                                   strategy=d.strategy.value if d.strategy else None,
                                   object=d.obj, why=self.step.fatal, gave_up=True)
            self.feedback_message = self.step.fatal
        return Status.FAILURE

    def ports(self) -> list[Port]:
        return [Port("diagnosis", "diagnosis", ref="local")]


class WaitFlag(_ProducerFlag):
    BTCPP_ID = "WaitFlag"
    DESCRIPTION = "RUNNING until a producer's done flag is set; FAILURE if its branch failed"

    def evaluate(self) -> Status:
        if self.runtime.flag_set(self.robot, self.producer):
            return Status.SUCCESS
        failed = self.runtime.branch_failed(self.producer_robot, reader=self.robot)
        if failed:
            assert self.step is not None
            self.step.fatal = f"dependency {self.producer} will not happen: {self.producer_robot} failed"
            return Status.FAILURE
        return Status.RUNNING


class AcquireSpot(Leaf):
    BTCPP_ID = "AcquireSpot"
    DESCRIPTION = "RUNNING until the spot is free, then takes its lock"

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState, spot: str) -> None:
        super().__init__(name, runtime, robot, step)
        self.spot = spot

    def evaluate(self) -> Status:
        return Status.SUCCESS if self.runtime.try_acquire(self.robot, self.spot) else Status.RUNNING

    def ports(self) -> list[Port]:
        return [*super().ports(), Port("spot", self.spot),
                Port("holder", lock_key(self.spot), "inout", ref="key")]


class ReleaseSpots(Leaf):
    BTCPP_ID = "ReleaseSpots"
    DESCRIPTION = "frees the spots at the end of the robot's run there"

    def __init__(self, name: str, runtime: Runtime, robot: str, spots: Sequence[str]) -> None:
        super().__init__(name, runtime, robot)
        self.spots = tuple(spots)

    def evaluate(self) -> Status:
        self.runtime.release(self.robot, self.spots)
        return Status.SUCCESS

    def ports(self) -> list[Port]:
        ports = [*super().ports(), Port("spots", ";".join(self.spots))]
        return ports + [Port(f"holder_{i}", lock_key(s), "inout", ref="key")
                        for i, s in enumerate(self.spots)]


class SignalDone(Leaf):
    BTCPP_ID = "SignalDone"
    DESCRIPTION = "writes the step's done flag for the robots waiting on it"

    def __init__(self, name: str, runtime: Runtime, robot: str, step_id: str) -> None:
        super().__init__(name, runtime, robot)
        self.step_id = step_id

    def evaluate(self) -> Status:
        self.runtime.set_flag(self.robot, self.step_id)
        return Status.SUCCESS

    def ports(self) -> list[Port]:
        return [Port("flag", flag_key(self.step_id), "output", ref="key")]


class WaitIdle(Leaf):
    BTCPP_ID = "WaitIdle"
    DESCRIPTION = "RUNNING until the robot's interrupted action has ended"

    def evaluate(self) -> Status:
        return Status.RUNNING if self.runtime.busy(self.robot) else Status.SUCCESS


class Backoff(Leaf):
    """Wait a bounded simulated time; asks the executor to wake the tree when it is over
    (the executor advances from event to event, so a wait must announce its end)."""

    BTCPP_ID = "Sleep"  # BehaviorTree.CPP's built-in Sleep(msec)
    BTCPP_KIND = "builtin"

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState, seconds: float) -> None:
        super().__init__(name, runtime, robot, step)
        self.seconds = seconds
        self.deadline = 0.0

    def initialise(self) -> None:
        assert self.step is not None
        self.step.waits += 1
        self.deadline = self.runtime.now + self.seconds
        self.runtime.wake_at(self.deadline)

    def evaluate(self) -> Status:
        return Status.SUCCESS if self.runtime.now >= self.deadline - 1e-9 else Status.RUNNING

    def ports(self) -> list[Port]:
        return [Port("msec", str(round(self.seconds * 1000)))]


class ClearFault(Leaf):
    BTCPP_ID = "ClearFault"
    DESCRIPTION = "marks the last attempt's failure as handled"

    def evaluate(self) -> Status:
        assert self.step is not None
        self.step.fault = None
        self.step.fault_message = ""
        return Status.SUCCESS

    def ports(self) -> list[Port]:
        return [Port("fault", "fault", "output", ref="local")]


class InReach(Leaf):
    BTCPP_KIND = "Condition"
    BTCPP_ID = "InReach"
    DESCRIPTION = "the object is within the robot's reach (1.5 m)"

    def __init__(self, name: str, runtime: Runtime, robot: str, step: StepState,
                 obj: Callable[[], str | None]) -> None:
        super().__init__(name, runtime, robot, step)
        self.obj = obj

    def evaluate(self) -> Status:
        o = self.obj()
        state = self.runtime.state()
        if o is None or o not in state.objects or self.robot not in state.robots:
            return Status.FAILURE
        return Status.SUCCESS if state.in_reach(self.robot, o) else Status.FAILURE

    def ports(self) -> list[Port]:
        return [*super().ports(), Port("object", "culprit", ref="local")]


# ---- decorators -----------------------------------------------------------------------

class _StepDecorator(py_trees.decorators.Decorator):
    """A decorator around one plan step's subtree, with the runtime and the step's state."""

    def __init__(self, name: str, child: py_trees.behaviour.Behaviour, runtime: Runtime,
                 step: StepState) -> None:
        super().__init__(name=name, child=child)
        self.runtime = runtime
        self.step = step


class Attempts(_StepDecorator):
    """Re-run a step's action sequence after a core failure, up to ``max_attempts``
    times; give up at once when recovery declared the step lost."""

    BTCPP_ID = "Attempts"
    DESCRIPTION = "retries the action sequence after a core failure; fails at once when recovery gave up"

    def update(self) -> Status:
        status = self.decorated.status
        if status != Status.FAILURE:
            return status
        self.step.attempts += 1
        limit = self.runtime.config.max_attempts
        exhausted = self.step.fatal is None and self.step.attempts >= limit
        if exhausted:
            self.step.fatal = (f"{self.step.attempts} attempts failed, last: "
                               f"{self.step.fault}: {self.step.fault_message}")
        self.runtime.mark_progress()
        if self.step.fatal is not None:
            self.feedback_message = self.step.fatal
            self.runtime.failed_steps[self.step.robot] = self.step
            if exhausted:  # a recovery that gave up has already said so in the trace
                self.runtime.emit("recovery", self.step.robot, step=self.step.step, strategy=None,
                                  why=self.step.fatal, gave_up=True)
            return Status.FAILURE
        self.feedback_message = f"attempt {self.step.attempts} failed ({self.step.fault}); retrying"
        return Status.RUNNING

    def ports(self) -> list[Port]:
        return [Port("max_attempts", str(self.runtime.config.max_attempts))]


class RecoverLoop(_StepDecorator):
    """Recover: run the recovery subtree Pre's diagnosis calls for, then report RUNNING
    so the reactive Fallback re-checks Pre on the next tick (a recovery succeeds only by
    making Pre true). FAILURE only when the step is lost."""

    BTCPP_ID = "RecoverLoop"
    DESCRIPTION = "runs the diagnosed recovery and hands back to Pre; fails only when the step is lost"

    def update(self) -> Status:
        status = self.decorated.status
        d = self.step.diagnosis
        if (status == Status.RUNNING and d is not None and not d.recoverable
                and not self.runtime.busy(self.step.robot)):
            # a wait in progress cannot outlast a lost cause (the robot broke down, the
            # producer it waits for failed): the memory selector would keep waiting
            self.decorated.stop(Status.INVALID)
            self.step.fatal = self.step.fatal or d.why
            self.runtime.emit("recovery", self.step.robot, step=self.step.step, strategy=None,
                                   object=d.obj, why=self.step.fatal, gave_up=True)
            return Status.FAILURE
        if status == Status.RUNNING:
            return Status.RUNNING
        if status == Status.FAILURE and self.step.fatal is not None:
            self.feedback_message = self.step.fatal
            return Status.FAILURE
        self.runtime.mark_progress()
        return Status.RUNNING

    def ports(self) -> list[Port]:
        cfg = self.runtime.config
        return [Port("max_recoveries", str(cfg.max_recoveries)), Port("max_waits", str(cfg.max_waits))]


class IsolateBranch(py_trees.decorators.Decorator):
    """Root policy: a robot's branch that fails is recorded (blackboard ``failed_<robot>``,
    its spots released) and reported as SUCCESS, so the team's Parallel keeps ticking the
    other robots' independent work; the executor decides about replanning."""

    BTCPP_ID = "IsolateBranch"
    DESCRIPTION = "records a failed branch (failed flag, spots released) and returns SUCCESS"

    def __init__(self, name: str, child: py_trees.behaviour.Behaviour, runtime: Runtime, robot: str) -> None:
        super().__init__(name=name, child=child)
        self.runtime = runtime
        self.robot = robot

    def update(self) -> Status:
        status = self.decorated.status
        if status == Status.RUNNING:
            return Status.RUNNING
        if status == Status.FAILURE:
            step = self.runtime.failed_steps.get(self.robot)
            reason = f"{step.step}: {step.fail_reason()}" if step is not None else "branch failed"
            self.feedback_message = reason
            self.runtime.fail_branch(self.robot, reason)
        else:
            self.runtime.release_all(self.robot)
        return Status.SUCCESS

    def ports(self) -> list[Port]:
        return [Port("robot", self.robot), Port("failed", failed_key(self.robot), "output", ref="key")]
