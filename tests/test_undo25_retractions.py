"""Undo, redo and later overrides across statements (issue 25, undo25): "undo" calls back
the request said before it, "redo" says the last undone one again, a change of mind takes
back the request before it; a self-correction opening the next sentence settles a device's
state; a place left unfinished and a hesitation start the place again. The sentences are
new, written for these tests (FloorPlan1: a kitchen)."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.knowledge import KnowledgeDataError, word_tables
from emboteam.pfg.offline.retractions import retract
from emboteam.pfg.offline.tagger import tag
from emboteam.pfg.offline.text import normalize
from offline_reading import goal_of

FRONTEND = OfflineFrontend()


def goal(text: str) -> set[str]:
    return goal_of(FRONTEND, text, 1)


def words(text: str) -> str:
    return " ".join(x.text for x in retract(tag(text)))


def test_undo_calls_back_the_request_before_it() -> None:
    got = goal("Put the apple in the fridge. Undo. Slice the tomato.")
    assert "sliced(Tomato)" in got
    assert "inside(Apple, Fridge)" not in got


def test_a_second_undo_takes_back_the_one_before() -> None:
    got = goal("put the potato in the pot [beep] undo [beep] put the potato in the pan [beep] "
               "undo that as well [beep] slice the tomato")
    assert "sliced(Tomato)" in got
    assert not any(c.startswith("inside(Potato") for c in got)


def test_redo_says_the_undone_request_again() -> None:
    assert words("the pan on the stove. undo. actually, redo it.") == ". actually , the pan on the stove ."


def test_redo_names_which_undone_request() -> None:
    said = words("the egg in the bowl. undo. the mug in the sink. undo. redo the bowl one.")
    assert said == ". . the egg in the bowl ."


def test_a_redo_called_off_redoes_nothing() -> None:
    said = words("the egg in the bowl. undo. redo the bowl one, no wait, not that one, close the fridge.")
    assert "egg" not in said and said.endswith("close the fridge .")


@pytest.mark.parametrize("text", [
    "Somebody moved the apple to the sink and I hate it. Undo it: the apple goes back in the fridge.",
    "my flatmate put the apple in the sink can you undo that it goes in the fridge",
])
def test_undo_of_what_someone_else_did_calls_nothing_back(text: str) -> None:
    assert "inside(Apple, Fridge)" in goal(text)


def test_undo_after_a_narrative_puts_back_what_someone_did() -> None:
    said = "she moved the apple to the sink ; it was in the fridge . undo that ."
    assert words(said) == said


def test_a_change_of_mind_takes_back_the_request_before_it() -> None:
    got = goal("Switch the light off. Update: my sister changed her mind; switch the toaster on instead.")
    assert "switched_on(Toaster)" in got
    assert "switched_off(LightSwitch)" not in got


def test_a_correction_opening_the_next_sentence_settles_the_state() -> None:
    got = goal("Fridge: open it. Wait no, keep it shut.")
    assert "open(Fridge)" not in got


def test_an_unfinished_place_and_a_hesitation_start_the_place_again() -> None:
    assert normalize("the soap bar in the soap... er, on the counter") == "the soap bar in the soap , no , on the counter"
    assert normalize("so... um, the mug") == "so . the mug"       # no place left unfinished: no correction


def test_a_sound_in_a_transcript_is_a_break() -> None:
    assert normalize("the egg in the fridge [BEEP] undo") == "the egg in the fridge . undo"


def test_the_cue_words_are_data() -> None:
    tables = word_tables("retractions")
    assert ("undo",) in tables.phrases("undo") and ("redo",) in tables.phrases("redo")
    with pytest.raises(KnowledgeDataError):
        tables.phrases("no such table")
