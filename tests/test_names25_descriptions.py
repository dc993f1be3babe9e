"""Things and robots named by description (issue 25, names25): a robot named by its role
("whoever is good with the knife", "the one that does buttons") is a team member, not a
thing of the scene; a bare noun the scene has only as part of a compound type ("the
curtain" of a bathroom: its shower curtain); a thing described by what you do in it ("the
thing you read the news in"); an appliance named loosely by what it makes ("the coffee
gadget"); a dish before a noun only names its kind ("a toast rack"); a dish called off ("no
coffee"); a thing left to cool by itself is no chilling. The sentences are new, written for
these tests."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.errors import OfflineParseError
from emboteam.pfg.offline.roles import role_subject
from emboteam.pfg.offline.tagger import tag
from offline_reading import goal_of

FRONTEND = OfflineFrontend()


def goal(text: str, fp: int) -> set[str]:
    return goal_of(FRONTEND, text, fp)


@pytest.mark.parametrize(("text", "fp", "expected", "tool"), [
    ("Whoever has the sharp knife slices the bread.", 1, {"sliced(Bread)"}, "Knife"),
    ("The one that only does switches turns the desk lamp on.", 304, {"switched_on(DeskLamp)"}, "LightSwitch"),
    ("Whichever of you knows knives cuts the apple, then it stays on the counter.", 1,
     {"sliced(Apple)"}, "Knife"),
])
def test_a_role_names_a_robot_not_a_thing(text: str, fp: int, expected: set[str], tool: str) -> None:
    got = goal(text, fp)
    assert expected <= got
    assert not any(tool in c for c in got)


@pytest.mark.parametrize("text", [
    "The one that is on the table goes in the box.",      # a thing, not a robot
    "Whichever of you has free hands: the pen goes in the box.",   # the colon comes first
])
def test_no_role_without_an_ability_and_a_verb(text: str) -> None:
    items = tag(text)
    assert role_subject(items, 0) == 0


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("The curtain wants opening, please.", 405, {"open(ShowerCurtain)"}),
    ("Please put the thing you read the news in on the sofa.", 219, {"inside(Newspaper, Sofa)"}),
    ("Pop the mug into the coffee gadget and turn it on.", 1,
     {"inside(Mug, CoffeeMachine)", "switched_on(CoffeeMachine)"}),
])
def test_a_loose_name_is_the_scene_thing(text: str, fp: int, expected: set[str]) -> None:
    got = goal(text, fp)
    assert expected <= got, got


@pytest.mark.parametrize(("text", "fp", "expected", "absent"), [
    ("We once owned a toast rack like a duck. The apple goes in the fridge.", 1,
     {"inside(Apple, Fridge)"}, "Bread"),
    ("No coffee this morning, so the coffee machine stays off.", 1,
     {"switched_off(CoffeeMachine)"}, "filled"),
    ("The kettle can sit there and cool down.", 1, set(), "cold"),
])
def test_food_states_only_when_asked(text: str, fp: int, expected: set[str], absent: str) -> None:
    try:
        got = goal(text, fp)
    except OfflineParseError:     # nothing left to do: "no action found"
        got = set()
    assert expected <= got, got
    assert not any(absent in c for c in got), got
