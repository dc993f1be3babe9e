"""The surfaces a request comes in, made plain clauses by the page step (pfg/offline/page.py):
a dialogue's questions and answers, a shouted telegram, typing slips fixed in place."""

from __future__ import annotations

import re

from emboteam.pfg.offline.page import read_page
from emboteam.pfg.offline.surface import _bare, _is_noun, _nounish

_BULLET = re.compile(r"^[ \t]*(?:[-*+]|\d+[.)])[ \t]+")


def _page(text: str) -> str:
    return read_page(text, _bare, _is_noun, _nounish, _BULLET)


def test_a_dialogue_answer_is_about_the_thing_asked() -> None:
    said = _page("Bot: What now? Me: a tidy desk. Bot: The pen? Me: into the drawer and shut it. "
                 "Bot: The kettle? Me: stays. Bot: Lamp? Me: off please.")
    assert "The pen into the drawer and shut it." in said
    assert "The kettle stays." in said and "Lamp off please." in said
    assert "Bot" not in said and "Me:" not in said


def test_a_dialogue_over_slashes_and_lower_case_labels() -> None:
    said = _page("R: mug? / me: into the sink / R: tv? / me: off / R: anything else? / me: no thx")
    assert said.startswith("mug into the sink. tv off.")


def test_speakers_who_both_give_orders_are_no_questions_and_answers() -> None:
    said = "TOM: the apple in the fridge. ANA: no, the tomato. TOM: fine. ANA: and the light off."
    assert _page(said) == said


def test_a_shouted_telegram_is_read_in_lower_case_with_stop_as_a_full_stop() -> None:
    said = _page("MUG TO SINK STOP CORRECTION MUG TO SHELF STOP BREAD STAYS COUNTER STOP LIGHT OFF STOP")
    assert said == "mug to sink. correction: mug to shelf. bread stays on counter. light off. "


def test_a_telegram_run_of_names_is_a_list_and_ends_at_its_place() -> None:
    said = _page("PEN PENCIL BOOK DRAWER DRAWER SHUT STOP CARD PHONE INTO BOX STOP NEGATIVE LAMP OFF STOP")
    assert said.startswith("pen, pencil, book → drawer. drawer shut. card, phone into box. no, lamp off.")


def test_shouting_without_stop_is_only_lower_cased_and_one_word_is_no_shout() -> None:
    assert _page("PUT THE MUG IN THE SINK AND THE BREAD ON THE COUNTER") == \
        "put the mug in the sink and the bread on the counter"
    assert _page("Floor lamp OFF, desk lamp ON, TV stays on.") == "Floor lamp OFF, desk lamp ON, TV stays on."


def test_a_slip_fixed_after_a_cue_replaces_the_word_it_fixes() -> None:
    assert _page("Put the male in the microwave - sorry, MUG, stupid autocorrect - microwave on.") == \
        "Put the mug in the microwave, microwave on."
    assert _page("The pan goes next to the pit, I mean pot, on the stove.") == \
        "The pan goes next to the pot, on the stove."
    # a cue after a word that names a thing is a correction, the corrections' business
    said = "Put the mug in the sink, sorry, shelf."
    assert _page(said) == said


def test_a_one_word_sentence_echoing_a_slip_replaces_it() -> None:
    assert _page("Bowl into the sinking. Sink. Cabinets shit. SHUT.") == "Bowl into the sink. Cabinets shut."
    said = "Lamp off. Light. Mug in the sink. Stop."
    assert _page(said) == said


def test_an_answer_that_only_names_a_place_is_where_the_thing_goes() -> None:
    said = _page("Bot: Spoons on the counter? Me: a drawer, then close it. Bot: Mug? Me: the sink. "
                 "Bot: Lamp? Me: off. Bot: TV? Me: the one on the wall stays on.")
    assert "Spoons on the counter → a drawer, then close it." in said and "Mug → the sink." in said
    assert "TV? the one on the wall stays on." in said


def test_a_thread_s_post_numbers_end_its_posts() -> None:
    assert _page("1/ bots, listen up 2/ keys + card -> a drawer 3/ mug -> sink") == \
        "bots, listen up. keys + card -> a drawer. mug -> sink"
    assert _page("2/4 pot -> stove 3/4 mug -> sink.").startswith("pot -> stove. mug -> sink.")
    said = "Cut 1/2 the bread and put 3/ of it away."     # no thread: numbers out of order
    assert _page(said) == said


def test_an_echo_that_inflects_the_word_is_no_slip() -> None:
    said = "Press two to confirm. Confirmed. Put it on the shelf. Shelves."
    assert _page(said) == said
