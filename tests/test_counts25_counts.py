"""Counts and conditions no one asked for (issue 25, round 61): a stated number is kept
by a keep, a section mark counts nothing, an order of acts is no contradiction, and no
goal comes from a word that names nothing asked (a phone mention is no switch)."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline.tagger import tag
from test_offline_reading import goal, read


@pytest.mark.parametrize(("text", "fp", "expected"), [
    # a number said before a kept thing is how many stay (both pillows start on the bed)
    ("Turn off the desk lamp. The two cushions stay on the bed, no touch.", 319,
     {"inside(2 of Pillow, Bed)", "switched_off(DeskLamp)"}),
    ("Open the shower curtain. Both loo rolls stay on the toilet.", 408,
     {"inside(2 of ToiletPaper, Toilet)", "open(ShowerCurtain)"}),
])
def test_a_stated_number_is_kept(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_a_section_mark_is_no_count() -> None:
    # "§2 Keys": the second rule about the keys, not two keys (the scene has one)
    assert "inside(KeyChain, SideTable)" in goal(read("§1 Lamps are off after 10.\n§2 Keys live on the side table.", 306))
    assert [i.text for i in tag("§3a Except the big light")][:2] == [";", "except"]


@pytest.mark.parametrize("text", ["a drawer open pls, and shut it after", "open a drawer and shut it afterwards"])
def test_an_act_then_its_undoing_is_an_order_not_a_contradiction(text: str) -> None:
    assert goal(read(text, 411)) == {"closed(Drawer)"}


def test_a_trailing_when_clause_is_still_a_condition() -> None:
    # "when it's done" is a subordinate clause, not a trailing "afterwards"
    spec = read("Cook the potato in the microwave and switch the microwave off when it's done.", 1).spec
    assert "switched_off(Microwave)" in {str(c) for c in spec.goal().conditions}


def test_a_phone_mentioned_is_not_switched_on() -> None:
    # a phone left unexplained proposes no switch state of its own (its switch is a means)
    reading = read("Phone: we'll see. Turn the lamp off.", 321)
    assert "switched_on(CellPhone)" not in goal(reading)
    assert all(r.label != "afford_switch" for c in reading.candidates for r in c.resolves)

