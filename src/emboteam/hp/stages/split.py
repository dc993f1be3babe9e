"""The split stage: more than one robot on the longest cluster one robot does
(:mod:`emboteam.hp.cluster_split`), its parts planned one after the other from the state
the previous part leaves, spliced in place of the robot's steps, replayed, merged and
simulated; the plan with the shorter makespan is kept. Only for specs whose subtasks are
final and independent (the splice keeps no dependency waits).

- :func:`split_clusters` (``PlannerConfig.split_clusters``): two parts, the first for a
  lightly loaded helper from where the cluster started, the second for the robot;
- :func:`split_containers` (``PlannerConfig.split_containers``): one part per block (a
  pencil, a book and a statue put in a box, the box put on a table), among several robots.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from emboteam.hp import cluster_split
from emboteam.hp.merge import GroundedStep, SeqStep
from emboteam.hp.plan import MergedPlan
from emboteam.hp.requirements import covers
from emboteam.hp.rounds import Unit, attribute, polish
from emboteam.hp.stages import drive_ahead
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.rebuilt import shorter, simulated
from emboteam.hp.stages.replay import replay, replay_reusing
from emboteam.pddl.domain import Universe
from emboteam.pddl.errors import PlanningError
from emboteam.pddl.problem import Problem, build_problem
from emboteam.pddl.runner import SolveResult
from emboteam.sim.durations import navigation_seconds
from emboteam.sim.rules import apply_action
from emboteam.world.checker import check_condition, condition_holds
from emboteam.world.goals import Condition, ObjectRef
from emboteam.world.state import WorldState

log = logging.getLogger(__name__)

#: Fast Downward calls one cluster split may make (two per order of its two parts)
SPLIT_CALLS = 4


@dataclass
class _Cut:
    """The cluster to split, cut out of the plan's sequence: the steps before it, its own
    (gone), the rest; the state where it started and the goals reached there."""

    target: cluster_split.SplitTarget
    before: list[GroundedStep]
    gone: list[GroundedStep]
    rest: list[GroundedStep]
    here: WorldState
    kept: list[Condition]
    universe: Universe
    subjects: dict[str, frozenset[str]]


def able_of(ctx: Context) -> Callable[[str, Sequence[str]], bool]:
    """``able(robot, members)``: can that robot do every one of those subtasks alone."""
    def able(robot: str, members: Sequence[str]) -> bool:
        profile = ctx.start.robots[robot].profile
        return all(covers([profile], n) for m in members for n in ctx.needs.get(m, ()))
    return able


def _cut(ctx: Context, draft: Draft) -> _Cut | None:
    """The longest cluster to split and the plan cut around it (None: nothing to split)."""
    if not ctx.independent:
        return None
    start = ctx.start
    target = cluster_split.find_target(draft.plan, draft.record.cluster, able_of(ctx))
    if target is None or len(draft.record.sequence) != len(draft.plan.steps):
        return None
    before, gone, rest = cluster_split.splice(draft.record.sequence, target)
    log.debug("split %s (makespan %.1f, bound %.1f)", target, draft.plan.makespan, draft.plan.resource_bound)
    here = start.copy()
    for g in before:
        apply_action(here, g.robot, g.action)
    members = set(target.members)
    kept = [c for t in ctx.spec.subtasks if t.id not in members for c in t.goal if condition_holds(c, here)]
    subjects = {t.id: frozenset(_kind(c.subject, start) for c in t.goal) for t in ctx.spec.subtasks
                if t.id in members}
    return _Cut(target, before, gone, rest, here, kept, ctx.universe, subjects)


def _conds(ctx: Context, part: Sequence[str]) -> list[Condition]:
    goal_of = {t.id: t.goal for t in ctx.spec.subtasks}
    return [c for m in part for c in goal_of[m]]


def _steps_of(ctx: Context, problem: Problem, result: SolveResult, part: Sequence[str],
              state: WorldState) -> list[SeqStep]:
    actions = polish(problem.decode(result.plan))
    unit = Unit("split", [ctx.spec.subtask(m) for m in part], ())
    return [SeqStep(r, a, t, t) for (r, a), t in zip(actions, attribute(actions, unit, state), strict=True)]


def split_containers(ctx: Context, draft: Draft) -> Draft:
    """One part per block among several robots: the part that moves the container first
    for the cluster's robot (or last), the helpers' parts for the able robots that could
    be at each part's first thing earliest (:func:`near_helpers`), each from the state the
    previous one leaves; kept when shorter."""
    cut = _cut(ctx, draft)
    if cut is None:
        return draft
    target, start, plan = cut.target, ctx.start, draft.plan
    receptacles = {t.id: frozenset(_kind(c.receptacle, start) for c in t.goal if c.receptacle is not None)
                   for t in ctx.spec.subtasks if t.id in set(target.members)}
    parts = cluster_split.container_parts(target, cut.subjects, receptacles,
                                          min(cluster_split.MAX_PARTS, len(target.helpers) + 1))
    if not parts:
        return draft
    helpers = near_helpers(ctx, draft, target.helpers, parts[:-1])
    found: tuple[MergedPlan, list[GroundedStep]] | None = None
    for order in cluster_split.CONTAINER_ORDERS:
        if order == "last":
            robots, ordered = [*helpers, target.robot], list(parts)
        else:
            robots = [target.robot, *helpers]
            ordered = cluster_split.container_first(parts, target.members, cut.subjects, receptacles)
        tried = _split_parts(ctx, found[0] if found else plan, cut, robots, ordered)
        if tried is not None:
            found = tried
    if found is None:
        return draft
    best, sequence = found
    draft.record.sequence = sequence
    ctx.notes.append(f"{', '.join(target.members)}: parted among {', '.join(helpers)} and "
                     f"{target.robot}: makespan {plan.makespan:.1f} -> {best.makespan:.1f} s")
    return Draft(best, draft.record)


def near_helpers(ctx: Context, draft: Draft, able: Sequence[str], parts: Sequence[Sequence[str]]) -> list[str]:
    """A helper for each part, in order: the able robot not chosen yet that could be at
    the part's first thing earliest (its end in the plan, then the drive from where the
    plan leaves it). The robot that merely ends first may stand across the room
    (FloorPlan201, goal seed 1, 32 x 32: a 9.75 s drive to the remote control)."""
    ends: dict[str, float] = {}
    for s in draft.plan.steps:
        ends[s.robot] = max(ends.get(s.robot, 0.0), s.est_end)
    final = ctx.start.copy()
    for g in draft.record.sequence:
        apply_action(final, g.robot, g.action)
    chosen: list[str] = []
    for part in parts:
        place = _first_place(ctx, part)
        free = [r for r in able if r not in chosen]
        if not free:
            break
        chosen.append(min(free, key=lambda r: (ends.get(r, 0.0) + _drive(final, r, place), r)))
    return chosen


def _drive(state: WorldState, robot: str, place: tuple[float, float] | None) -> float:
    """Seconds ``robot`` drives from where it stands in ``state`` to ``place``."""
    if place is None:
        return 0.0
    r = state.robots[robot]
    return navigation_seconds(r.position, place, r.profile.speed, state.floor_plan)


def _first_place(ctx: Context, part: Sequence[str]) -> tuple[float, float] | None:
    """Where the first thing a part drives to stands at the start (None: nothing)."""
    objects = ctx.start.objects
    for m in part:
        for need in ctx.needs.get(m, ()):
            for oid in need.visits:
                o = objects.get(oid) or objects.get(oid.split("_Slice_")[0])
                if o is not None:
                    return o.position[0], o.position[2]
    return None


def _split_parts(ctx: Context, plan: MergedPlan, cut: _Cut, robots: Sequence[str], parts: Sequence[Sequence[str]]
                 ) -> tuple[MergedPlan, list[GroundedStep]] | None:
    """The cluster in ``parts`` (:func:`cluster_split.container_parts`), one robot each,
    each planned from the state the previous one leaves with the goals reached so far
    protected (one Fast Downward call a part); spliced, replayed, merged and simulated.
    The plan and its sequence when its makespan is shorter, else None."""
    state, reached = cut.here, list(cut.kept)
    new: list[GroundedStep] = []
    for robot, part in zip(robots, parts, strict=True):
        problem = _split_problem(state, _conds(ctx, part), robot, reached)
        if problem is None:
            return None
        result = ctx.solver.solve_all([problem], 1)[0]
        if not isinstance(result, SolveResult) or not result.solved:
            return None
        after = state.copy()
        grounded, why = replay(after, _steps_of(ctx, problem, result, part, state), cut.universe)
        if why is not None or not all(condition_holds(c, after) for c in _conds(ctx, part)):
            log.debug("part %s of %s fails: %s", part, robot, why or "misses its goal")
            return None
        new.extend(grounded)
        reached.extend(_conds(ctx, part))
        state = after
    found = _spliced(ctx, plan, cut, state, new, f"split into {parts}")
    return _appended(ctx, found[0] if found else plan, cut, new, f"split into {parts}, after the helpers' work") \
        or found


def _appended(ctx: Context, plan: MergedPlan, cut: _Cut, new: Sequence[GroundedStep], what: str
              ) -> tuple[MergedPlan, list[GroundedStep]] | None:
    """The new parts after the rest of the plan instead of in the cluster's place: each
    helper first does its own jobs, then its part (spliced in place, a helper's part
    delays all its own jobs; FloorPlan201 goal seed 1, 8 x 32). The parts' steps are
    replayed where their robots then stand (the replay drives within reach). The plan and
    its sequence when shorter than ``plan``, else None."""
    trial = cut.here.copy()
    tail, why = replay_reusing(trial, cut.rest, set(), cut.universe, cut.gone)
    if why is not None:
        return None
    parts, why = replay(trial, [SeqStep(g.robot, g.action, g.subtask, g.group) for g in new], cut.universe)
    if why is not None or not all(condition_holds(c, trial) for c in ctx.goal.conditions):
        return None
    return _kept(ctx, plan, [*cut.before, *tail, *parts], what)


def _spliced(ctx: Context, plan: MergedPlan, cut: _Cut, state: WorldState, new: Sequence[GroundedStep],
             what: str) -> tuple[MergedPlan, list[GroundedStep]] | None:
    """The rest of the plan replayed after the new parts, merged and simulated: the plan
    and its sequence when shorter than ``plan``, else None."""
    trial = state.copy()
    tail, why = replay_reusing(trial, cut.rest, set(), cut.universe, [*cut.gone, *new])
    if why is not None or not all(condition_holds(c, trial) for c in ctx.goal.conditions):
        return None
    return _kept(ctx, plan, [*cut.before, *new, *tail], what)


def _kept(ctx: Context, plan: MergedPlan, sequence: list[GroundedStep], what: str
          ) -> tuple[MergedPlan, list[GroundedStep]] | None:
    """``sequence`` merged and simulated (its waiting drives driven ahead): the plan and
    its sequence when shorter than ``plan``, else None."""
    found = simulated(ctx, sequence, what)
    if found is not None and ctx.config.drive_ahead:  # the helpers' drives to the container, ahead
        found = drive_ahead.ahead(ctx, found.plan, found.sequence) or found
    return shorter(found, plan, what)


def split_clusters(ctx: Context, draft: Draft) -> Draft:
    """Two parts: the first planned for a helper from where the cluster started, the
    second for the robot from where the first leaves it (both orders of each partition,
    at most ``SPLIT_CALLS`` calls); the shortest plan is kept."""
    cut = _cut(ctx, draft)
    if cut is None:
        return draft
    target, plan = cut.target, draft.plan
    orders = [o for a, b in cluster_split.partitions(target, cut.subjects) for o in ((a, b), (b, a))]
    orders = orders[:SPLIT_CALLS // 2]
    built = [(o, _split_problem(cut.here, _conds(ctx, o[0]), target.helper, cut.kept)) for o in orders]
    firsts = [(o, p) for o, p in built if p is not None]
    staged: list[tuple[list[GroundedStep], WorldState, Sequence[str], Problem]] = []
    results = ctx.solver.solve_all([p for _, p in firsts])
    for ((a, b), problem), result in zip(firsts, results, strict=True):
        if not isinstance(result, SolveResult) or not result.solved:
            continue
        after = cut.here.copy()
        grounded, why = replay(after, _steps_of(ctx, problem, result, a, cut.here), cut.universe)
        if why is not None or not all(condition_holds(c, after) for c in _conds(ctx, a)):
            continue
        second_problem = _split_problem(after, _conds(ctx, b), target.robot, [*cut.kept, *_conds(ctx, a)])
        if second_problem is not None:
            staged.append((grounded, after, b, second_problem))
    seconds = ctx.solver.solve_all([p for *_, p in staged]) if staged else []
    best: tuple[MergedPlan, list[GroundedStep]] | None = None
    for (grounded, after, part, problem), result in zip(staged, seconds, strict=True):
        if not isinstance(result, SolveResult) or not result.solved:
            continue
        trial = after.copy()
        second, why = replay(trial, _steps_of(ctx, problem, result, part, after), cut.universe)
        if why is not None:
            continue
        found = _spliced(ctx, best[0] if best else plan, cut, trial, [*grounded, *second],
                         f"split, second part {part}")
        if found is not None:
            best = found
    if best is None:
        return draft
    draft.record.sequence = best[1]
    ctx.notes.append(f"{', '.join(target.members)}: split between {target.helper} and {target.robot}: "
                     f"makespan {plan.makespan:.1f} -> {best[0].makespan:.1f} s")
    return Draft(best[0], draft.record)


def _split_problem(state: WorldState, conditions: Sequence[Condition], robot: str,
                   kept: Sequence[Condition]) -> Problem | None:
    """One part of a split cluster for one robot, keeping the goals already reached that
    its problem's objects take part in (None: the goal compiler finds it out of that
    robot's reach, and the split is not tried that way)."""
    try:
        problem = build_problem(state, conditions, [robot], name="split")
        objects = set(problem.objects)
        overlap = [c for c in kept if _objects_of(c, state) & objects]
        if not overlap:
            return problem
        return build_problem(state, conditions, [robot], name="split", protect=overlap)
    except PlanningError:
        return None


def _objects_of(c: Condition, state: WorldState) -> set[str]:
    result = check_condition(c, state)
    objs = set(result.witnesses)
    for w in result.witnesses:
        if w in state.objects:
            objs.update(state.ancestors(w))
    return objs


def _kind(ref: ObjectRef, state: WorldState) -> str:
    """What an object reference is about, as a type (``Egg_1`` and ``Egg`` alike)."""
    if ref.id is not None:
        o = state.objects.get(ref.id)
        return o.type if o is not None else ref.id
    return "|".join(sorted(ref.types))


