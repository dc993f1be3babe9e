"""How the words are laid out and mangled (offline/layout.py, data/surface.json): a markdown
table's place column, struck-out words, things listed under a heading, punctuation dictated
as words, and a real English word a voice keyboard put for a scene thing (a guess the
ranker weighs, never a rewrite of the text that is read)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.pfg import offline
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.knowledge import KnowledgeDataError, validate
from emboteam.pfg.offline.surface import SurfaceFile, read_surface
from emboteam.world.scene import load_scene
from offline_reading import read_offline

FRONTEND = OfflineFrontend()


def goal(text: str, floor_plan: str = "FloorPlan1") -> set[str]:
    return {str(c) for c in read_offline(FRONTEND, text, floor_plan).spec.goal().conditions}


def types(floor_plan: str = "FloorPlan1") -> frozenset[str]:
    return frozenset(load_scene(floor_plan).types())


@pytest.mark.parametrize(("text", "expected", "not_expected"), [
    # a table whose second column is headed as a place: its cells are where the things go,
    # a cell that says what to do keeps its words, a struck-out place is corrected away
    ("| thing | goes to |\n|---|---|\n| the apple | fridge |\n| the bread | ~~counter~~ microwave |",
     {"inside(Apple, Fridge)", "inside(Bread, Microwave)"}, {"inside(Bread, CounterTop)"}),
    ("| what | how |\n|:--|:--|\n| light | off |\n| kettle | on the stove |",
     {"switched_off(LightSwitch)", "inside(Kettle, StoveBurner)"}, set()),
    ("Put the egg in the ~~microwave~~ fridge.", {"inside(Egg, Fridge)"}, {"inside(Egg, Microwave)"}),
    # things listed under a heading that is a place or a verb take it
    ("Before bed:\n- onto the counter:\n  - the apple\n  - the tomato\n- light off",
     {"inside(Apple, CounterTop)", "inside(Tomato, CounterTop)", "switched_off(LightSwitch)"}, set()),
    ("To do:\n1. throw out:\n   a) the egg\n   b) the sponge\n2. the light off",
     {"inside(Egg, GarbageCan)", "inside(DishSponge, GarbageCan)", "switched_off(LightSwitch)"}, set()),
    # items under a heading that say what to do keep their own lines
    ("Kitchen:\n  - apple in the fridge\n  - light off", {"inside(Apple, Fridge)", "switched_off(LightSwitch)"}, set()),
    # punctuation dictated to a speech keyboard
    ("robots comma put the egg in the fridge full stop new paragraph the bread goes in the microwave full stop",
     {"inside(Egg, Fridge)", "inside(Bread, Microwave)"}, set()),
])
def test_a_laid_out_list_reads_as_its_items(text: str, expected: set[str], not_expected: set[str]) -> None:
    read = goal(text)
    assert expected <= read
    assert not (not_expected & read)


def test_a_table_without_a_place_column_only_joins_its_cells() -> None:
    said = read_surface("| job | note |\n|---|---|\n| fridge | shut it |", types()).text
    assert "→" not in said and "fridge shut it" in said


def test_a_real_word_for_a_scene_thing_is_a_guess_not_a_rewrite() -> None:
    text = "the apple goes in the fridge, and the pit stays on the stove"
    surface = read_surface(text, types())
    assert surface.text == text                     # what is read first is what was said
    assert surface.alternative is not None and "the pot stays" in surface.alternative
    assert "real_word" in surface.guesses
    reading = read_offline(FRONTEND, text)
    assert {str(c) for c in reading.candidates[0].goals} == {"inside(Apple, Fridge)"}     # a low prior
    assert any("inside(Pot, StoveBurner)" in {str(c) for c in c.goals} for c in reading.candidates)


@pytest.mark.parametrize("text", [
    "wipe the top shelf",                   # a modifier, not the thing
    "put the mug on the shelf, the rest can wait",   # sounds like nothing of the scene
    "put the apple in the fridge",          # nothing unknown
])
def test_a_real_word_names_a_thing_only_in_a_things_slot_and_like_one_thing(text: str) -> None:
    assert "real_word" not in read_surface(text, types()).guesses


def test_a_real_word_needs_the_thing_in_the_scene() -> None:
    # FloorPlan201 (a living room) has no pot: "the pit" stays a pit
    assert "Pot" not in types("FloorPlan201")
    assert "real_word" not in read_surface("the pit stays on the table", types("FloorPlan201")).guesses


def test_a_malformed_layout_entry_names_the_file_and_the_entry() -> None:
    data = json.loads((Path(offline.__file__).parent / "data" / "surface.json").read_text(encoding="utf-8"))
    del data["layout"]["place_columns"]
    with pytest.raises(KnowledgeDataError, match=r"surface\.json.*layout"):
        validate("surface.json", data, SurfaceFile)
