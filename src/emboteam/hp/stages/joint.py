"""The joint fallback: the whole goal as ONE multi-robot problem, deordered and validated
as a decomposed plan is (robots taking turns if the partial order fails); the plan is
marked ``joint``."""

from __future__ import annotations

from emboteam.hp.merge import SeqStep, StepFailure, ground_sequence
from emboteam.hp.plan import MergedPlan
from emboteam.hp.rounds import Unit, attribute, polish
from emboteam.hp.stages.context import Context, Invalid
from emboteam.hp.stages.merge import finish
from emboteam.pddl.errors import PlanValidationError
from emboteam.pddl.problem import build_problem


def plan_joint(ctx: Context) -> MergedPlan:
    """One joint problem for the whole team; typed errors when it has no plan or the plan
    does not run."""
    spec, start, team, notes = ctx.spec, ctx.start, ctx.team, ctx.notes
    goal = spec.goal()
    if any(not t.final for t in spec.subtasks):
        notes.append("joint problem: intermediate (non-final) subtask goals are not planned")
    problem = build_problem(start, goal.conditions, team, name="joint")
    result = ctx.solver.solve([problem])[0]
    if not result.solved:
        problem = build_problem(start, goal.conditions, team, name="joint", narrow=False)
        result = ctx.solver.solve([problem])[0]
    if not result.solved:
        raise ctx.solver.unsolvable("joint (the whole goal)", goal.conditions, start, team)
    actions = polish(problem.decode(result.plan))
    unit = Unit("joint", list(spec.subtasks), tuple(team))
    steps = [SeqStep(r, a, t, "joint") for (r, a), t in zip(actions, attribute(actions, unit, start), strict=True)]
    try:
        grounded, _ = ground_sequence(start, steps)
    except StepFailure as exc:
        raise PlanValidationError(f"Fast Downward's joint plan does not run in the simulator: {exc}") from None
    try:
        plan = finish(grounded, {}, team, start, goal, "formal", ctx.config.validate)
    except Invalid as exc:
        notes.append(f"joint plan's partial order failed ({exc}): robots take turns")
        try:
            plan = finish(grounded, {}, team, start, goal, "sequential", ctx.config.validate)
        except Invalid as again:
            raise PlanValidationError(f"the joint plan fails in the simulator: {again}") from None
    return plan.model_copy(update={"joint": True})
