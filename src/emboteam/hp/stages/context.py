"""What every stage gets and gives: the planning :class:`Context` (the task, the start
state, the team, the configuration, the Fast Downward :class:`Solver`, the notes so far) and
the :class:`Draft` (a validated plan with the record of how it was made)."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from emboteam.hp.config import PlannerConfig
from emboteam.hp.merge import GroundedStep
from emboteam.hp.plan import MergedPlan
from emboteam.hp.requirements import Need
from emboteam.pddl.domain import Universe
from emboteam.pddl.errors import PlannerTimeoutError, PlanningError, UnsolvableSubtaskError
from emboteam.pddl.problem import Problem, build_problem
from emboteam.pddl.runner import FastDownward, SolveResult
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.checker import condition_holds
from emboteam.world.goals import Condition, Goal
from emboteam.world.state import WorldState


class Fallback(Exception):
    """Decomposition cannot work here; the reason goes into the plan's notes."""


class Invalid(Exception):
    """The merged plan failed in the simulator; ``index`` is the position of the failed
    step in the merged sequence (None: no step failed, e.g. the goal did not hold)."""

    def __init__(self, why: str, index: int | None = None) -> None:
        super().__init__(why)
        self.index = index


@dataclass
class Record:
    """What a decomposed planning pass allocated: subtask -> cluster id, subtask -> robots,
    cluster id -> robots able to do it alone (empty: it stays where it is)."""

    cluster: dict[str, str] = field(default_factory=dict)
    assigned: dict[str, tuple[str, ...]] = field(default_factory=dict)
    candidates: dict[str, tuple[str, ...]] = field(default_factory=dict)
    #: the grounded sequence the plan was merged from (its steps in the plan's order)
    sequence: list[GroundedStep] = field(default_factory=list)


@dataclass
class Draft:
    """A validated plan and the record of how it was made (what the improvements change)."""

    plan: MergedPlan
    record: Record


class Solver:
    """Fast Downward for the stages: problems in parallel, time-outs raised (the time limit
    is a safety net: no plan may depend on where a search was cut off, issue 28), and the
    problems asked for in this planning call counted (the budgets count these)."""

    def __init__(self, fd: FastDownward, workers: int) -> None:
        self.fd = fd
        self.workers = workers
        #: texts of the problems asked for since :meth:`reset` (cache hits too), so that a
        #: warm cache, a disk cache or a planner reused for a second task gives the same plan
        self.asked: set[str] = set()

    def reset(self) -> None:
        self.asked = set()

    def solve_all(self, problems: Sequence[Problem], workers: int | None = None,
                  then: Callable[[Problem, SolveResult], None] | None = None
                  ) -> list[SolveResult | PlanningError]:
        """Each problem's result or typed error, in order; a time-out is raised. ``then``:
        see :meth:`FastDownward.solve_problems`."""
        self.asked.update(p.text for p in problems)
        results = self.fd.solve_problems(problems, self.workers if workers is None else workers, then)
        for r in results:
            if isinstance(r, PlannerTimeoutError):
                raise r
        return results

    def solve(self, problems: Sequence[Problem]) -> list[SolveResult]:
        """Each problem's result; any error is raised."""
        results = self.solve_all(problems)
        for r in results:
            if isinstance(r, PlanningError):
                raise r
        return [r for r in results if isinstance(r, SolveResult)]

    def unsolvable(self, what: str, conditions: Sequence[Condition], state: WorldState,
                   robots: Sequence[str]) -> UnsolvableSubtaskError:
        """Name the conditions that cannot be reached (each tried alone, a few calls)."""
        unmet = [c for c in conditions if not condition_holds(c, state)]
        culprits: list[Condition] = []
        if 1 < len(unmet) <= 4:
            problems = [build_problem(state, [c], robots, name="why", narrow=False, release=False)
                        for c in unmet]
            culprits = [c for c, r in zip(unmet, self.solve(problems), strict=True) if not r.solved]
        shown = culprits or unmet
        return UnsolvableSubtaskError(
            f"subtask {what} has no plan: {', '.join(str(c) for c in shown)} cannot be reached by "
            f"{', '.join(robots)}", subtask=what, unmet=tuple(str(c) for c in shown))


@dataclass
class Context:
    """One planning call: the task, where it starts, who may act, how to plan; ``notes``
    collects what the stages did, in words (the plan's notes)."""

    config: PlannerConfig
    solver: Solver
    spec: TaskSpec
    start: WorldState
    team: list[str]
    needs: Mapping[str, Sequence[Need]]
    notes: list[str] = field(default_factory=list)
    #: objects, statics and groundings over ``start`` that every stage's replays share
    #: (:meth:`Universe.at` their own states): a step grounded by one stage is reused by
    #: the next where the state answers alike (:mod:`emboteam.pddl.recorded`)
    universe: Universe = field(init=False, repr=False)
    #: what pure functions of a draft gave, by (what, id of its plan), with the plan and
    #: the sequence they were computed from (holding their ids): two stages asking about
    #: the same draft (the route stage left it as it was, the idle stage asks again)
    #: compute it once
    memo: dict[tuple[str, int], tuple[object, object, object]] = field(default_factory=dict, repr=False)

    #: ``spec.goal()`` and the spec it was made of (:attr:`goal`)
    _goal: tuple[TaskSpec, Goal] | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        self.universe = Universe(self.start.copy())

    @property
    def goal(self) -> Goal:
        """The task's goal, made once per spec (both frozen): every rebuilt plan's replay
        and simulation asks for it, and ``TaskSpec.goal`` builds and validates a new one."""
        if self._goal is None or self._goal[0] is not self.spec:
            self._goal = (self.spec, self.spec.goal())
        return self._goal[1]

    @property
    def independent(self) -> bool:
        """Every subtask final and independent: the improvements that splice or reorder
        steps keep no dependency waits, so they work only then."""
        return not any(t.depends_on or not t.final for t in self.spec.subtasks)
