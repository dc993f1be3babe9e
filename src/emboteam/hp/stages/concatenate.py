"""The no-HP ablation (``merge="concatenate"``): each subtask is solved from the state its
dependencies leave, robots' lists are concatenated in subtask order, the only waits are
the subtask dependencies; with validation off nothing is simulated."""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.hp.allocation import allocate
from emboteam.hp.merge import GroundedStep, SeqStep, StepFailure, assemble, ground_sequence, order
from emboteam.hp.plan import MergedPlan
from emboteam.hp.rounds import polish
from emboteam.hp.stages.context import Context, Invalid
from emboteam.hp.stages.joint import plan_joint
from emboteam.hp.stages.merge import finish
from emboteam.hp.subtask_order import ancestors
from emboteam.hp.validate import estimate
from emboteam.pddl.errors import PlanValidationError
from emboteam.pddl.problem import build_problem
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.state import WorldState


def plan_concatenated(ctx: Context) -> MergedPlan:
    """The concatenated plan (validated unless validation is off; the joint fallback when
    it fails in the simulator)."""
    spec, start, team = ctx.spec, ctx.start, ctx.team
    load: dict[str, float] = {r: 0.0 for r in team}
    assigned = {a.subtask: a.robots for a in allocate(list(spec.subtasks), ctx.needs, start, team, load)}
    levels = _levels(spec)
    plans: dict[str, list[SeqStep]] = {}
    bases: dict[str, WorldState] = {}
    used: set[str] = set()  # robots with an earlier subtask: they start elsewhere
    for level in levels:
        problems = []
        for t in level:
            bases[t.id] = _lenient_state(start, [s for d in ancestors(spec, t.id) for s in plans.get(d, [])])
            away = [r for r in assigned[t.id] if r in used]
            used.update(assigned[t.id])
            problems.append(build_problem(bases[t.id], t.goal, assigned[t.id], name=t.id, elsewhere=away))
        results = ctx.solver.solve(problems)
        for t, problem, result in zip(level, problems, results, strict=True):
            if not result.solved:
                problem = build_problem(bases[t.id], t.goal, team, name=t.id, narrow=False, elsewhere=team)
                result = ctx.solver.solve([problem])[0]
                if not result.solved:
                    raise ctx.solver.unsolvable(t.id, t.goal, bases[t.id], team)
            plans[t.id] = [SeqStep(r, a, t.id, t.id) for r, a in polish(problem.decode(result.plan))]
    grounded: list[GroundedStep] = []
    for t in (t for level in levels for t in level):
        try:
            g, _ = ground_sequence(bases[t.id], plans[t.id])
        except StepFailure as exc:
            raise PlanValidationError(f"subtask {t.id}'s plan does not run: {exc}") from None
        grounded.extend(g)
    deps = {t.id: tuple(ancestors(spec, t.id)) for t in spec.subtasks}
    if not ctx.config.validate:
        waits = order(grounded, deps, "concatenate")
        plan = assemble(grounded, waits, team, deps)
        return estimate(plan, {s.id: g.seconds for s, g in zip(plan.steps, grounded, strict=True)})
    try:
        return finish(grounded, deps, team, start, spec.goal(), "concatenate")
    except Invalid as exc:
        ctx.notes.append(f"the concatenated plan failed in the simulator ({exc}): planned as one joint problem")
        return plan_joint(ctx)


def _levels(spec: TaskSpec) -> list[list[Subtask]]:
    """Subtasks by dependency depth (each level only depends on earlier ones)."""
    depth: dict[str, int] = {}

    def d(sid: str) -> int:
        if sid not in depth:
            deps = spec.subtask(sid).depends_on
            depth[sid] = 1 + max((d(x) for x in deps), default=-1)
        return depth[sid]

    levels: dict[int, list[Subtask]] = {}
    for t in spec.subtasks:
        levels.setdefault(d(t.id), []).append(t)
    return [levels[k] for k in sorted(levels)]


def _lenient_state(start: WorldState, steps: Sequence[SeqStep]) -> WorldState:
    """The state after ``steps``, skipping those that cannot run (no validation: the
    no-HP ablation plans each subtask from what its dependencies *probably* leave)."""
    s = start.copy()
    for st in steps:
        if check_action(s, st.robot, st.action) is None:
            apply_action(s, st.robot, st.action)
    return s
