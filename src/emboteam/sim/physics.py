"""Side effects that AI2-THOR applies by itself: heating, cooking, cooling, running water,
coffee, and stove knobs that switch their burners.

:func:`settle` is called after every successful action and is idempotent. Effects are
persistent (a potato taken out of a hot microwave stays hot and cooked), which is how
goal checks in SMART-LLM, LaMMA-P and ALFRED read them; AI2-THOR itself lets temperature
drift back to RoomTemp after about ten seconds (docs/world.md).
"""

from __future__ import annotations

from collections import defaultdict

from emboteam.world.catalogue import BREWERS, BURNERS, COLD_SOURCES, HEATERS, WATER_SOURCES
from emboteam.world.state import ObjectState, WorldState

__all__ = ["is_cold_source", "settle", "switch"]


def is_cold_source(o: ObjectState) -> bool:
    """A fridge that cools (the catalogue's cold source types, flagged ``isColdSource``)."""
    return o.type in COLD_SOURCES and o.has("isColdSource")


def switch(state: WorldState, o: ObjectState, *, on: bool) -> None:
    """Toggle an object; a StoveKnob toggles the burners it controls with it."""
    o.is_on = on
    for controlled in o.controls:
        target = state.objects[controlled]
        if target.type in BURNERS:
            # a burner burns while any of its knobs is on
            target.is_on = any(k.is_on for k in state.objects.values()
                               if controlled in k.controls and k.type == "StoveKnob")


def _heat(o: ObjectState) -> None:
    o.temperature = "Hot"
    if o.has("cookable"):
        o.is_cooked = True


#: the types :func:`settle` looks at: only they have standing effects
_SOURCES: frozenset[str] = COLD_SOURCES | HEATERS | BREWERS | WATER_SOURCES


def settle(state: WorldState) -> None:
    """Apply every standing side effect of running appliances and cold sources.

    One pass builds a parent -> children index and picks out the few objects that can have
    an effect (fridges, heaters, coffee machines, faucets), so the cost is linear in the
    number of objects however many appliances run (it runs after every action, thousands
    of times per plan), and the rest of the work is per source.

    Measured (issue 28, 32 robots x 96 conditions in FloorPlan1, 5,873 calls per plan):
    about 9.5 us a call, 7 us of it this pass, some 7% of the planner's own CPU (cProfile
    shows about three times that). Exact alternatives were slower or level: C-level
    ``map``/``compress`` passes (about twice as slow here) and children looked up per
    source (an active fridge, burners and a faucet ask for several). Not cached:
    ``ObjectState.parent`` and ``type`` are public fields that change without notice.
    """
    children: dict[str, list[ObjectState]] = defaultdict(list)
    sources: list[ObjectState] = []
    for o in state.objects.values():
        if o.parent is not None:
            children[o.parent].append(o)
        if o.type in _SOURCES:
            sources.append(o)
    if not children:
        return

    def within(root: str) -> list[ObjectState]:
        out: list[ObjectState] = []
        frontier = [root]
        while frontier:
            for child in children.get(frontier.pop(), ()):
                out.append(child)
                frontier.append(child.id)
        return out

    for src in sources:  # in the objects' order, as before: the last effect on an object wins
        t = src.type
        if is_cold_source(src):
            for o in within(src.id):
                o.temperature = "Cold"
        if not src.is_on:
            continue
        if t in HEATERS:  # a pan on a burner, a potato in a bowl in the microwave
            for o in within(src.id):
                _heat(o)
        elif t in BREWERS:
            # AI2-THOR: an empty Mug in a running coffee machine fills with coffee and
            # turns Hot (only Mugs fit, see the catalogue's receptacle whitelist)
            for o in children.get(src.id, ()):
                if o.has("canFillWithLiquid") and o.liquid is None:
                    o.liquid = "coffee"
                if o.type == "Mug":
                    o.temperature = "Hot"
        elif t in WATER_SOURCES:
            for basin in src.controls:
                for o in within(basin):
                    if o.is_dirty:
                        o.is_dirty = False
                    if o.has("canFillWithLiquid") and o.liquid is None:
                        o.liquid = "water"
