"""Switch and lid states outside imperatives (data/force.json ``states``, text.json's Scots
forms, rule_words.json ``exclusive.excepted_from``): a present state told to be kept, a state
meant "for a reason", code and config forms, sarcasm's sincere correction and a dialect's
"aff" are the end state; a described state followed by a fix is still a complaint."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.force import read_force
from offline_reading import goal_of

FRONTEND = OfflineFrontend()


@pytest.mark.parametrize(("text", "fp", "expected"), [
    # kept: a present state followed by "leave it", "don't touch it"
    ("Put the apple in the fridge. The toaster's on, leave it.", 1,
     {"inside(Apple, Fridge)", "switched_on(Toaster)"}),
    ("Slice the bread. The fridge is open - don't touch it.", 1, {"sliced(Bread)", "open(Fridge)"}),
    ("don't touch the microwave, it's open for a reason", 1, {"open(Microwave)"}),
    # sarcasm: the ironic permission, then the sincere state
    ("Oh sure, keep the coffee machine running all night, genius. Off.", 1, {"switched_off(CoffeeMachine)"}),
    # code and config
    ("toaster.stays_off()", 1, {"switched_off(Toaster)"}),
    ("fridge.state = closed", 1, {"closed(Fridge)"}),
    # Scots
    ("Turn the toaster aff.", 1, {"switched_off(Toaster)"}),
    # a complaint stays a complaint
    ("The toaster's on, turn it off.", 1, {"switched_off(Toaster)"}),
])
def test_a_kept_or_described_state_is_the_goal(text: str, fp: int, expected: set[str]) -> None:
    assert goal_of(FRONTEND, text, fp) == expected


def test_an_exception_to_a_move_is_no_purpose_of_light() -> None:
    goals = goal_of(FRONTEND, "Everything on the counter goes in the fridge except the apple. Light on.", 1)
    assert "switched_on(LightSwitch)" in goals
    assert "switched_off(LightSwitch)" not in goals


def test_prose_sentences_keep_their_boundaries() -> None:
    for text in ("the tv is off . on the sofa put the remote .", "the lamp is on , turn it off ."):
        assert read_force(text) == text
