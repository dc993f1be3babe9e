"""A clause's force (offline/force.py, data/force.json): double negations cancel, denials of
the opposite and litotes ask for the state, hedged questions ask, a past arrangement told to
be repeated and a rule stated as a fact are the wished end state."""

from __future__ import annotations

import json

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.force import ForceFile, read_force
from emboteam.pfg.offline.knowledge import DATA_DIR, KnowledgeDataError, validate
from offline_reading import goal_of

FRONTEND = OfflineFrontend()


@pytest.mark.parametrize(("text", "fp", "expected"), [
    # cancel: two negations make a request
    ("I'm not not wanting the toaster on.", 1, {"switched_on(Toaster)"}),
    ("Don't you dare not switch the coffee machine on.", 1, {"switched_on(CoffeeMachine)"}),
    ("I don't want to come home to the fridge not shut.", 1, {"closed(Fridge)"}),
    # litotes: a denied opposite, an approval by understatement
    ("I wouldn't dream of leaving the microwave open.", 1, {"closed(Microwave)"}),
    ("I wouldn't mind if the apple was in the fridge.", 1, {"inside(Apple, Fridge)"}),
    # only: nowhere but there
    ("The apple shouldn't be anywhere other than in the fridge.", 1, {"inside(Apple, Fridge)"}),
    ("The potato isn't to be anywhere but the fridge.", 1, {"inside(Potato, Fridge)"}),
    # repeat: a past arrangement to do again
    ("The microwave was open this morning and should be again.", 1, {"open(Microwave)"}),
    ("Yesterday the toaster was on and that was fine.", 1, {"switched_on(Toaster)"}),
    ("Last night the toaster was on. Same tonight please.", 1, {"switched_on(Toaster)"}),
    ("Once upon a time the fridge was open and the apple was in it. The end. Make it so.", 1,
     {"open(Fridge)", "inside(Apple, Fridge)"}),
    # rule: a described state after a rule's header
    ("Kitchen rules: the fridge is open on Sundays.", 1, {"open(Fridge)"}),
    ("In this house the microwave is open at night.", 1, {"open(Microwave)"}),
    # request: a question and its elliptical answer, a prohibition said of nobody
    ("Is the fridge still open? It shouldn't be.", 1, {"closed(Fridge)"}),
    ("Nobody is to leave the fridge open.", 1, {"closed(Fridge)"}),
])
def test_the_force_of_a_clause_is_the_state_asked(text: str, fp: int, expected: set[str]) -> None:
    assert goal_of(FRONTEND, text, fp) == expected


def test_negations_compose_by_count() -> None:
    assert read_force("i am not not wanting the lamp off .") == "i want the lamp off ."
    assert read_force("i am not not not wanting the lamp off .") == "i am not wanting the lamp off ."


def test_a_restore_wishes_the_past_not_the_present() -> None:
    assert read_force("undo it . the mug was where it is now .") == "undo it . the mug should be where it is now ."
    assert read_force("the lamp is off and is meant to stay that way .") == "the lamp should be off ."


def test_plain_sentences_are_left_alone() -> None:
    for text in ("do not put the apple in the fridge .", "the lamp was on all night , turn it off .",
                 "the fridge is open , shut it ."):
        assert read_force(text) == text


def test_a_rule_naming_no_piece_is_refused() -> None:
    raw = json.loads((DATA_DIR / "force.json").read_text(encoding="utf-8"))
    raw["cancel"][0]["pattern"] = "{nothing} not"
    with pytest.raises(KnowledgeDataError, match="no piece 'nothing'"):
        validate("force.json", raw, ForceFile)
