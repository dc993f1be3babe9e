"""Positions within the speaker's own list (issue 25, order25): a list named, then its items
referred to by order ("the former", "the first two", "the middle one", "number three on my
list") or by what is left ("the rest", "the other two"). The sentences are new, written for
these tests (FloorPlan201: keys, watch, card, remote, pen, pencil, book in a living room with
a box, a drawer, a shelf, a sofa; FloorPlan1: a kitchen)."""

from __future__ import annotations

import pytest

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.list_positions import EARLIER_LIST, earlier_list_reading, resolve_list_positions
from emboteam.pfg.offline.tagger import tag
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from offline_reading import goal_of

FRONTEND = OfflineFrontend()


def goal(text: str, fp: int = 201) -> set[str]:
    return goal_of(FRONTEND, text, fp)


def resolved(text: str) -> str:
    return " ".join(i.text for i in resolve_list_positions(tag(text)))


@pytest.mark.parametrize(("text", "expected"), [
    ("The watch and the pen: the former goes in the box, the latter onto the shelf.",
     {"inside(Watch, Box)", "inside(Pen, Shelf)"}),
    ("The keys, the watch and the book are on the table. Put the first and the last in the box.",
     {"inside(KeyChain, Box)", "inside(Book, Box)"}),
    ("There are the pen, the pencil, the card and the watch. The first two go in the drawer, the "
     "last one goes in the box.",
     {"inside(Pen, Drawer)", "inside(Pencil, Drawer)", "inside(Watch, Box)"}),
    ("Three things: the remote on the sofa, the book on the shelf, the watch on the table. The "
     "second goes in the box; the middle one is all I need moved.",
     {"inside(Book, Box)"}),
])
def test_a_position_in_the_list_is_the_item_there(text: str, expected: set[str]) -> None:
    assert expected <= goal(text)


def test_the_former_and_the_latter_are_not_swapped() -> None:
    got = goal("The pen and the book: put the latter on a shelf and the former in the drawer.")
    assert {"inside(Book, Shelf)", "inside(Pen, Drawer)"} <= got
    assert "inside(Pen, Shelf)" not in got


def test_the_rest_is_what_later_words_did_not_pick() -> None:
    assert resolved("The pen, the pencil, the card and the watch: the card goes in the box and the "
                    "rest in the drawer.").endswith(
        "the card goes in the box and the pen and the pencil and the watch in the drawer .")
    # a count that does not fit what is left is no reference to the list
    assert "the other three" in resolved("The pen, the pencil and the card: the card goes in the box, "
                                         "the other three stay.")


def test_a_list_that_only_names_items_again_is_no_new_list() -> None:
    # "half of them, the bread and the egg": the same items again; "the other half" is the rest
    assert resolved("Apple, bread, egg, tomato - half of them, the bread and the egg, go in the fridge, "
                    "the other half stay.").endswith("go in the fridge , apple and tomato stay .")


def test_the_kind_of_a_list_names_its_items() -> None:
    # "the two soaps, the bar and the bottle": "the bar" is the soap bar
    assert resolved("The two soaps, the bar and the bottle: the first goes in the cabinet.").endswith(
        "the soap bar goes in the cabinet .")


def test_an_indefinite_item_is_definite_when_referred_back_to() -> None:
    assert resolved("There's an apple, a lettuce and a tomato. Slice the second.").endswith(
        "slice the lettuce .")


@pytest.mark.parametrize("text", [
    "Put the pen and the book on the shelf. The first drawer stays shut.",      # an ordinal of a noun
    "Put the pen and the book on the shelf. The last time I asked, nobody did.",  # not a thing
    "Put the pen and the book on the shelf, then the rest of the toys in the box.",  # the rest of X
    "The pen and the book go on the shelf; leave the lifting to the other.",    # the other robot
    "Put the pen in the box. The first goes in the drawer.",                    # no list named
])
def test_words_that_are_no_reference_to_the_list_stay(text: str) -> None:
    assert resolved(text) == " ".join(i.text for i in tag(text))


def test_the_other_one_of_a_plural_item_is_not_that_item() -> None:
    # "both rolls ... one roll here, the other one there": one of the rolls, not both
    text = "The candle, the soap and both rolls: candle and soap in the box, one roll on the shelf, the other one stays."
    assert "the other one" in resolved(text)


def test_a_list_far_behind_is_not_reached() -> None:
    text = ("Put the pen and the book on the shelf. Switch the lamp off. Shut the laptop. "
            "Close the drawer. The first goes in the box.")
    assert resolved(text).endswith("the first goes in the box .")


def test_the_one_mentioned_first_and_a_number_on_the_list() -> None:
    assert resolved("Take the watch, the keys and the pen. The one I mentioned first goes in the box, "
                    "number three on my list goes in the drawer.").endswith(
        "the watch goes in the box , the pen goes in the drawer .")


def test_a_position_that_fits_two_lists_is_a_point_of_doubt() -> None:
    # the latest list is read; the list before it is the other candidate, not a silent guess
    scene = load_scene(201)
    team = parse_team("1,2")
    reading = FRONTEND.parse("The pen and the pencil are on the table, the watch and the keys on the sofa. "
                             "Put the first in the box.", scene, initial_state({}, scene, team), team)
    assert "inside(Watch, Box)" in {str(c) for c in reading.candidates[0].goals}
    other = [c for d in reading.doubts for c in d.choices if c.label == EARLIER_LIST]
    assert len(other) == 1 and "inside(Pen, Box)" in {str(c) for c in other[0].add}
    assert "inside(Watch, Box)" in {str(c) for c in other[0].drop}


def test_a_position_only_one_list_fits_has_no_other_reading() -> None:
    # "the third": only the first list has three items
    assert earlier_list_reading(tag("The pen, the pencil and the card are here, the watch and the keys there. "
                                    "The third goes in the box.")) is None
    assert resolved("The pen, the pencil and the card are here, the watch and the keys there. "
                    "The third goes in the box.").endswith("the card goes in the box .")
