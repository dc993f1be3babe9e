"""What a compiled tree needs while it runs: the environment, the shared blackboard,
the action bookkeeping between the tree and the executor, wake-up timers and a trace sink.

The tree's leaves never call the environment directly: :meth:`Runtime.start` starts an
action and returns a ticket, the executor hands every outcome it gets from
``Environment.advance`` to :meth:`Runtime.deliver`, and the leaf that holds the ticket
picks its outcome up on its next tick. That indirection is what lets the executor advance
simulated time from event to event while the tree only reacts.

A runtime without an environment (``env=None``) backs a tree that is only exported
(BehaviorTree.CPP XML, DOT, ASCII), never ticked.
"""

from __future__ import annotations

import heapq
import itertools
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any, Protocol

import py_trees
from py_trees.common import Access

from emboteam.btc.config import BTConfig
from emboteam.btc.keys import failed_key, flag_key, lock_key
from emboteam.btc.recovery import Diagnosis
from emboteam.sim.faults import FaultConfig, FaultInjector, MessageFaults
from emboteam.world.actions import Action, ActionOutcome
from emboteam.world.environment import Environment
from emboteam.world.state import WorldState


class TraceSink(Protocol):
    """Where the runtime reports what happens (the executor's trace recorder)."""

    def emit(self, kind: str, robot: str | None, **data: Any) -> None: ...


class _NullSink:
    def emit(self, kind: str, robot: str | None, **data: Any) -> None:
        return None


@dataclass(slots=True)
class Ticket:
    """One action started by a leaf of the tree."""

    id: int
    robot: str
    action: Action
    step: str
    recovery: str | None
    outcome: ActionOutcome | None = None
    orphaned: bool = False


@dataclass(slots=True)
class StepState:
    """Step-local scratch shared by the nodes of one step's subtree: the pending failure
    of its last core attempt, the current diagnosis and the budgets used so far. (The
    BehaviorTree.CPP export shows these as subtree-local blackboard entries.)"""

    step: str
    robot: str
    fault: str | None = None
    fault_message: str = ""
    diagnosis: Diagnosis | None = None
    fatal: str | None = None
    attempts: int = 0
    recoveries: int = 0
    waits: int = 0
    last_error: str = ""

    def fail_reason(self) -> str:
        return self.fatal or self.last_error or (f"{self.fault}: {self.fault_message}" if self.fault else
                                                 "gave up")


_RUNS = itertools.count(1)


class Board:
    """The shared py_trees blackboard of one compiled tree, behind one namespace
    (``/emboteam/run<N>``) so several episodes in one process never see each other's
    flags. Every robot has its own py_trees ``Client``; the compiler registers which keys
    it may read and write (a producer has exclusive write on its done flags), so a leaf
    that touches another robot's entry fails loudly instead of corrupting the protocol."""

    def __init__(self, sink: TraceSink, plan_index: int = 0) -> None:
        self.namespace = f"/emboteam/run{next(_RUNS)}"
        self._sink = sink
        self._plan_index = plan_index
        self._clients: dict[str, py_trees.blackboard.Client] = {}
        self._reader = py_trees.blackboard.Client(name="executor", namespace=self.namespace)
        self._values: dict[str, Any] = {}

    def client(self, robot: str) -> py_trees.blackboard.Client:
        c = self._clients.get(robot)
        if c is None:
            c = py_trees.blackboard.Client(name=robot, namespace=self.namespace)
            self._clients[robot] = c
        return c

    def register(self, robot: str, key: str, access: Access) -> None:
        c = self.client(robot)
        if not c.is_registered(key=key):
            c.register_key(key=key, access=access)
        if not self._reader.is_registered(key=key):
            self._reader.register_key(key=key, access=Access.READ)

    def read(self, robot: str, key: str, default: Any = None) -> Any:
        try:
            return self.client(robot).get(key)
        except KeyError:
            return default

    def peek(self, key: str, default: Any = None) -> Any:
        """Read as the executor (any registered key)."""
        if not self._reader.is_registered(key=key):
            return default
        try:
            return self._reader.get(key)
        except KeyError:
            return default

    def write(self, robot: str, key: str, value: Any) -> None:
        self.client(robot).set(key, value)
        if self._values.get(key, object()) != value:
            self._values[key] = value
            self._sink.emit("blackboard", robot, key=key, value=value, plan=self._plan_index)

    def snapshot(self) -> dict[str, Any]:
        """Every entry written so far (for tests and the trace viewer)."""
        return dict(self._values)

    def close(self) -> None:
        """Unregister the clients and clear the namespace's entries (the py_trees
        blackboard is process-global)."""
        for c in self._clients.values():
            c.unregister(clear=True)
        self._reader.unregister(clear=True)
        self._clients.clear()
        prefix = self.namespace + "/"
        for k in [k for k in py_trees.blackboard.Blackboard.storage if k.startswith(prefix)]:
            del py_trees.blackboard.Blackboard.storage[k]


class Runtime:
    """The environment binding and shared services of one compiled tree."""

    def __init__(self, env: Environment | None, *, config: BTConfig | None = None,
                 sink: TraceSink | None = None, plan_index: int = 0,
                 messages: MessageFaults | None = None, seed: int = 0) -> None:
        self._env = env
        #: the blackboard as a lossy network (``--msg-loss``/``--msg-delay``); the draws are
        #: seeded per message, so the same run loses and delays the same messages
        self.messages = messages or MessageFaults()
        self._net = FaultInjector(FaultConfig(messages=self.messages), seed)
        #: step -> (writer, simulated time) of its done flag
        self._flag_written: dict[str, tuple[str, float]] = {}
        #: spot -> (holder, time) of a lock whose release was lost: its lease runs out
        #: ``config.lock_lease`` seconds later, since the holder no longer renews it
        self._stale: dict[str, tuple[str, float]] = {}
        self._releases: dict[tuple[str, str], int] = {}
        self._spot_of_key: dict[str, str] = {}
        self._late: set[tuple[str, str]] = set()
        #: counts of the network's effects (recorded with the episode)
        self.lost_releases = 0
        self.lock_timeouts = 0
        self.late_reads = 0
        #: which plan of the run this tree executes (0: the first, k: the k-th replan);
        #: recorded with every action so step ids of different plans stay apart
        self.plan_index = plan_index
        self.config = config or BTConfig()
        self.sink: TraceSink = sink or _NullSink()
        self.board = Board(self.sink, plan_index)
        self._tickets: dict[int, Ticket] = {}
        self._running: dict[str, Ticket] = {}
        self._ids = itertools.count(1)
        self._timers: list[float] = []
        self.progress = False
        #: robot -> why its branch failed (filled by the branch isolation decorator)
        self.branch_failures: dict[str, str] = {}
        #: robot -> the step whose failure ended its branch
        self.failed_steps: dict[str, StepState] = {}
        #: recovery subtrees started (protocol waits excluded)
        self.recoveries = 0
        self.step_states: dict[str, StepState] = {}

    def emit(self, kind: str, robot: str | None, **data: Any) -> None:
        """Report to the trace, tagged with this tree's plan index."""
        self.sink.emit(kind, robot, **data, plan=self.plan_index)

    # ---- environment -----------------------------------------------------------------
    @property
    def env(self) -> Environment:
        if self._env is None:
            raise RuntimeError("this tree was compiled for export only; it has no environment")
        return self._env

    @property
    def attached(self) -> bool:
        return self._env is not None

    @property
    def now(self) -> float:
        return self.env.now

    def state(self) -> WorldState:
        return self.env.observe()

    def busy(self, robot: str) -> bool:
        return self.env.busy(robot) or robot in self._running

    def start(self, robot: str, action: Action, *, step: str, recovery: str | None) -> Ticket:
        """Start an action on the environment for a leaf of the tree."""
        ticket = Ticket(next(self._ids), robot, action, step, recovery)
        state = self.env.observe()
        obj = action.receptacle or action.target
        spot = state.spot_of(obj) if obj in state.objects else None
        self.emit("action_start", robot, step=step, action=str(action), skill=action.skill.value,
                       target=action.target, receptacle=action.receptacle, spot=spot,
                       recovery=recovery is not None, strategy=recovery)
        self._tickets[ticket.id] = ticket
        self._running[robot] = ticket
        self.env.start(robot, action)
        self.mark_progress()
        return ticket

    def deliver(self, outcomes: Iterable[ActionOutcome]) -> list[ActionOutcome]:
        """Hand outcomes from ``Environment.advance`` to the tickets waiting for them and
        record them; returns the outcomes no ticket of this tree claimed."""
        unclaimed: list[ActionOutcome] = []
        for out in outcomes:
            ticket = self._running.pop(out.robot, None)
            if ticket is None or ticket.action != out.action:
                if ticket is not None:
                    self._running[out.robot] = ticket
                unclaimed.append(out)
                continue
            ticket.outcome = out
            self.emit("action_end", out.robot, step=ticket.step, action=str(out.action),
                           success=out.success, reason=out.reason.value if out.reason else None,
                           message=out.message, recovery=ticket.recovery is not None,
                           strategy=ticket.recovery, orphaned=ticket.orphaned, start=out.start)
            if ticket.orphaned:
                del self._tickets[ticket.id]
            self.mark_progress()
        return unclaimed

    def take(self, ticket: Ticket) -> ActionOutcome | None:
        """The outcome of a ticket, once it has arrived (then the ticket is done)."""
        if ticket.outcome is not None:
            self._tickets.pop(ticket.id, None)
        return ticket.outcome

    def orphan(self, ticket: Ticket) -> None:
        """The leaf that started this action was interrupted: its outcome will be recorded
        but nobody waits for it (the robot counts as busy until it arrives)."""
        ticket.orphaned = True

    # ---- timers and progress ----------------------------------------------------------
    def wake_at(self, t: float) -> None:
        """Ask the executor to tick again at simulated time ``t`` (bounded waits)."""
        heapq.heappush(self._timers, t)

    def next_wakeup(self, after: float) -> float | None:
        while self._timers and self._timers[0] <= after + 1e-9:
            heapq.heappop(self._timers)
        return self._timers[0] if self._timers else None

    def mark_progress(self) -> None:
        self.progress = True

    # ---- blackboard protocol ----------------------------------------------------------
    def flag_set(self, robot: str, step: str) -> bool:
        """Has ``robot`` received the step's done flag? With a flag delay, another robot's
        flag arrives late: until then the reader sees it unset and asks to be woken."""
        if not self.board.read(robot, flag_key(step), False):
            return False
        written = self._flag_written.get(step)
        if written is None or written[0] == robot or not self.messages.flag_delay:
            return True
        arrives = written[1] + self._net.flag_delay(f"{self.plan_index}|{step}", robot)
        if self.now + 1e-9 >= arrives:
            return True
        if (step, robot) not in self._late:
            self._late.add((step, robot))
            self.late_reads += 1
            self.emit("network", robot, what="late_read", key=flag_key(step), arrives=round(arrives, 6))
        self.wake_at(arrives)
        return False

    def set_flag(self, robot: str, step: str) -> None:
        if step not in self._flag_written:
            self._flag_written[step] = (robot, self.now if self.attached else 0.0)
        self.board.write(robot, flag_key(step), True)
        self.mark_progress()

    def branch_failed(self, robot: str, reader: str | None = None) -> str | None:
        key = failed_key(robot)
        value = self.board.read(reader, key) if reader is not None else self.board.peek(key)
        return str(value) if value else None

    def holder(self, robot: str, spot: str) -> str | None:
        value = self.board.read(robot, lock_key(spot))
        return str(value) if value else None

    def spot_taken_by_other(self, robot: str, spot: str) -> bool:
        """Is the spot reserved by another robot? (Spots this robot never registered are
        checked through the executor's reader.)"""
        value = self.board.peek(lock_key(spot))
        return bool(value) and value != robot

    def try_acquire(self, robot: str, spot: str) -> bool:
        """Take the spot if it is free. Ticks are single-threaded, so test-and-set needs
        no further synchronisation."""
        holder = self.holder(robot, spot)
        if holder == robot:
            self._stale.pop(spot, None)  # its own lock: it renews the lease again
            return True
        if holder is not None:
            stale = self._stale.get(spot)
            if stale is None or stale[0] != holder:
                return False
            expires = stale[1] + self.config.lock_lease
            if self.now + 1e-9 < expires:
                self.wake_at(expires)
                return False
            # the holder's lease ran out (its release was lost): the lock is taken over
            del self._stale[spot]
            self.lock_timeouts += 1
            self.emit("network", robot, what="lock_timeout", key=lock_key(spot), holder=holder,
                      since=round(stale[1], 6))
        self._spot_of_key[lock_key(spot)] = spot
        self.board.write(robot, lock_key(spot), robot)
        self.mark_progress()
        return True

    def _release(self, robot: str, spot: str) -> None:
        """The robot lets the spot go; the message may be lost (the lock then stays on the
        board until its lease expires)."""
        n = self._releases.get((robot, spot), 0)
        self._releases[(robot, spot)] = n + 1
        self.mark_progress()
        if self._net.release_lost(f"{self.plan_index}|{robot}", spot, n):
            self._stale[spot] = (robot, self.now if self.attached else 0.0)
            self.lost_releases += 1
            self.emit("network", robot, what="release_lost", key=lock_key(spot),
                      lease_ends=round(self._stale[spot][1] + self.config.lock_lease, 6))
            return
        self.board.write(robot, lock_key(spot), None)

    def release(self, robot: str, spots: Iterable[str]) -> None:
        for spot in spots:
            if self.holder(robot, spot) == robot and spot not in self._stale:
                self._release(robot, spot)

    def release_all(self, robot: str) -> None:
        """Free every spot the robot holds (its branch ended or failed)."""
        c = self.board.client(robot)
        keys = [k.rsplit("/", 1)[-1] for k in (*c.write, *c.exclusive)]
        for key in keys:
            if key.startswith("lock_") and self.board.read(robot, key) == robot:
                spot = self._spot_of_key.get(key)
                if spot is None:
                    self.board.write(robot, key, None)
                    self.mark_progress()
                elif spot not in self._stale:
                    self._release(robot, spot)

    def fail_branch(self, robot: str, reason: str) -> None:
        self.branch_failures[robot] = reason
        self.board.write(robot, failed_key(robot), reason)
        self.release_all(robot)
        self.mark_progress()

    def close(self) -> None:
        self.board.close()
