"""Keeps as one rule (issue 25, doubts/kept_place.py): a thing named as a landmark or
told as already in place, a thing given only a state whose words say it stays, and a bare
"X no move" keep its present place; never an act on it. New sentences, not the dev
rounds'."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.pfg.offline.doubts.kept_place import KIND, KeptPlaceCues
from emboteam.pfg.offline.knowledge import KnowledgeDataError
from emboteam.pfg.offline.knowledge import read as read_knowledge
from test_offline_reading import goal, read


@pytest.mark.parametrize(("text", "fp", "expected"), [
    # a landmark keeps its place (FloorPlan205: the pillow on the sofa; FloorPlan4: the
    # pot on a burner)
    ("Put the remote on the sofa next to the pillow.", 205,
     {"inside(RemoteControl, Sofa)", "inside(Pillow, Sofa)"}),
    ("Put the pan on the stove beside the pot.", 4,
     {"inside(Pan, StoveBurner)", "inside(Pot, StoveBurner)"}),
    # already in place (FloorPlan1: the egg in the fridge)
    ("The egg is already in the fridge, don't take it out; put the tomato in there too.", 1,
     {"inside(Egg, Fridge)", "inside(Tomato, Fridge)"}),
    # a state beside a keep of its place (FloorPlan205: the laptop on the dining table)
    ("Switch the TV on; the laptop gets closed, not moved.", 205,
     {"switched_on(Television)", "closed(Laptop)", "inside(Laptop, DiningTable)"}),
    ("Close the laptop, but don't take it off the table.", 205,
     {"closed(Laptop)", "inside(Laptop, DiningTable)"}),
    # a bare keep ("no move" is no self-correction; FloorPlan221: the plate on the dining table)
    ("Switch the TV on. The plate no move.", 221,
     {"switched_on(Television)", "inside(Plate, DiningTable)"}),
])
def test_kept_in_place(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_a_landmark_moved_later_is_not_kept() -> None:
    # the pillow is a landmark first, then moved: where it goes wins, no keep is proposed
    reading = read("Put the remote next to the pillow, then put the pillow in the box.", 205)
    assert "inside(Pillow, Box)" in goal(reading)
    assert "inside(Pillow, Sofa)" not in goal(reading)
    assert not [d for d in reading.doubts if d.kind == KIND and d.span == "pillow"]


def test_a_place_named_beside_a_state_is_only_a_candidate() -> None:
    # "the candle on the counter" only says which candle: its place is no wish of its own
    # (FloorPlan427), so the reading lights it and the kept place is the alternative
    reading = read("Light the candle on the counter.", 427)
    assert goal(reading) == {"switched_on(Candle)"}


def test_the_landmark_relations_are_checked_at_load(tmp_path: Path) -> None:
    bad = tmp_path / "kept_place.json"
    bad.write_text(json.dumps({"keep_after": [["stays"]], "place_preps": ["in"], "already": [],
                               "landmark_preps": ["near"], "reach": 8}), encoding="utf-8")
    with pytest.raises(KnowledgeDataError):
        read_knowledge(bad, KeptPlaceCues)
