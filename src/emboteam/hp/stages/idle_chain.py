"""Two jobs moved at once for the idle-robot stage (:mod:`emboteam.hp.stages.idle`): an
*ejection chain*. A job of the robot that ends last goes to any robot able to do it, and
a job of that robot (or a second job of the last one) goes on to a robot that ends early.

Why (issue 28): on the sweep cells still more than 10 % above CP-SAT's optimum, no single
move shortens the walked routes, but CP-SAT's schedules move several jobs at once.
FloorPlan1 8 x 16 seed 1: the last robot (9.75 s) opens a cabinet first; that job alone on
any early robot ends after 9.75 (it waits on that robot's own chain), but given to a robot
that ends at 7.75 while that robot's next-but-last job goes to the robot that did nothing,
the walked routes end at 9.0. A single move cannot see that the middle robot only passes
work along.

Bounded in counts: the pairs are priced until :data:`CHAIN_WALKS` times the plan's steps
stops have been walked; a first move that leaves a third robot at the makespan (or both
robots it changes) is not followed up, since one more move cannot bring both down.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

from emboteam.hp.routes import Node, Routes

#: the chain search's budget: stops walked at most, this many times the plan's steps
CHAIN_WALKS = 1000

Change = dict[str, list[str]]
Key = tuple[float, ...]
#: the robots' ends -> a tuple that sorts shorter routes first (:func:`emboteam.hp.stages.idle.unload_key`)
KeyOf = Callable[[Mapping[str, float]], Key]


def relocations(order: Mapping[str, Sequence[str]], nodes: Mapping[str, Node], giver: str,
                receivers: Sequence[str]) -> list[tuple[str, str, Change]]:
    """Every move of one job of ``giver`` to any place in the route of a receiver (not
    the giver) able to do it: (the job, the receiver, the change)."""
    out: list[tuple[str, str, Change]] = []
    for nid in order[giver]:
        rest = [x for x in order[giver] if x != nid]
        for r in receivers:
            if r == giver or r not in nodes[nid].robots:
                continue
            base = list(order[r])
            out.extend((nid, r, {giver: rest, r: [*base[:i], nid, *base[i:]]}) for i in range(len(base) + 1))
    return out


def chained(routes: Routes, receivers: Sequence[str], budget: int, key: KeyOf) -> Change | None:
    """The best pair of moves (a job of the last robot to any able robot, then a job of
    that robot or of the last one to one of ``receivers``) whose walked routes compare
    shorter under ``key`` (the robots' ends -> a sortable tuple, longest first); None when
    no pair priced before ``budget`` stops were walked does."""
    now: Key = key(routes.ends)
    last = max(sorted(routes.order), key=lambda r: routes.ends[r])
    best: tuple[Key, int, Change] | None = None
    k = 0
    for _, middle, first in relocations(routes.order, routes.nodes, last, sorted(routes.order)):
        if routes.walked >= budget:
            break
        givers = _followed(routes, first, last, middle, now[0])
        after = {**routes.order, **first}
        for giver in givers:
            for _, _, second in relocations(after, routes.nodes, giver, receivers):
                change = {**first, **second}
                if routes.walked >= budget or not all(routes.keeps_order(v) for v in change.values()):
                    continue
                ends = routes.ends_with(change)
                k += 1
                if ends is not None and key(ends) < now and (best is None or key(ends) < best[0]):
                    best = (key(ends), k, change)
    return None if best is None else best[2]


def _followed(routes: Routes, first: Change, last: str, middle: str, makespan: float) -> list[str]:
    """Whose job the second move takes after ``first`` (a job of ``last`` to ``middle``):
    the one of the two still at the makespan; either when neither is; none when both
    are, or a third robot is (one more move cannot bring them all down)."""
    if not all(routes.keeps_order(v) for v in first.values()):
        return []
    ends = routes.ends_with(first)
    if ends is None:
        return []
    high = {r for r, e in ends.items() if e >= makespan - 1e-6}
    if not high <= {last, middle} or len(high) == 2:
        return []
    return sorted(high) if high else [middle, last]
