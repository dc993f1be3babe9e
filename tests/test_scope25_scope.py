"""Scope of exclusions and self-corrections (issue 25, round 59's classes): a keep added to
the exceptions in the next sentence, "everything there", "bar the", kinds named as "every
bit of", a false start finished by the word said later, a swap "not the X, the Y" across a
verbless sentence. Sentences in new words, not the development rounds'."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.text import normalize
from offline_reading import goal_of


@pytest.fixture(scope="module")
def frontend() -> OfflineFrontend:
    return OfflineFrontend()


def test_a_broken_off_word_is_the_word_said_later() -> None:
    assert "into the box kid" in normalize("Pens into the b-\nKid: The BOX, Mum")
    assert normalize("hey kit- okay kitchen").startswith("hey kitchen okay kitchen")


def test_a_broken_off_word_with_no_later_word_stays() -> None:
    assert normalize("Alexa- no, not you") == "alexa no , not you"


def test_a_keep_said_too_in_the_next_sentence_is_an_exception(frontend: OfflineFrontend) -> None:
    goals = goal_of(frontend, "Everything on the counter goes into a drawer except the soap bar. "
                              "Hang on, the spray bottle stays out as well.", 410)
    assert "inside(SprayBottle, CounterTop)" in goals
    assert "inside(SprayBottle, Drawer)" not in goals
    assert "inside(ToiletPaper, Drawer)" in goals


def test_without_too_the_next_sentence_is_its_own(frontend: OfflineFrontend) -> None:
    goals = goal_of(frontend, "Everything on the counter goes into a drawer except the soap bar. "
                              "The candle stays lit.", 410)
    assert "inside(SprayBottle, Drawer)" in goals


def test_everything_there_is_the_place_just_named(frontend: OfflineFrontend) -> None:
    goals = goal_of(frontend, "The counter is a mess. Everything there goes into a drawer, "
                              "apart from the soap bar.", 410)
    assert {"inside(SprayBottle, Drawer)", "inside(SoapBottle, Drawer)"} <= goals
    assert "inside(SoapBar, Drawer)" not in goals


def test_bar_the_excludes(frontend: OfflineFrontend) -> None:
    goals = goal_of(frontend, "Everything on the counter goes into a drawer, bar the soap bottle.", 410)
    assert "inside(SoapBottle, Drawer)" not in goals
    assert "inside(SprayBottle, Drawer)" in goals


def test_every_bit_of_a_kind_is_every_one_not_its_pieces(frontend: OfflineFrontend) -> None:
    goals = goal_of(frontend, "Every bit of fruit and veg goes in the fridge except the potato.", 1)
    assert {"inside(Apple, Fridge)", "inside(Lettuce, Fridge)", "inside(Tomato, Fridge)"} <= goals
    assert not any("Sliced" in g or "Potato" in g for g in goals)


def test_not_the_x_the_y_swaps_the_member(frontend: OfflineFrontend) -> None:
    goals = goal_of(frontend, "Put the card and the remote in the box. Right. Sorry, not the remote, the watch.", 222)
    assert {"inside(CreditCard, Box)", "inside(Watch, Box)"} <= goals
    assert "inside(RemoteControl, Box)" not in goals
