"""A thing's places by role (issue 25, places25): a keep cue that a state word follows
keeps the state, not the place; a receptacle that receives things, described by where it
already stands, is named by that place (a landmark), not moved there; a question in
parentheses is an aside."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.pfg.offline.doubts.place_roles import KIND, PlaceRoles, load_place_roles
from emboteam.pfg.offline.knowledge import KnowledgeDataError
from emboteam.pfg.offline.knowledge import read as read_knowledge
from emboteam.pfg.offline.text import normalize
from test_offline_reading import goal, read


@pytest.mark.parametrize(("text", "state"), [
    ("The laptop stays shut.", "closed(Laptop)"),
    ("The laptop stays open.", "open(Laptop)"),
])
def test_a_kept_state_is_no_kept_place(text: str, state: str) -> None:
    # FloorPlan310: the laptop on the desk; "stays shut" keeps its lid, not its place
    assert goal(read(text, 310)) == {state}


def test_a_keep_with_a_place_after_it_keeps_the_place() -> None:
    assert goal(read("The laptop stays on the desk.", 310)) == {"inside(Laptop, Desk)"}


def test_a_receptacle_described_by_where_it_stands_is_not_moved_there() -> None:
    # FloorPlan222: the box stands on the side table
    reading = read("Put the card and the keys in the box, the box on the side table.", 222)
    assert goal(reading) == {"inside(CreditCard, Box)", "inside(KeyChain, Box)"}
    # the place as read stays a candidate
    assert any("inside(Box, SideTable)" in {str(c) for c in cand.goals} for cand in reading.candidates)
    assert [d.kind for d in reading.doubts].count(KIND) == 1


def test_a_receptacle_a_verb_moves_keeps_its_place() -> None:
    reading = read("Put the card in the box, then put the box on the side table.", 222)
    assert goal(reading) == {"inside(CreditCard, Box)", "inside(Box, SideTable)"}
    assert KIND not in [d.kind for d in reading.doubts]


def test_a_question_in_parentheses_is_an_aside() -> None:
    text = normalize("The one in the bin (who did that?) goes onto the holder.")
    assert "who" not in text and "?" not in text and "goes onto the holder" in text


def test_the_cue_file_is_checked_at_load(tmp_path: Path) -> None:
    assert "there" in load_place_roles().place_after_state
    bad = tmp_path / "place_roles.json"
    bad.write_text(json.dumps({"place_after_state": ["there"], "describing_preps": ["on"], "state_words": []}), encoding="utf-8")
    with pytest.raises(KnowledgeDataError, match=r"place_roles\.json"):
        read_knowledge(bad, PlaceRoles)
