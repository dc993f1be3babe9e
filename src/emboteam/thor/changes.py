"""The initial-state changes that turn one symbolic state into another: what a live
AI2-THOR scene must be made to match before an episode (a task's dirty mug, open box,
potato in the fridge), read off the planning state rather than re-derived from the task."""

from __future__ import annotations

from emboteam.sim.setup import StateChange
from emboteam.world.state import WorldState


def changes_between(before: WorldState, after: WorldState) -> list[StateChange]:
    """One change per object whose placement or state differs (moves first, so an object
    moved into a receptacle is opened or filled where it ends up)."""
    moves: list[StateChange] = []
    states: list[StateChange] = []
    for oid, a in sorted(after.objects.items()):
        b = before.objects.get(oid)
        if b is None:
            continue
        if a.parent != b.parent and a.parent is not None:
            moves.append(StateChange(object=oid, parent=a.parent))
        fields = {name: getattr(a, name) for name in ("is_open", "is_on", "is_dirty", "temperature")
                  if getattr(a, name) != getattr(b, name)}
        if a.liquid != b.liquid and a.liquid is not None:
            fields["liquid"] = a.liquid
        if fields:
            states.append(StateChange.model_validate({"object": oid, **fields}))
    return moves + states
