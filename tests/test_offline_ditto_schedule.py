"""'Ditto' and 'same as the pen' carry the act before to the next thing, and clock times in
a schedule say when, never how many (pfg/offline/data/idioms.json)."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.text import normalize
from offline_reading import read_offline

FRONTEND = OfflineFrontend()


def goal(text: str, floor_plan: str) -> set[str]:
    return {str(c) for c in read_offline(FRONTEND, text, floor_plan).spec.goal().conditions}


@pytest.mark.parametrize(("text", "floor_plan", "expected"), [
    ("Potato into the fridge. Egg: ditto.", "FloorPlan16",
     {"inside(Potato, Fridge)", "inside(Egg, Fridge)"}),
    ("Move the fork to a drawer, then the spoon - same like the fork.", "FloorPlan16",
     {"inside(Fork, Drawer)", "inside(Spoon, Drawer)"}),
    ("the remote control into the box please, and the watch dito", "FloorPlan207",
     {"inside(RemoteControl, Box)", "inside(Watch, Box)"}),
    ("soap bar onto the counter. the cloth: same.", "FloorPlan409",
     {"inside(SoapBar, CounterTop)", "inside(Cloth, CounterTop)"}),
    ("Put the pen in the box. The pencil, same as the pen. Book ditto.", "FloorPlan316",
     {"inside(Pen, Box)", "inside(Pencil, Box)", "inside(Book, Box)"}),
])
def test_ditto_and_same_carry_the_act_before(text: str, floor_plan: str, expected: set[str]) -> None:
    assert goal(text, floor_plan) == expected


@pytest.mark.parametrize("text", ["leave the desk lamp the same.", "the desk lamp, same as before.",
                                  "put two apples on the table at the window."])
def test_keeps_and_counts_are_not_rewritten(text: str) -> None:
    """'the same' after a verb and 'same as before' keep a state; a count stays a count."""
    assert normalize(text) == " ".join(text.replace(",", " ,").replace(".", " .").split())


@pytest.mark.parametrize(("text", "floor_plan", "expected"), [
    ("7:00 mug into the coffee machine. 7:30 the egg into the fridge.", "FloorPlan16",
     {"inside(Mug, CoffeeMachine)", "inside(Egg, Fridge)"}),
    ("by noon the watch is in the box, at half six the television goes on", "FloorPlan207",
     {"inside(Watch, Box)", "switched_on(Television)"}),
])
def test_clock_times_are_when_not_how_many(text: str, floor_plan: str, expected: set[str]) -> None:
    assert goal(text, floor_plan) == expected


def test_a_spoken_list_of_dittos_keeps_every_item() -> None:
    """Said without commas, each "too" ends its item; the act after it is still read."""
    assert goal("the remote control into the box and the watch dito and the credit card dito "
                "and then the television on", "FloorPlan207") == {
        "inside(RemoteControl, Box)", "inside(Watch, Box)", "inside(CreditCard, Box)",
        "switched_on(Television)"}


def test_emphasis_of_a_rule_is_no_exclusion() -> None:
    """"no exceptions" stresses the rule; the rule and "the same rule" still hold."""
    assert goal("House rule: pens sleep in the box, no exceptions, and pencils follow the same "
                "rule.", "FloorPlan316") == {"inside(Pen, Box)", "inside(Pencil, Box)"}


@pytest.mark.parametrize(("text", "floor_plan", "expected"), [
    ("Put half of the two cloths in the hamper.", "FloorPlan307", {"inside(Cloth, LaundryHamper)"}),
    ("Of the three vases, two thirds should end up in the sink.", "FloorPlan5",
     {"inside(2 of Vase, SinkBasin)"}),
    ("\u00bd of the 2 rolls onto the toilet", "FloorPlan401", {"inside(ToiletPaper, Toilet)"}),
])
def test_a_fraction_of_a_said_number_is_a_count(text: str, floor_plan: str, expected: set[str]) -> None:
    assert goal(text, floor_plan) == expected


def test_a_fraction_that_is_no_whole_count_is_left_as_said() -> None:
    assert normalize("half of three apples") == "half of three apples"
