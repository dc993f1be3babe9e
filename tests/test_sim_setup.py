"""Initial-state changes a task asks for before it starts (sim/setup.py)."""

from __future__ import annotations

import pytest

from emboteam.errors import UnknownObjectError
from emboteam.sim.setup import StateChange, apply_changes
from emboteam.world import WorldState


def test_changes_apply_in_order_then_side_effects(state1: WorldState) -> None:
    apply_changes(state1, [
        StateChange(object="Mug_1", is_dirty=True, parent="CoffeeMachine_1"),
        StateChange(object="CoffeeMachine_1", is_on=True),
        StateChange(object="Fridge_1", is_open=True),
    ])
    mug = state1.objects["Mug_1"]
    assert mug.parent == "CoffeeMachine_1" and mug.is_dirty
    assert mug.liquid == "coffee" and mug.temperature == "Hot"  # the running machine filled it
    assert state1.objects["Fridge_1"].is_open
    assert mug.position == state1.objects["CoffeeMachine_1"].position
    assert state1.invariant_violations() == []


def test_a_change_moves_contents_along(state1: WorldState) -> None:
    apply_changes(state1, [StateChange(object="Apple_1", parent="Bowl_1"),
                           StateChange(object="Bowl_1", parent="Fridge_1")])
    assert state1.is_within("Apple_1", "Fridge_1")
    assert state1.objects["Apple_1"].temperature == "Cold"
    assert state1.objects["Apple_1"].position == state1.objects["Fridge_1"].position


@pytest.mark.parametrize("change", [StateChange(object="Unicorn_1", is_open=True),
                                    StateChange(object="Apple_1", parent="Nowhere_1")])
def test_unknown_objects_are_typed_errors(state1: WorldState, change: StateChange) -> None:
    with pytest.raises(UnknownObjectError):
        apply_changes(state1, [change])


def test_change_text_form() -> None:
    assert str(StateChange(object="Mug_1", is_dirty=True)) == "Mug_1: is_dirty=True"
