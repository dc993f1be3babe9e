"""Unexplained mentions completed from their clause (issue 25): a thing named with its
destination but no verb ("potato and apple: fridge", "Same for the cloth.", "the keys go in
the same spot") is placed there in the first reading; words that only look alike ("Tonight:
fridge", "too hot", "back in the same place") place nothing."""

from __future__ import annotations

import pytest

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.destination import led, same_place, window
from emboteam.pfg.offline.tagger import tag
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from test_offline_reading import goal, read


def _ctx(text: str, fp: int = 1) -> DoubtContext:
    scene, team = load_scene(fp), parse_team("1,2")
    return DoubtContext(items=tag(text), goals=(), scene=scene, state=initial_state({"setup": []}, scene, team))


def _at(ctx: DoubtContext, word: str) -> int:
    return next(k for k, i in enumerate(ctx.items) if i.text == word)


@pytest.mark.parametrize(("text", "wanted"), [
    # a link mark between things and a place
    ("Put the mug in the sink. Potato and apple: fridge.", {"inside(Potato, Fridge)", "inside(Apple, Fridge)"}),
    # an additive word in a verbless stretch carries the place said before
    ("Put the knife in a drawer. Same for the fork.", {"inside(Knife, Drawer)", "inside(Fork, Drawer)"}),
    # "the same spot": where the thing before went; "as" another thing: where that one goes
    ("The bowl goes in the microwave. The cup goes in the same spot.", {"inside(Cup, Microwave)"}),
    ("The apple goes in the fridge. The lettuce goes to the same place as the apple.", {"inside(Lettuce, Fridge)"}),
])
def test_a_verbless_placement_is_read(text: str, wanted: set[str]) -> None:
    assert wanted <= goal(read(text, 1))


def test_a_degree_too_carries_nothing() -> None:
    # "too hot" is no additive "too" (a copula stands in the stretch)
    assert "inside(Pan, StoveBurner)" not in goal(read("Put the pot on the stove. The pan is too hot.", 1))


@pytest.mark.parametrize(("text", "place", "cue"), [
    ("potato and apple: fridge", "fridge", ":"),
    ("tonight: fridge", "fridge", None),          # no thing before the mark: a heading
    ("why is the egg on the floor? fridge.", "fridge", "?"),   # a place said as a sentence of its own
    ("why is the egg on the floor? fridge shut.", "fridge", None),
])
def test_a_mark_leads_to_a_place(text: str, place: str, cue: str | None) -> None:
    ctx = _ctx(text)
    assert led(ctx, _at(ctx, place)) == cue


def test_back_in_the_same_place_is_where_it_was() -> None:
    ctx = _ctx("the bowl goes in the microwave. put the cup back in the same place.")
    k = _at(ctx, "cup")
    lo, hi = window(ctx, k, "Cup")
    assert same_place(ctx, k, lo, hi, "Cup") == ()
    ctx = _ctx("the bowl goes in the microwave. put the cup in the same place.")
    k = _at(ctx, "cup")
    lo, hi = window(ctx, k, "Cup")
    assert same_place(ctx, k, lo, hi, "Cup") == ("Microwave",)


def test_a_colon_after_a_landmark_sends_nothing_of_the_sentence_before() -> None:
    # FloorPlan308: the clock and the bowl stand on a desk, the laptop on the other; "the one
    # with the laptop:" names a desk, not a thing placed, so the shelf is only the mug's
    got = goal(read("Two things stay, the clock and the bowl. The one with the laptop: the mug onto a shelf.", 308))
    assert "inside(Mug, Shelf)" in got
    assert not {"inside(AlarmClock, Shelf)", "inside(Bowl, Shelf)"} & got
