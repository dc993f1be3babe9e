"""Things named by their use, their look or what they stand next to (issue 25, use25):
"the thing you boil water in", "the thing I pay with", "everything I write with", "the
plastic disc", "the roll by the soap stays". The sentences are new, written for these
tests, not taken from a development round."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.described import DescribedFile, name_described
from emboteam.pfg.offline.knowledge import DATA_DIR, KnowledgeDataError, read
from offline_reading import goal_of

FRONTEND = OfflineFrontend()


def test_every_entry_names_its_type_by_a_noun_the_lexicon_knows() -> None:
    data = read(DATA_DIR / "described.json", DescribedFile)
    nouns = lx.nouns()
    for entry in (*data.things, *data.looks):
        concept = nouns.get(entry.name) or nouns.get(entry.name.rstrip("s"))
        assert concept is not None, entry.name
        assert entry.type in concept.types, (entry.name, entry.type, concept.types)


def test_an_unknown_type_is_named(tmp_path: Path) -> None:
    data: dict[str, Any] = json.loads((DATA_DIR / "described.json").read_text())
    data["things"][0]["type"] = "Kettel"
    path = tmp_path / "described.json"
    path.write_text(json.dumps(data))
    with pytest.raises(KnowledgeDataError, match=r"^described\.json: things\[0\] -> 'type'.*'Kettel'"):
        read(path, DescribedFile)


@pytest.mark.parametrize(("text", "types", "named"), [
    ("the thing you boil water in goes on the stove", {"Kettle"}, "the kettle goes"),
    ("the gadget that makes the coffee, switch it on", {"CoffeeMachine"}, "the coffee machine,"),
    ("the thing we call people with stays", {"CellPhone"}, "the phone stays"),
    ("the tool for flipping pancakes", {"Spatula"}, "the spatula"),
    ("the one that wakes us up in the morning", {"AlarmClock"}, "the alarm clock in the morning"),
    ("the thing above the window that keeps the sun out", {"Blinds"}, "the blinds"),
    ("the thing above the window that keeps the sun out", {"Curtains"}, "the curtains"),
    ("the thing you draw with", {"Pen", "Pencil"}, "the pencil"),
    ("the things I write with", {"Pen", "Pencil"}, "the pen and the pencil"),
    ("the shiny disc", {"CD"}, "the cd"),
])
def test_a_description_is_named_for_the_scene(text: str, types: set[str], named: str) -> None:
    assert named in name_described(text, types)


@pytest.mark.parametrize(("text", "types"), [
    ("the apple, the one you cut in half, stays", {"Knife", "Apple"}),     # the thing cut, not the tool
    ("the one standing on the left", {"ShowerHead"}),                      # no relative clause, no purpose
    ("the thing you boil water in goes on the stove", {"Pot"}),            # the scene has no kettle
    ("the shiny disc", {"Plate"}),                                         # nor a cd
    ("everything I write with goes in the box", {"Pen"}),                  # a property: properties.py
])
def test_no_name_without_a_description_the_scene_fits(text: str, types: set[str]) -> None:
    assert name_described(text, types) == text


@pytest.mark.parametrize(("text", "named"), [
    ("The candle next to the soap stays, the cloth goes in a drawer.", "The candle stays,"),
    ("Put the mug beside the kettle into the sink.", "Put the mug into the sink."),
    ("The knife - the one lying by the bread - goes in a drawer.", "The knife goes in a drawer."),
    ("The phone near the laptop stays, it is charging.", "The phone stays"),
])
def test_a_landmark_only_names_where_a_thing_is(text: str, named: str) -> None:
    assert name_described(text, {"Mug"}).startswith(named)


@pytest.mark.parametrize("text", [
    "Put the mug next to the kettle.",                           # where it goes
    "The soap goes on the counter next to the bottle, thanks.",  # the place's own landmark
    "The holder by the loo is empty.",                           # a copula: which holder
])
def test_a_relation_to_where_a_thing_goes_stays(text: str) -> None:
    assert name_described(text, {"Mug"}) == text


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("The thing I drink coffee from goes into the sink, and the thing you cut bread with into a drawer.", 1,
     {"inside(Mug, SinkBasin)", "inside(Knife, Drawer)"}),
    ("The thing I flick channels with goes on the sofa.", 201, {"inside(RemoteControl, Sofa)"}),
    ("The thing I play tennis with goes on the bed.", 302, {"inside(TennisRacket, Bed)"}),
])
def test_a_described_thing_is_read(text: str, fp: int, expected: set[str]) -> None:
    got = goal_of(FRONTEND, text, fp)
    assert expected <= got, got
