"""AI2-THOR errorMessage -> typed failure reasons. The messages are AI2-THOR's own, as its
agent controller emits them (collected verbatim by TEACh's AI2-THOR wrapper and ALFRED's)."""

from __future__ import annotations

import pytest

from emboteam.thor.failures import failure_reason
from emboteam.world.actions import TRANSIENT_FAILURES, FailureReason, Skill

R = FailureReason

MESSAGES = [
    ("Object ID appears to be invalid.", R.UNKNOWN_OBJECT),
    ("Agent hand has something in it already! Can't pick up anything else", R.HAND_FULL),
    ("Can't place an object if Agent isn't holding anything", R.HAND_EMPTY),
    ("Place: ObjectInteraction only supported when holding an object", R.HAND_EMPTY),
    ("Floor|+00.00|+00.00|+00.00 must have the property CanPickup to be picked up.", R.NOT_PICKUPABLE),
    ("CounterTop|-00.08|+01.15|00.00 is not an Openable object", R.NOT_OPENABLE),
    ("Target must be OFF to open!", R.ALREADY_ON),
    ("object is not toggleable", R.NOT_TOGGLEABLE),
    ("can't toggle object on if it's already on!", R.ALREADY_ON),
    ("can't toggle object off if it's already off!", R.ALREADY_OFF),
    ("CounterTop_d7cc8dfe Does not have the CanBeSliced property!", R.NOT_SLICEABLE),
    ("Slice: ObjectInteraction only supported for held object Knife", R.NO_KNIFE),
    ("This target object is NOT a receptacle!", R.NOT_A_RECEPTACLE),
    ("No valid positions to place object found", R.NOT_ALLOWED_HERE),
    ("another object's collision is blocking held object from being placed", R.NOT_ALLOWED_HERE),
    ("cracked_egg_5(Clone) is not a valid Object Type to be placed in StoveBurner_58b674c4", R.NOT_ALLOWED_HERE),
    ("Knife|-01.70|+01.71|+04.01 is not interactable and (perhaps it is occluded by something).", R.NOT_VISIBLE),
    ("No target found", R.NOT_VISIBLE),
    ("CounterTop|+00.69|+00.95|-02.48 is too far away to be interacted with", R.NOT_REACHABLE),
    ("StandardIslandHeight is blocking Agent 0 from moving 0", R.NOT_REACHABLE),
    ("Picking up object would cause it to collide and clip into something!", R.NOT_REACHABLE),
]


@pytest.mark.parametrize(("message", "reason"), MESSAGES)
def test_thor_messages_map_to_our_reasons(message: str, reason: FailureReason) -> None:
    assert failure_reason(message) is reason


def test_unknown_messages_are_a_retryable_actuation_fault_and_a_failed_drive_is_unreachable() -> None:
    assert failure_reason("Object failed to open/close successfully.") is R.ACTUATION_FAULT
    assert failure_reason("something new in AI2-THOR 5.1") in TRANSIENT_FAILURES
    assert failure_reason("", Skill.GoToObject) is R.NOT_REACHABLE
