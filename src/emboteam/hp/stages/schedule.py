"""The CP-SAT stage (``PlannerConfig.schedule="optimal"``): the plan's actions given to the
exact model of the whole schedule (:mod:`emboteam.hp.optimal`: which robot does each job,
in which order, when), and the plan rebuilt from its answer: each job's steps for the
robot CP-SAT chose, all steps in the order of its start times, replayed on the symbolic
state (a moved job first drives to its object), merged and simulated; kept when the
simulated makespan is shorter. Only for specs whose subtasks are final and independent,
as the split (the rebuilt sequence keeps no dependency waits). No model is built where its
cheap lower bound (:mod:`emboteam.hp.optimal_lower`) already reaches the plan's makespan:
CP-SAT could find nothing shorter, so the plan is the same (30 of the 44 calls on MACE-THOR)."""

from __future__ import annotations

from dataclasses import dataclass

from emboteam.hp import optimal
from emboteam.hp.merge import SeqStep
from emboteam.hp.optimal_lower import lower_bound
from emboteam.hp.plan import MergedPlan
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.rebuilt import adopted, replayed, shorter

#: ``schedule="optimal"``: CP-SAT's deterministic time limit (about seconds of one core)
#: and the largest model (:func:`emboteam.hp.optimal.arcs`) it is given
OPTIMAL_LIMIT = optimal.REFERENCE_LIMIT
OPTIMAL_ARCS = optimal.MAX_ARCS
#: ``schedule="fast"``: the same for small models only (a MACE-THOR task's solves in a
#: few milliseconds; the budget is deterministic time, so the plan does not depend on
#: the machine's load)
FAST_LIMIT = 0.05
FAST_ARCS = 400
#: ``schedule="fast"``: not even the model is built for a plan of more steps (its replay
#: alone costs the 32-robot cells tens of milliseconds, and their models are far larger)
FAST_STEPS = 80


@dataclass(frozen=True)
class Budget:
    """How one CP-SAT call of the stage searches (counted in deterministic time)."""

    limit: float
    max_arcs: int
    #: ``linearization_level``: 2 puts the circuits and the route lengths into the LP
    #: (the bound that proves the larger models); 1 is cheaper for a model of a few jobs
    linearization: int = 2
    #: the strong search's CP-SAT searches (``linearization=2`` only; a fixed worker count
    #: and deterministic time, so the plan does not depend on the machine)
    portfolio: optimal.Portfolio = optimal.PORTFOLIO


FAST = Budget(FAST_LIMIT, FAST_ARCS, linearization=1)
OPTIMAL = Budget(OPTIMAL_LIMIT, OPTIMAL_ARCS)


def schedule(ctx: Context, draft: Draft) -> Draft:
    """``schedule="optimal"``: the draft rescheduled as CP-SAT's best schedule says, or
    the draft itself."""
    return _rescheduled(ctx, draft, OPTIMAL)


def schedule_small(ctx: Context, draft: Draft) -> Draft:
    """``schedule="fast"``: the same for a small model under a small budget."""
    if len(draft.plan.steps) > FAST_STEPS:
        return draft
    return _rescheduled(ctx, draft, FAST)


#: rounds of the stage, each from the plan the last one made (the model lets nobody wait
#: for what the merge orders on the way, so its schedule simulates a little longer, and
#: the next round's model starts from the new plan's actions); a count, not a clock
ROUNDS = 3


def _rescheduled(ctx: Context, draft: Draft, budget: Budget) -> Draft:
    for _ in range(ROUNDS):
        better = _once(ctx, draft, budget)
        if better is draft:
            break
        draft = better
    return draft


def _no_shorter(problem: optimal.Problem, makespan: float) -> bool:
    """Whether the model cannot end before ``makespan``: its cheap lower bound
    (:mod:`emboteam.hp.optimal_lower`) reaches it, so CP-SAT's answer would be dropped
    anyway (most MACE-THOR tasks' plans, issue 28: the model and the search cost ``fast``
    a quarter of its main thread there, for the same plan)."""
    bound = lower_bound(problem)
    return bound is not None and bound / optimal.SCALE >= makespan - 1e-6


def _keys(plan: MergedPlan, ref: optimal.Reference) -> dict[str, tuple[float, int]]:
    """Each step's place in CP-SAT's schedule: its own start (an operation) or that of the
    operation of its robot it drives to (a drive: just before it); a drive to nothing
    stays after the one before."""
    key: dict[str, tuple[float, int]] = {}
    pending: dict[str, list[str]] = {}
    last: dict[str, float] = {}
    for s in plan.steps:
        mine = pending.setdefault(s.robot, [])
        if s.id in ref.starts:
            last[s.robot] = ref.starts[s.id]
            for k, p in enumerate(mine):
                key[p] = (last[s.robot], k - len(mine))
            mine.clear()
            key[s.id] = (last[s.robot], 0)
        else:
            mine.append(s.id)
    for robot, mine in pending.items():
        for p in mine:
            key[p] = (last.get(robot, 0.0), 1)
    return key


def _once(ctx: Context, draft: Draft, budget: Budget) -> Draft:
    plan, seq = draft.plan, draft.record.sequence
    if not ctx.independent or len(seq) != len(plan.steps):
        return draft
    # without the carries' orders (optimal_carry): the replay below plans the drives again,
    # so a put into a box may cross its carry (at the box's other place), and the simulation
    # judges; with them fp303-pack-box's fast plan was 17.75 s, not 16.75
    problem = optimal.problem_of(plan, ctx.spec, ctx.start, carries=False)
    if problem is None or not problem.jobs or optimal.arcs(problem) > budget.max_arcs:
        return draft
    if _no_shorter(problem, plan.makespan):
        return draft
    ref = optimal.solve(problem, plan, budget.limit, linearization=budget.linearization, portfolio=budget.portfolio)
    if not ref.robots or ref.makespan >= plan.makespan - 1e-6:
        return draft
    key = _keys(plan, ref)
    robot_of = {s.id: ref.robots.get(s.id, s.robot) for s in plan.steps}
    order = sorted(range(len(seq)), key=lambda i: (*key[plan.steps[i].id], i))
    steps = [SeqStep(robot_of[plan.steps[i].id], seq[i].action, seq[i].subtask, seq[i].group) for i in order]
    what = f"CP-SAT's schedule ({ref.makespan:.1f} s in its model)"
    found = shorter(replayed(ctx, steps, what), plan, what)
    if found is None:
        return draft
    return adopted(ctx, draft, found, f"rescheduled by CP-SAT ({ref.status}, {ref.makespan:.1f} s in its model): "
                                      f"makespan {plan.makespan:.1f} -> {found.plan.makespan:.1f} s")
