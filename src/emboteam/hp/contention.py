"""Which planned unit goes first where units contend for a shared spot.

Units planned in one round are accepted one by one, and the merge orders two robots'
conflicting steps (the same microwave door, the same knife) the way they were accepted.
Accepting in the order the round's units were made lets whoever came first in the list
take the knife while the units that need the microwave, the round's bottleneck, wait for
it, then queue at the microwave one after another: the makespan becomes knife chain +
microwave chain. Accepting first the units that use the most contended spot (the spot
with the most manipulation seconds over the round's plans) starts the bottleneck's queue
at once and lets the other work run alongside it: the list-scheduling rule of serving the
bottleneck resource first.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TypeVar

from emboteam.sim.durations import ACTION_SECONDS
from emboteam.world.actions import Action, Skill
from emboteam.world.state import WorldState

T = TypeVar("T")


def _spot(state: WorldState, action: Action) -> str | None:
    where = action.receptacle or action.target
    if where not in state.objects:  # a piece not cut yet: it is where its whole is
        where = where.split("_Slice_")[0]
    return state.spot_of(where) if where in state.objects else None


def spot_seconds(state: WorldState, actions: Sequence[tuple[str, Action]]) -> dict[str, float]:
    """Manipulation seconds a plan spends at each interaction spot (as seen from ``state``)."""
    out: dict[str, float] = {}
    for _, a in actions:
        if a.skill is Skill.GoToObject:
            continue
        spot = _spot(state, a)
        if spot is not None:
            out[spot] = out.get(spot, 0.0) + ACTION_SECONDS.get(a.skill, 1.0)
    return out


def bottleneck_first(items: Sequence[T], uses: Sequence[dict[str, float] | None]) -> list[T]:
    """``items`` reordered: those using the most contended spot (most seconds over all
    ``uses``, shared by at least two items) first, heavier users of it before lighter;
    items without a plan (``None``) and the rest keep their order."""
    demand: dict[str, float] = {}
    users: dict[str, int] = {}
    for use in uses:
        for spot, sec in (use or {}).items():
            demand[spot] = demand.get(spot, 0.0) + sec
            users[spot] = users.get(spot, 0) + 1

    def key(k: int) -> tuple[float, float, int]:
        use = uses[k] or {}
        shared = [s for s in use if users[s] > 1]
        if not shared:
            return (0.0, 0.0, k)
        top = max(shared, key=lambda s: (demand[s], s))
        return (-demand[top], -use[top], k)

    return [items[k] for k in sorted(range(len(items)), key=key)]
