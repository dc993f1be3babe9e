"""The page's shapes made plain clauses before reading (pfg/offline/page.py, data/page.json)."""

from __future__ import annotations

import re

from emboteam.pfg.offline.page import read_page
from emboteam.pfg.offline.surface import _bare, _is_noun, _nounish

_BULLET = re.compile(r"^[ \t]*(?:[-*+]|\d+[.)])[ \t]+")


def _page(text: str) -> str:
    return read_page(text, _bare, _is_noun, _nounish, _BULLET)


def test_a_question_and_its_answer_are_one_clause() -> None:
    assert _page("Q: TV? A: Off, obviously.") == "TV Off, obviously."
    assert "the keys and the card go Into the box" in _page("Q: Where do the keys and the card go? A: Into the box.")
    assert _page("Q: The soap? A: They stay on the shelf.") == "The soap stay on the shelf."
    assert _page("The shower door: open. The light? Off. More at eleven.").endswith("The light Off. More at eleven.")


def test_an_answer_with_its_own_subject_or_a_long_one_stays() -> None:
    said = "Q: Spare roll? A: The one on the shelf goes onto the toilet."
    assert _page(said) == said
    said = "coffee machine? ngl leave it off it's really mid."
    assert _page(said) == said
    assert _page("And the pot on the table? It's not a centrepiece.") == "And the pot on the table? It's not a centrepiece."


def test_a_thread_is_read_oldest_first_without_headers() -> None:
    text = "Keep the lamp ON.\n> On Fri, Ana wrote:\n> Lamp off. TV off."
    assert _page(text) == "Lamp off. TV off.\nKeep the lamp ON."


def test_speaker_labels_go_only_in_a_chat() -> None:
    assert _page("DAD: The cloth into the bin.\nMUM (from the hall): Not the bin! Into the tub.") == \
        "The cloth into the bin.\nNot the bin! Into the tub."
    assert _page("Note: the cloth into the bin.") == "Note: the cloth into the bin."


def test_a_bare_heading_is_the_place_of_its_items() -> None:
    text = "- fridge\n  - lettuce in too\n  - the egg on it\n- misc\n  - microwave shut"
    assert _page(text) == "- fridge\n  - lettuce in the fridge too\n  - the egg on the fridge\n- misc\n  - microwave shut"


def test_config_lines_are_clauses() -> None:
    text = "[rules]\nsoap_bar.home = drawer\ndrawers.state = closed\n[shower]\ndoor = open\n[lights]\nmain = off"
    assert _page(text) == "soap bar → drawer.\ndrawers closed.\nshower door open.\nmain lights off."
    assert _page("the score = 3") == "the score = 3"     # one line is no config file


def test_code_lines_and_arrows() -> None:
    assert _page("for lamp in lamps: lamp.off()") == "lamps off"
    assert _page("tv.stays_off()") == "tv stays_off"
    assert _page("newspaper: shelf -> sofa") == "newspaper from shelf → sofa"
    assert _page("laptop lid ↓") == "laptop lid down"


def test_a_report_of_the_future_is_the_end_state() -> None:
    assert _page("the spray will be in a cabinet") == "the spray should be in a cabinet"
    assert _page("The keys'll be in the drawer") == "The keys should be in the drawer"
    assert _page("I will be back at six") == "I will be back at six"
