"""Side effects that AI2-THOR applies by itself: heating, cooking, cooling, running water,
coffee, and stove knobs that switch their burners.

:func:`settle` is called after every successful action and is idempotent. Effects are
persistent (a potato taken out of a hot microwave stays hot and cooked), which is how
goal checks in SMART-LLM, LaMMA-P and ALFRED read them.
"""

from __future__ import annotations

from emboteam.world.state import ObjectState, WorldState


def switch(state: WorldState, o: ObjectState, *, on: bool) -> None:
    """Toggle an object; a StoveKnob toggles the burners it controls with it."""
    o.is_on = on
    for controlled in o.controls:
        target = state.objects[controlled]
        if target.type == "StoveBurner":
            # a burner burns while any of its knobs is on
            target.is_on = any(k.is_on for k in state.objects.values()
                               if controlled in k.controls and k.type == "StoveKnob")


def _heat(o: ObjectState) -> None:
    o.temperature = "Hot"
    if o.has("cookable"):
        o.is_cooked = True


def settle(state: WorldState) -> None:
    """Apply every standing side effect of running appliances and cold sources."""
    for src in state.objects.values():
        t = src.type
        if t == "Fridge" and src.has("isColdSource"):
            for o in state.descendants(src.id):
                o.temperature = "Cold"
        if not src.is_on:
            continue
        if t in ("Microwave", "StoveBurner"):
            # contents and contents of pans/pots on the burner heat; cookables cook
            for o in state.descendants(src.id):
                _heat(o)
        elif t == "Toaster":
            for o in state.descendants(src.id):
                _heat(o)
        elif t == "CoffeeMachine":
            for o in state.children(src.id):
                if o.has("canFillWithLiquid") and o.liquid is None:
                    o.liquid = "coffee"
                if o.type == "Mug":
                    o.temperature = "Hot"
        elif t == "Faucet":
            for basin in src.controls:
                for o in state.descendants(basin):
                    if o.is_dirty:
                        o.is_dirty = False
                    if o.has("canFillWithLiquid") and o.liquid is None:
                        o.liquid = "water"
