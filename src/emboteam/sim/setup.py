"""Initial-state changes a task may ask for before it starts (a dirty mug, an open box,
a potato moved into the fridge), applied to a fresh state from the scene."""

from __future__ import annotations

from collections.abc import Sequence

from pydantic import BaseModel, ConfigDict, Field

from emboteam.errors import UnknownObjectError
from emboteam.sim.physics import settle
from emboteam.world.scene import Liquid, Temperature
from emboteam.world.state import WorldState


class StateChange(BaseModel):
    """Set some of one object's state; ``None`` fields stay as the scene has them."""

    model_config = ConfigDict(frozen=True)

    object: str = Field(description="object id, e.g. Mug_1")
    is_open: bool | None = None
    is_on: bool | None = None
    is_dirty: bool | None = None
    liquid: Liquid | None = None
    temperature: Temperature | None = None
    parent: str | None = Field(None, description="move it in/on this receptacle")

    def __str__(self) -> str:
        fields = self.model_dump(exclude_none=True, exclude={"object"})
        return f"{self.object}: " + ", ".join(f"{k}={v}" for k, v in fields.items())


def apply_changes(state: WorldState, changes: Sequence[StateChange]) -> None:
    """Apply changes in order, then the standing side effects (a mug put in a running
    coffee machine fills)."""
    for ch in changes:
        if ch.object not in state.objects:
            raise UnknownObjectError(f"initial-state change names unknown object {ch.object!r}")
        o = state.objects[ch.object]
        if ch.parent is not None:
            if ch.parent not in state.objects:
                raise UnknownObjectError(f"initial-state change names unknown receptacle {ch.parent!r}")
            state.move_object(o.id, ch.parent)
        for name in ("is_open", "is_on", "is_dirty", "liquid", "temperature"):
            value = getattr(ch, name)
            if value is not None:
                setattr(o, name, value)
    settle(state)
