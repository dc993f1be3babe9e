"""The route stage (``PlannerConfig.route``): the plan's jobs put in a shorter order and
spread over the robots able to do them (:mod:`emboteam.hp.routes`: routes walked as the
simulator drives), then the plan rebuilt with its drives *planned again*: the drives that
went to the next thing acted on are dropped, and the replay drives to each thing only
when it is out of reach from where the robot stands then (:func:`emboteam.hp.rounds.
preparations`), so a moved job gets the drives its new place needs, not the old ones.
Merged and simulated; kept only when the simulated makespan is shorter.

Why (issue 28): on the 2-robot sweep cells the plan was 20-50 % above CP-SAT's optimum
for its own actions, nearly all of it driving (lama-first orders a unit's goals without
regard to the way between them), and CP-SAT's better orders simulated longer once its
schedule was rebuilt from the old steps (docs/planning.md). Only for specs whose
subtasks are final and independent, as the other reordering stages.

A plan of more than :data:`ROUTE_STEPS` steps (the 8- and 32-robot, 96-goal cells) gets a
cheaper variant: only the jobs of the robots that end last move
(:mod:`emboteam.hp.critical_routes`), over waits that no longer chain the jobs of one
cluster in the plan's order (the conflicting pairs keep what the state needs), for a
budget of :data:`LARGE_WALKS` walks of the plan, one round and one rebuild."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import cast

from emboteam.hp import optimal, spot_order
from emboteam.hp.critical_routes import improve_late
from emboteam.hp.dependencies import Footprint
from emboteam.hp.merge import GroundedStep, SeqStep
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.hp.routes import Node, Routes, Stop, Walker, improve, timetable
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.rebuilt import Rebuilt, adopted, replayed, shorter
from emboteam.sim.rules import apply_action
from emboteam.world.actions import Skill
from emboteam.world.state import WorldState

#: the walked routes must promise at least this many seconds less than the plan's own
#: (each rebuild costs a replay and a simulation; a smaller promise rarely survives them)
MIN_GAIN = 0.5
#: the stage searches only when the walked timetable's makespan is at least this share of
#: the plan's: below it the makespan is made by what the walk does not see (robots in
#: each other's way, orders the merge adds), and the search would cost without paying
ROUTE_BOUND = 0.8
#: a plan of more steps gets the cheaper search instead (:func:`emboteam.hp.critical_routes.
#: improve_late`: only the jobs of the robots that end last move, one round, one rebuild):
#: the full search and its rebuilds cost the 32-robot, 96-goal cell (223 steps) 2.6-3.3 s
#: on this 2-core machine, more than its whole planning time
ROUTE_STEPS = 160
#: the cheaper search's budget: this many walks of the whole plan (stops walked = this x
#: the plan's steps; a count scaled to the plan, never seconds)
LARGE_WALKS = 50
#: nor does it search a large plan whose walk is this much longer than its simulated
#: makespan: the walk misprices it (robots the merge lets overlap), and its routes would
#: not survive the rebuild (FloorPlan1 32x96, seed 4: walked 36.0 s, simulated 31.0)
LARGE_MISPRICED = 1.05
#: rounds of the stage (a count, not a clock)
ROUNDS = 2
#: the spot order runs again after the large-plan search only for a team of at most this
#: many robots: on the 32-robot, 96-goal cells it gained nothing that the drive-ahead
#: stage after it did not find too (FloorPlan1, goal seeds 0-4: the same makespans),
#: for about 0.09 s of CPU (a tenth of that cell's planning, issue 28's 1 s target);
#: on the 8-robot cells it pays (seed 4: 60.0 -> 55.25 s with it)
REORDER_TEAM = 8


@dataclass(frozen=True)
class Layout:
    """What a plan's routes are made of: the nodes (its jobs), each robot's jobs in the
    plan's order, the steps each step waits for in the merged plan (what it needs another
    job to do first; the jobs of one subtask on one robot in their order), and the same
    with every conflicting pair of steps kept in order (``strict``); the walker of the
    scene."""

    nodes: dict[str, Node]
    order: dict[str, list[str]]
    waits: dict[str, frozenset[str]]
    strict: dict[str, frozenset[str]]
    walker: Walker
    #: the conflicting pairs and the waits between robots, without the chain that keeps
    #: the jobs of one cluster on one robot in the plan's order (the large-plan search's)
    free: dict[str, frozenset[str]] = field(default_factory=dict)


def reroute(ctx: Context, draft: Draft) -> Draft:
    """The draft with its jobs on shorter routes, or the draft itself: up to
    :data:`ROUNDS` rounds, each from the plan the last one made (its robots stand on
    other poses, so its jobs are other stops)."""
    if len(draft.plan.steps) > ROUTE_STEPS:
        return _once_large(ctx, draft)
    for _ in range(ROUNDS):
        better = _once(ctx, draft)
        if better is draft:
            break
        draft = better
    return draft


def reorder_after(ctx: Context, draft: Draft) -> bool:
    """Is the spot order worth running again once the stage has rerouted ``draft`` (the
    draft it was given): after the search of a small plan, or after the large-plan
    search of a team of at most :data:`REORDER_TEAM` robots."""
    return len(draft.plan.steps) <= ROUTE_STEPS or len(ctx.team) <= REORDER_TEAM


def _once(ctx: Context, draft: Draft) -> Draft:
    """One round: the draft with its jobs on shorter routes, or the draft itself. The routes are
    searched with the waits of the merged plan first; when that plan no longer runs or
    misses the goal (two jobs switching one microwave swapped), once more with every
    conflicting pair of jobs kept in its order (:func:`conflicts`)."""
    plan, seq = draft.plan, draft.record.sequence
    layout = draft_layout(ctx, draft) if len(plan.steps) <= ROUTE_STEPS else None
    if layout is None:
        return draft
    other = None
    for waits in (layout.waits, layout.strict):
        if timetable(layout.walker, layout.nodes, layout.order, waits) is None:
            break  # jobs interleaved in the plan wait on each other both ways: not modelled
        routes = Routes(layout.walker, layout.nodes, waits, {r: list(v) for r, v in layout.order.items()})
        before = routes.cost()
        if before[0] < ROUTE_BOUND * plan.makespan:
            return draft  # the makespan is waiting (at spots, for other robots), not driving
        improve(routes)
        if routes.cost()[0] > before[0] - MIN_GAIN:
            return draft
        other = rebuild(ctx, sequence_of(routes, plan, seq))
        if other is not None:
            break
    return _kept(ctx, draft, other, f"{before[0]:.1f} -> {routes.cost()[0]:.1f} s")


def draft_layout(ctx: Context, draft: Draft) -> Layout | None:
    """The draft's layout, when the stage applies to it (final, independent subtasks; a
    plan made of its sequence)."""
    plan, seq = draft.plan, draft.record.sequence
    if not ctx.independent or len(seq) != len(plan.steps):
        return None
    hit = ctx.memo.get(("layout", id(plan)))
    if hit is not None and hit[0] is plan and hit[1] is seq:
        return cast(Layout | None, hit[2])  # read only: the searches copy what they change
    layout = layout_of(ctx, plan, seq)
    ctx.memo[("layout", id(plan))] = (plan, seq, layout)
    return layout


def _once_large(ctx: Context, draft: Draft) -> Draft:
    """The stage on a plan of more than :data:`ROUTE_STEPS` steps: one round of the
    cheaper search (:func:`improve_late`, :data:`LARGE_WALKS` walks of the plan) over the
    waits without the chains of each cluster's jobs (``layout.free``: what a long cluster
    one robot does can then spread over the idle ones), one rebuild."""
    plan = draft.plan
    layout = draft_layout(ctx, draft)
    if layout is None or timetable(layout.walker, layout.nodes, layout.order, layout.free) is None:
        return draft
    routes = Routes(layout.walker, layout.nodes, layout.free, {r: list(v) for r, v in layout.order.items()})
    before = routes.cost()
    if not ROUTE_BOUND * plan.makespan <= before[0] <= LARGE_MISPRICED * plan.makespan:
        return draft  # the walk does not price this plan's makespan: its routes would not pay
    improve_late(routes, LARGE_WALKS * len(plan.steps))
    if routes.cost()[0] > before[0] - MIN_GAIN:
        return draft
    other = rebuild(ctx, sequence_of(routes, plan, draft.record.sequence))
    return _kept(ctx, draft, other, f"{before[0]:.1f} -> {routes.cost()[0]:.1f} s, the late robots' jobs")


def _kept(ctx: Context, draft: Draft, other: Rebuilt | None, walked: str) -> Draft:
    """The rebuilt plan when it simulates shorter than the draft, else the draft."""
    plan = draft.plan
    found = shorter(other, plan, "rerouted plan")
    if found is None:
        return draft
    return adopted(ctx, draft, found, f"jobs rerouted (walked routes {walked}, drives planned "
                                      f"again): makespan {plan.makespan:.1f} -> {found.plan.makespan:.1f} s")


def _xz(p: Sequence[float]) -> tuple[float, float]:
    return (p[0], p[1])


def _need(step: PlanStep) -> str | None:
    """The thing an operation must be in reach of (None: a drop or a throw, which go where
    the drive before them went)."""
    a = step.action
    if a.skill in (Skill.DropHandObject, Skill.ThrowObject):
        return None
    return a.receptacle if a.skill is Skill.PutObject else a.target


def _point(state: WorldState, thing: str | None) -> tuple[float, float] | None:
    if thing is None or thing not in state.objects:
        return None
    o = state.objects[thing]
    if o.held_by is not None:
        return None
    return (o.position[0], o.position[2])


def _stops(ctx: Context, plan: MergedPlan) -> dict[str, Stop | None] | None:
    """Step id -> its stop (None: a drive the replay plans again), replaying the plan for
    where things are; None when a robot ends holding something (its last job stays)."""
    nxt: dict[int, PlanStep | None] = {}
    last: dict[str, PlanStep | None] = {}
    for i in range(len(plan.steps) - 1, -1, -1):
        s = plan.steps[i]
        nxt[i] = last.get(s.robot)
        if s.action.skill is not Skill.GoToObject:
            last[s.robot] = s
    state = ctx.start.copy()
    out: dict[str, Stop | None] = {}
    for i, s in enumerate(plan.steps):
        if s.action.skill is Skill.GoToObject:
            op = nxt[i]
            planned_again = op is not None and _need(op) == s.action.target
            out[s.id] = None if planned_again else Stop(s.id, _point(state, s.action.target), 0.0, forced=True)
        else:
            out[s.id] = Stop(s.id, _point(state, _need(s)), s.est_end - s.est_start,
                             spot=s.resources[0] if s.resources else None)
        apply_action(state, s.robot, s.action)
    if any(r.holding is not None for r in state.robots.values()):
        return None
    return out


def conflicts(accesses: Sequence[tuple[str, Footprint]]) -> set[tuple[str, str]]:
    """(a, b): step (or node) b must stay after a, from their footprints in the plan's
    order: a write after any earlier access of the variable since its last write, a read
    or a set update after the last write, a read after updates (two updates commute).
    The merge's waits alone let the rebuilt order flip two jobs that both switch the
    microwave, and the last one to switch it decides the goal. A robot's own pose and
    hand are its own business (not shared)."""
    last: dict[str, str] = {}
    seen: dict[str, dict[str, set[str]]] = {}  # var -> node -> {"r", "u"} since the last write
    out: set[tuple[str, str]] = set()
    for node, fp in accesses:
        for kind, names in (("r", fp.reads), ("u", fp.updates), ("w", fp.writes)):
            for v in names:
                if v.startswith(("pose:", "hand:")):
                    continue
                since = seen.setdefault(v, {})
                before = [last[v]] if v in last else []
                before += [n for n, kinds in since.items() if kind == "w" or kinds - {kind}]
                out.update((b, node) for b in before if b != node)
                if kind == "w":
                    last[v], seen[v] = node, {}
                else:
                    since.setdefault(node, set()).add(kind)
    return out


def layout_of(ctx: Context, plan: MergedPlan, seq: Sequence[GroundedStep]) -> Layout | None:
    """The nodes of ``plan`` (:mod:`emboteam.hp.optimal`'s jobs: one robot's steps between
    two moments its hands are empty, each for the robots its subtask's group may go to)
    and what they wait for; None when the plan cannot be taken apart so."""
    problem = optimal.problem_of(plan, ctx.spec, ctx.start)
    stops = _stops(ctx, plan) if problem is not None else None
    if problem is None or stops is None:
        return None
    job_of = {sid: j.id for j in problem.jobs for sid in j.steps}
    if any(s.id not in job_of and s.action.skill is not Skill.GoToObject for s in plan.steps):
        return None
    waits: dict[str, set[str]] = {}
    for a, b in [*problem.precedences, *problem.drive_waits]:
        waits.setdefault(b, set()).add(a)
    strict = {n: set(ps) for n, ps in waits.items()}
    free = {n: set(ps) for n, ps in _unchained(problem).items()}
    for a, b in conflicts([(s.id, g.footprint) for s, g in zip(plan.steps, seq, strict=True)
                           if stops.get(s.id) is not None]):
        strict.setdefault(b, set()).add(a)
        free.setdefault(b, set()).add(a)
    nodes = {j.id: Node(j.id, tuple(st for sid in j.steps if (st := stops[sid]) is not None),
                        problem.candidates[j.group]) for j in problem.jobs}
    order: dict[str, list[str]] = {r: [] for r in plan.robots}
    for j in problem.jobs:  # in the plan's order of their first steps
        order[j.robot].append(j.id)
    walker = Walker(ctx.start.floor_plan, {r: ctx.start.robots[r].profile.speed for r in order},
                    {r: _xz(ctx.start.robots[r].position) for r in order})
    return Layout(nodes, order, {n: frozenset(ps) for n, ps in waits.items()},
                  {n: frozenset(ps) for n, ps in strict.items()}, walker,
                  {n: frozenset(ps) for n, ps in free.items()})


def _unchained(problem: optimal.Problem) -> dict[str, set[str]]:
    """The problem's waits (step -> the steps it waits for) without the chain that orders
    the jobs of one group (one cluster on one robot) as the plan did: those orders come
    from the plan, not from the state, and the conflicting pairs (:func:`conflicts`) keep
    the ones the state needs."""
    chain: set[tuple[str, str]] = set()
    last: dict[str, str] = {}
    for j in problem.jobs:
        if j.group in last:
            chain.add((last[j.group], j.ops[0].step))
        last[j.group] = j.ops[-1].step
    out: dict[str, set[str]] = {}
    for a, b in [*problem.precedences, *problem.drive_waits]:
        if (a, b) not in chain:
            out.setdefault(b, set()).add(a)
    return out


def sequence_of(routes: Routes, plan: MergedPlan, seq: Sequence[GroundedStep]) -> list[SeqStep] | None:
    """The kept steps of the new routes in the order of their starts (each on the robot of
    its route), or None when the routes cannot be timed."""
    found = routes.timetable()
    if found is None:
        return None
    times = found[0]
    robot_of = {s.step: r for r, route in routes.order.items() for nid in route for s in routes.nodes[nid].stops}
    index = {s.id: i for i, s in enumerate(plan.steps)}
    kept = sorted(times, key=lambda sid: (times[sid], robot_of[sid], index[sid]))
    return [SeqStep(robot_of[sid], seq[index[sid]].action, seq[index[sid]].subtask, seq[index[sid]].group)
            for sid in kept]


def rebuild(ctx: Context, steps: list[SeqStep] | None) -> Rebuilt | None:
    """The plan of ``steps`` with its drives planned again by the replay, merged and
    simulated; None when it no longer runs, misses the goal or fails in the simulator."""
    return None if steps is None else replayed(ctx, steps, "rerouted plan", spot_order.reopen)
