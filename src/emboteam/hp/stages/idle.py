"""The idle-robot stage (``PlannerConfig.idle``): jobs of the robot that ends last (or,
when none of theirs helps, of the others) moved to capable robots that end early or never
moved, each route walked from the robot's start (:mod:`emboteam.hp.routes`), then the plan rebuilt with its drives planned again
(:func:`emboteam.hp.stages.route.rebuild`), merged, simulated and kept only when its
simulated makespan is shorter (:mod:`emboteam.hp.stages.rebuilt`).

Why (issue 28): in every sweep cell where ``fast`` was more than 10 % above CP-SAT's
proven optimum, one capable robot ended far before the makespan, in five of them with no
work at all (FloorPlan201 4x8 seed 1: robots end at 0, 14.75, 17.5 and 18.5 s; the
optimum, 16.0 s, gives the idle robot two jobs). The route stage moves a job only to the
robots whose routes pass nearest to it, and a robot that never left its start passes near
nothing. Here the receivers are chosen by *when* they end, not where they pass.

When no single move shortens the walked routes, two at once (:mod:`emboteam.hp.stages.
idle_chain`: an ejection chain through a robot that only passes work along; FloorPlan1
8 x 16 seeds 0 and 1).

Bounded in counts, never seconds: it runs only when some robot ends before
:data:`EARLY_SHARE` of the makespan, on plans of at most
:data:`emboteam.hp.stages.route.ROUTE_STEPS` steps, moves at most :data:`MOVES` jobs
and walks at most :data:`WALKS` times the plan's steps."""

from __future__ import annotations

import logging
from collections.abc import Mapping

from emboteam.hp.plan import MergedPlan
from emboteam.hp.routes import Node, Routes, timetable
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.idle_chain import CHAIN_WALKS, chained
from emboteam.hp.stages.rebuilt import Rebuilt, adopted, shorter
from emboteam.hp.stages.route import MIN_GAIN, ROUTE_STEPS, draft_layout, rebuild, sequence_of
from emboteam.world.actions import Skill

log = logging.getLogger(__name__)

#: a robot that ends (simulated, or walked during the search) before this share of the
#: makespan receives jobs; none such, and the stage costs one pass over the plan's steps
EARLY_SHARE = 0.75
#: jobs moved at most, one at a time
MOVES = 6
#: rebuilds (replay, merge, simulation) tried at most per search
TRIES = 3
#: the search's budget: stops walked at most, this many times the plan's steps
WALKS = 200


Change = dict[str, list[str]]


def give_idle(ctx: Context, draft: Draft) -> Draft:
    """The draft with jobs of its last robot given to robots that end early, when the
    rebuilt plan simulates shorter; else the draft itself. Searched first with the jobs
    that carry a thing another job acts on kept in the plan's order (:func:`carried`: the
    merge's waits do not see a robot's hands, and a rebuild put a book in a box another
    robot was carrying, FloorPlan201 4x8 seed 1), then, when no rebuild of that search
    simulates shorter, with the merge's waits alone."""
    plan = draft.plan
    if len(plan.steps) > ROUTE_STEPS or not early_robots(draft, EARLY_SHARE):
        return draft
    layout = draft_layout(ctx, draft)
    if layout is None:
        return draft
    for waits in (_joined(layout.waits, carried(plan, layout.nodes)), layout.waits):
        if timetable(layout.walker, layout.nodes, layout.order, waits) is None:
            break
        routes = Routes(layout.walker, layout.nodes, waits, {r: list(v) for r, v in layout.order.items()})
        found, moved = _searched(ctx, draft, routes)
        if found is not None:
            return adopted(ctx, draft, found, f"{moved} job(s) given to robots that ended early: "
                                              f"makespan {plan.makespan:.1f} -> {found.plan.makespan:.1f} s")
    return draft


def _searched(ctx: Context, draft: Draft, routes: Routes) -> tuple[Rebuilt | None, int]:
    """The walk moves one job at a time (:func:`ranked`'s best, else the best ejection
    chain of two, :func:`emboteam.hp.stages.idle_chain.chained`) while that shortens the
    routes, up to :data:`MOVES`; then the plan is rebuilt with all those moves and, when
    it does not simulate shorter, with one move fewer, for at most :data:`TRIES`
    rebuilds. The rebuilt plan that simulates shorter (or None) and the jobs it moved."""
    plan = draft.plan
    before = routes.cost()[0]
    undo: list[Change] = []
    while len(undo) < MOVES:
        change = next(iter(ranked(routes, WALKS * len(plan.steps))), None)
        if change is None:
            change = chained(routes, _receivers(routes), routes.walked + CHAIN_WALKS * len(plan.steps), unload_key)
        if change is None:
            break
        undo.append({r: routes.order[r] for r in change})
        routes.apply(change)
    tries, found = 0, None
    if routes.cost()[0] <= before - MIN_GAIN:
        while undo and tries < TRIES and found is None:  # all the moves, then fewer
            tries += 1
            found = shorter(rebuild(ctx, sequence_of(routes, plan, draft.record.sequence)), plan,
                            "plan with work for idle robots")
            if found is None:
                routes.apply(undo.pop())
    log.debug("idle: %d moved in %d rebuilds, %d stops walked", len(undo), tries, routes.walked)
    return found, len(undo)


def carried(plan: MergedPlan, nodes: Mapping[str, Node]) -> dict[str, set[str]]:
    """Waits that keep, in the plan's order, two jobs of which one picks up a thing the
    other acts on (a box carried to a table, a book put in it): the merge's waits leave a
    robot's hands out, and the walk would let such jobs overlap. Step -> the steps it
    waits for: the later job's first stop at the thing waits for the earlier job's last
    stop (its hands empty again)."""
    step = {s.id: s for s in plan.steps}
    index = {s.id: i for i, s in enumerate(plan.steps)}
    ordered = sorted((n for n in nodes.values() if n.stops), key=lambda n: index[n.stops[0].step])
    picks: dict[str, set[str]] = {}
    at: dict[str, dict[str, str]] = {}  # job -> thing -> its first stop acting on it
    for n in ordered:
        picks[n.id] = set()
        at[n.id] = {}
        for st in n.stops:
            act = step[st.step].action
            if act.skill is Skill.PickupObject:
                picks[n.id].add(act.target)
            for x in (act.target, act.receptacle):
                if x:
                    at[n.id].setdefault(x, st.step)
    out: dict[str, set[str]] = {}
    for i, a in enumerate(ordered):
        for b in ordered[i + 1:]:
            for x in sorted((picks[a.id] & at[b.id].keys()) | (picks[b.id] & at[a.id].keys())):
                out.setdefault(at[b.id][x], set()).add(a.stops[-1].step)
    return out


def _joined(waits: Mapping[str, frozenset[str]], more: Mapping[str, set[str]]) -> dict[str, frozenset[str]]:
    return {s: frozenset(waits.get(s, frozenset()) | more.get(s, set())) for s in {*waits, *more}}


def early_robots(draft: Draft, share: float) -> list[str]:
    """The plan's robots whose last step ends (simulated) before ``share`` of its
    makespan, those without a step included."""
    ends = dict.fromkeys(draft.plan.robots, 0.0)
    for s in draft.plan.steps:
        ends[s.robot] = max(ends.get(s.robot, 0.0), s.est_end)
    return [r for r in draft.plan.robots if ends[r] < share * draft.plan.makespan]


def ranked(routes: Routes, budget: int) -> list[Change]:
    """The moves of one job to a robot able to do it whose walked route ends before
    :data:`EARLY_SHARE` of the longest (at the job's best place in its route) that
    shorten the walked routes, best first (ties in a fixed order). The jobs of the robot
    that ends last are tried first; when none of their moves helps, those of the other
    robots, latest first (the last robot may be waiting for another's job: a box it puts
    things in, FloorPlan201 4x8 seed 1). The search stops once ``budget`` stops have been
    walked. Routes compare by their ends, longest first (:func:`unload_key`): when several
    robots end at the makespan, a move that shortens one of them is progress, though it
    lengthens the routes' sum."""
    now = unload_key(routes.ends)
    receivers = _receivers(routes)
    givers = sorted((r for r in routes.order if r not in receivers), key=lambda r: (-routes.ends[r], r))
    for giver in givers:
        found = _improving(routes, giver, receivers, now, budget)
        if found or routes.walked >= budget:
            return found
    return []


def _receivers(routes: Routes) -> list[str]:
    """The robots whose walked routes end before :data:`EARLY_SHARE` of the longest."""
    longest = max(routes.ends.values(), default=0.0)
    return [r for r in sorted(routes.order) if routes.ends[r] < EARLY_SHARE * longest]


def _improving(routes: Routes, giver: str, receivers: list[str], now: tuple[float, ...], budget: int
               ) -> list[Change]:
    """The moves of one job of ``giver`` to a receiver that shorten the walked routes, each
    job and receiver at its best place, best first."""
    best: dict[tuple[str, str], tuple[tuple[float, ...], int, Change]] = {}
    for k, (nid, robot, change) in enumerate(_moves(routes, giver, receivers)):
        if routes.walked >= budget:
            break
        if not all(routes.keeps_order(route) for route in change.values()):
            continue
        ends = routes.ends_with(change)
        if ends is None or not unload_key(ends) < now:
            continue
        if (nid, robot) not in best or unload_key(ends) < best[nid, robot][0]:
            best[nid, robot] = (unload_key(ends), k, change)
    return [c for _, _, c in sorted(best.values(), key=lambda x: (x[0], x[1]))]


def unload_key(ends: Mapping[str, float]) -> tuple[float, ...]:
    """The robots' ends, longest first (rounded to the simulator's quarter seconds' scale,
    so that sums of floats compare as equal)."""
    return tuple(sorted((round(e, 6) for e in ends.values()), reverse=True))


def _moves(routes: Routes, late: str, receivers: list[str]) -> list[tuple[str, str, Change]]:
    """Every move of one job of robot ``late`` to any place in the route of a receiver
    able to do it: (the job, the receiver, the change)."""
    out: list[tuple[str, str, Change]] = []
    for nid in routes.order[late]:
        rest = [x for x in routes.order[late] if x != nid]
        for r in receivers:
            if r not in routes.nodes[nid].robots:
                continue
            base = routes.order[r]
            out.extend((nid, r, {late: rest, r: [*base[:i], nid, *base[i:]]}) for i in range(len(base) + 1))
    return out
