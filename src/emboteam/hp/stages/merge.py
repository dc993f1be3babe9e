"""The merge stage: a grounded sequence -> a partial order (:mod:`emboteam.hp.merge`),
validated in the simulator (:mod:`emboteam.hp.validate`); subtask dependencies as causal
orderings (:mod:`emboteam.hp.subtask_order`), made strict where the causal one fails."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from emboteam.hp.merge import GroundedStep, MergeMode, assemble, order
from emboteam.hp.plan import MergedPlan
from emboteam.hp.stages.context import Context, Invalid
from emboteam.hp.subtask_order import (
    Dependency,
    DependencyWaits,
    ancestors,
    dependency_waits,
    subtask_dependencies,
)
from emboteam.hp.validate import estimate, simulate, with_times
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Goal
from emboteam.world.state import WorldState


def finish(grounded: Sequence[GroundedStep], deps: Mapping[str, Sequence[str]], team: Sequence[str],
           start: WorldState, goal: Goal, mode: MergeMode, validate: bool = True,
           dependencies: DependencyWaits | None = None) -> MergedPlan:
    """Order, assemble and (with ``validate``) simulate; :class:`Invalid` when the plan
    fails there. ``dependencies`` replaces the whole-unit waits ``deps`` implies (the
    causal subtask dependencies)."""
    waits = order(grounded, deps, mode, dependency_waits=None if dependencies is None else dependencies.preds)
    plan = assemble(grounded, waits, team, deps, None if dependencies is None else dependencies.reasons)
    if not validate:
        return estimate(plan, {s.id: g.seconds for s, g in zip(plan.steps, grounded, strict=True)})
    timing = simulate(plan, start, goal)
    if not timing.ok:
        index = next((k for k, s in enumerate(plan.steps) if s.id == timing.failed_step), None)
        raise Invalid(timing.failure, index)
    return with_times(plan, timing)


def finish_independent(ctx: Context, sequence: Sequence[GroundedStep]) -> MergedPlan:
    """:func:`finish` for a sequence of independent final subtasks (the improvements')."""
    return finish(sequence, {}, ctx.team, ctx.start, ctx.goal, "formal", ctx.config.validate)


def merge_causal(ctx: Context, accepted: Sequence[GroundedStep], unit_of: Mapping[str, str],
                 notes: list[str]) -> MergedPlan:
    """Merge with the subtask dependencies as causal orderings
    (:mod:`emboteam.hp.subtask_order`) and validate. When that plan fails in the
    simulator, the dependencies involving the unit whose step failed (all remaining
    ones if no step failed or none of those is still causal) become strict (every
    step of the later subtask after the earlier one), noted, until the plan validates
    or every dependency is strict (then :class:`Invalid` propagates: the joint
    fallback). Never returns an unvalidated plan (unless validation is off)."""
    deps = subtask_dependencies(ctx.spec, unit_of)
    groups = group_dependencies(ctx.spec, unit_of)
    strict: set[Dependency] = set()
    while True:
        waits = dependency_waits(ctx.start, accepted, deps, strict)
        try:
            return finish(accepted, groups, ctx.team, ctx.start, ctx.goal, "formal", ctx.config.validate,
                          waits)
        except Invalid as exc:
            relaxed = [d for d in deps if d not in strict]
            if not relaxed:
                raise
            failed = accepted[exc.index].group if exc.index is not None else None
            culprits = [d for d in relaxed if failed in (d.later_group, d.earlier_group)] or relaxed
            strict.update(culprits)
            notes.append(f"the causal ordering of {', '.join(str(d) for d in culprits)} failed in the "
                         f"simulator ({exc}): strict ordering there (every step of the later subtask "
                         "waits for the earlier one)")


def group_dependencies(spec: TaskSpec, unit_of: Mapping[str, str]) -> dict[str, tuple[str, ...]]:
    """Planning unit -> the units holding its subtasks' (transitive) dependencies."""
    out: dict[str, set[str]] = {}
    for t in spec.subtasks:
        u = unit_of.get(t.id)
        if u is None:
            continue
        out.setdefault(u, set()).update(unit_of[d] for d in ancestors(spec, t.id) if d in unit_of)
    return {u: tuple(sorted(d - {u})) for u, d in out.items()}
