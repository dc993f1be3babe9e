"""Readings checked by the planner: when the reading cannot be planned, its next
candidates, then the most of it that can be. (In hp, not pfg: it plans, and hp already
reads pfg; pfg reading hp would make the packages import each other.)

The ranker checks a reading against the scene, the placement rules and the team, not
against the planner (a Fast Downward call per candidate would cost the reader its
milliseconds). So a reading can still fail there: a spurious ``held(Pen)`` next to
``closed(Box)``, a mug "in" the bed, a table no grid cell reaches, a joint problem too big
for the time limit, a plan the simulator refuses. Then the whole task failed although the
reader had other readings.
Here, only after the reading failed to plan:

1. the reading's next candidates (best first, as the ranker made them) are planned, at
   most :data:`MAX_CANDIDATES` of them;
2. if none plans, each goal condition of the reading is planned on its own (the
   planner's own validation and search, cheap per condition): those that fail are not
   attempted; if the rest still fails together, one more condition is left out (the
   reader's unsure ones first, then the last said), the fewest that lets the rest plan;
3. if nothing can be planned, the reading's own typed error stands.

Nothing is dropped silently: each condition left out is a :class:`NotAttempted` with the
planner's reason, and the notes say which reading ran and why (the reading is marked
unsure). The order of the tries is fixed, so the outcome depends only on the planner's
answers (deterministic, except where a time-out depends on the machine).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

from emboteam.hp.plan import MergedPlan
from emboteam.pddl.errors import PlannerLimitError, PlanningError, PlanValidationError, UnsolvableSubtaskError
from emboteam.pfg.candidates import Candidate, NotAttempted
from emboteam.pfg.ranker import edit_spec
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Condition
from emboteam.world.navfit import UnreachableObjectError

#: the planner's answers that say "this goal cannot be planned here" (a reading's fault,
#: worth another reading); other errors (a missing skill, bad input) stay errors
INFEASIBLE: tuple[type[Exception], ...] = (UnsolvableSubtaskError, PlannerLimitError, PlanValidationError,
                                           UnreachableObjectError)
#: what ends a fallback's try (a candidate or a part may fail the planner any way)
NOT_PLANNED: tuple[type[Exception], ...] = (*INFEASIBLE, PlanningError)
#: how many of the reading's other candidates are planned before falling back to a part
#: of it (each failed try can cost the planner's time limit)
MAX_CANDIDATES = 3

#: plans a TaskSpec or raises the planner's typed error
PlanFn = Callable[[TaskSpec], MergedPlan]


@dataclass(frozen=True)
class Feasible:
    """What is planned and run (``spec``, ``plan``), the reading it stands for
    (``requested``: all its conditions, those not attempted included), what was left out
    and the notes that say so."""

    spec: TaskSpec
    plan: MergedPlan
    requested: TaskSpec
    not_attempted: tuple[NotAttempted, ...] = ()
    notes: tuple[str, ...] = ()


def _why(exc: Exception) -> str:
    return f"{type(exc).__name__}: {exc}"


def plan_feasible(spec: TaskSpec, plan: PlanFn, candidates: Sequence[Candidate] = (),
                  unsure: Sequence[str] = ()) -> Feasible:
    """The reading planned as it is, else its next plannable candidate, else its largest
    plannable part (:mod:`module docs <emboteam.hp.feasible>`); raises the reading's own
    error when nothing of it plans."""
    try:
        return Feasible(spec, plan(spec), spec)
    except INFEASIBLE as exc:
        first = exc
    found = _next_candidate(spec, plan, candidates, first)
    if found is not None:
        return found
    part = _plannable_part(spec, plan, unsure, first)
    if part is None:
        raise first
    return part


def _next_candidate(spec: TaskSpec, plan: PlanFn, candidates: Sequence[Candidate],
                    first: Exception) -> Feasible | None:
    goals = set(spec.goal().conditions)
    others = [c for c in candidates if set(c.goals) != goals][:MAX_CANDIDATES]
    for rank, cand in enumerate(others, start=2):
        try:
            planned = plan(cand.spec)
        except PlannerLimitError:
            if isinstance(first, PlannerLimitError):
                break       # near copies of a problem too big for the limit: the next one is too
            continue
        except NOT_PLANNED:
            continue
        note = (f"unsure (planning): the reading as read cannot be planned ({_why(first)}); "
                f"took the next reading that plans, candidate {rank}: {cand.sentence}")
        return Feasible(cand.spec, planned, cand.spec, notes=(note,))
    return None


def _fails(spec: TaskSpec | None, plan: PlanFn) -> Exception | None:
    """The planner's reason ``spec`` cannot be planned, None when it plans."""
    if spec is None:
        return None
    try:
        plan(spec)
    except NOT_PLANNED as exc:
        return exc
    return None


def _plannable_part(spec: TaskSpec, plan: PlanFn, unsure: Sequence[str], first: Exception) -> Feasible | None:
    """The reading without the fewest conditions that keep it from planning: those that
    fail alone, then (if the rest still fails together) one more, unsure ones first."""
    goals = tuple(spec.goal().conditions)
    if len(goals) < 2:
        return None
    left_out: list[NotAttempted] = []
    for c in goals:
        exc = _fails(edit_spec(spec, (c,)), plan)
        if exc is not None:
            left_out.append(NotAttempted(condition=str(c), reason=f"cannot be planned on its own: {_why(exc)}"))
    rest = tuple(c for c in goals if str(c) not in {n.condition for n in left_out})
    part = _try_part(spec, rest, plan) if left_out else None    # (all of it failed already)
    if part is None:
        part, extra = _one_more_out(spec, rest, plan, unsure, first)
        left_out += extra
    if part is None:
        return None
    sub, planned = part
    note = (f"unsure (planning): the reading cannot be planned as a whole ({_why(first)}); "
            f"{len(left_out)} of its {len(goals)} conditions not attempted, the rest planned")
    return Feasible(sub, planned, spec, tuple(left_out), (note,))


def _try_part(spec: TaskSpec, goals: tuple[Condition, ...],
              plan: PlanFn) -> tuple[TaskSpec, MergedPlan] | None:
    sub = edit_spec(spec, goals) if goals else None
    if sub is None:
        return None
    try:
        return sub, plan(sub)
    except NOT_PLANNED:
        return None


def _one_more_out(spec: TaskSpec, rest: tuple[Condition, ...], plan: PlanFn, unsure: Sequence[str],
                  first: Exception) -> tuple[tuple[TaskSpec, MergedPlan] | None, list[NotAttempted]]:
    """Conditions that each plan alone but not together: leave out one, the reader's
    unsure ones first, then from the last said back (a late clause is likelier a misread
    aside than the main request); None when no single one frees the rest."""
    if len(rest) < 2:
        return None, []
    order = sorted(range(len(rest)), key=lambda i: (str(rest[i]) not in unsure, -i))
    for i in order:
        part = _try_part(spec, rest[:i] + rest[i + 1:], plan)
        if part is not None:
            why = f"plans alone, but not together with the rest ({_why(first)})"
            return part, [NotAttempted(condition=str(rest[i]), reason=why)]
    return None, []
