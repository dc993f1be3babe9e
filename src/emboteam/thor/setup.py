"""A task's initial-state changes (a dirty mug, an open box, a potato in the fridge),
made in AI2-THOR with ``forceAction`` steps of agent 0 before the episode starts."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from emboteam.sim.setup import StateChange
from emboteam.thor.errors import ThorSetupError
from emboteam.thor.ids import ThorIds
from emboteam.thor.skills import ThorSkills
from emboteam.world.catalogue import COLD_SOURCES, HEATERS
from emboteam.world.state import WorldState


def _tempered_by_place(state: WorldState, object_id: str, temperature: str, parent: str | None) -> bool:
    """Does where the object is (or is put) give it ``temperature`` in AI2-THOR by itself:
    cold inside a Fridge, hot inside a running Microwave, StoveBurner or Toaster?"""
    chain = ([parent, *state.ancestors(parent)] if parent is not None else state.ancestors(object_id))
    holders = [state.objects[r] for r in chain if r in state.objects]
    if temperature == "Cold":
        return any(r.type in COLD_SOURCES for r in holders)
    return any(r.type in HEATERS and r.is_on for r in holders)


def setup_steps(change: StateChange, ids: ThorIds, state: WorldState) -> list[dict[str, Any]]:
    """The AI2-THOR actions that make ``change`` hold in ``state`` (nothing already true)."""
    if change.object not in state.objects:
        raise ThorSetupError(f"initial-state change names unknown object {change.object!r}")
    o = state.objects[change.object]
    oid = ids.thor(o.id)
    steps: list[dict[str, Any]] = []
    if change.temperature is not None and change.temperature != o.temperature \
            and not _tempered_by_place(state, o.id, change.temperature, change.parent):
        raise ThorSetupError(f"{change}: AI2-THOR has no action that sets an object's temperature")
    if change.parent is not None and change.parent != o.parent:
        steps += [dict(action="PickupObject", objectId=oid, forceAction=True),
                  dict(action="PutObject", objectId=ids.thor(change.parent), forceAction=True,
                       placeStationary=True)]
    if change.is_open is not None and change.is_open != o.is_open:
        steps.append(dict(action="OpenObject" if change.is_open else "CloseObject", objectId=oid, forceAction=True))
    if change.is_on is not None and change.is_on != o.is_on:
        steps.append(dict(action="ToggleObjectOn" if change.is_on else "ToggleObjectOff", objectId=oid,
                          forceAction=True))
    if change.is_dirty is not None and change.is_dirty != o.is_dirty:
        steps.append(dict(action="DirtyObject" if change.is_dirty else "CleanObject", objectId=oid,
                          forceAction=True))
    if change.liquid is not None and change.liquid != o.liquid:
        steps.append(dict(action="FillObjectWithLiquid", objectId=oid, fillLiquid=change.liquid, forceAction=True))
    return steps


def apply_setup(skills: ThorSkills, changes: Sequence[StateChange], observe: Callable[[], WorldState]) -> None:
    """Apply the changes in order; ``observe()`` gives the state after the previous ones.
    A step AI2-THOR refuses ends the episode before it starts, with AI2-THOR's reason."""
    for change in changes:
        for step in setup_steps(change, skills.ids, observe()):
            action = str(step.pop("action"))
            result, _ = skills.step(0, action, **step)
            if not result.success:
                raise ThorSetupError(f"initial state {change}: AI2-THOR {action} failed: {result.message}")
