"""Keeps and hands-off phrasings (issue 25): a thing kept, left alone or not to be moved
is read as its start place or state, never moved, never switched the other way."""

from __future__ import annotations

import pytest

from test_offline_reading import goal, read


@pytest.mark.parametrize(("text", "fp", "expected"), [
    # "the way it is" names the start state itself (FloorPlan218: floor lamp on at the
    # start), not the opposite of the desk lamp switched on beside it
    ("Switch the desk lamp on; the floor lamp can stay the way it is.", 218,
     {"switched_on(DeskLamp)", "switched_on(FloorLamp)"}),
    # "do not move X", "X isn't to be moved": X kept where it starts (FloorPlan207: the
    # card and the keys lie on the TV stand)
    ("Put the remote on the sofa, and please do not move the card.", 207,
     {"inside(RemoteControl, Sofa)", "inside(CreditCard, TVStand)"}),
    ("Switch the TV on. The keys aren't to be moved.", 207,
     {"switched_on(Television)", "inside(KeyChain, TVStand)"}),
    # "leave X alone" is hands off X, not "X alone on, every other light off"
    ("Open the shower curtain, but leave the candle alone.", 427,
     {"open(ShowerCurtain)", "inside(Candle, CounterTop)"}),
    # "is to be" / "is not to be": a duty, like "should be" / "must not be"
    ("Close the laptop. The television is to be left off.", 207,
     {"closed(Laptop)", "switched_off(Television)"}),
    ("Pull the shower curtain open. The candle on the counter is not to be lit tonight.", 427,
     {"open(ShowerCurtain)", "switched_off(Candle)"}),
])
def test_kept_things(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected
