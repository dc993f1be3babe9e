"""Things picked out by a property instead of a name (issue 25, prop25): "all the
breakables on the table", "anything over four kilos", "whatever runs on electricity",
"everything small on the stand". The vocabulary is data (doubts/properties.json); the
sentences are new, written for these tests (FloorPlan201: a living room whose dining table
holds a book, a card, a laptop, a newspaper, a pen, a pencil and a plate; FloorPlan1: a
kitchen with an apple, bread, a tomato on one counter, a lettuce and a potato on another)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.properties import PROPERTIES_FILE, load_properties, properties_in
from emboteam.pfg.offline.knowledge import KnowledgeDataError
from emboteam.pfg.offline.tagger import tag
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

FRONTEND = OfflineFrontend()


def readings(text: str, fp: int = 201) -> list[set[str]]:
    """The candidate readings' goals, likeliest first."""
    scene = load_scene(fp)
    team = parse_team("1,2")
    reading = FRONTEND.parse(text, scene, initial_state({}, scene, team), team)
    return [{str(c) for c in cand.goals} for cand in reading.candidates]


def test_a_flag_of_the_metadata_picks_the_things() -> None:
    first = readings("All the breakables on the dining table go onto the coffee table, please.")[0]
    assert {"inside(Plate, CoffeeTable)", "inside(Laptop, CoffeeTable)"} <= first
    assert not {"inside(Book, CoffeeTable)", "inside(Pen, CoffeeTable)", "inside(CreditCard, CoffeeTable)"} & first


def test_a_type_table_says_what_the_metadata_does_not() -> None:
    first = readings("Everything on the dining table that runs on electricity goes onto the sofa.")[0]
    assert "inside(Laptop, Sofa)" in first
    assert not {"inside(Book, Sofa)", "inside(Plate, Sofa)", "inside(Pen, Sofa)"} & first


def test_a_property_alone_picks_from_the_whole_room() -> None:
    first = readings("Whatever you can eat goes into the fridge, and that's it.", fp=1)[0]
    assert {"inside(Apple, Fridge)", "inside(Bread, Fridge)", "inside(Tomato, Fridge)",
            "inside(Lettuce, Fridge)", "inside(Potato, Fridge)"} <= first
    assert not {"inside(Mug, Fridge)", "inside(Book, Fridge)"} & first


def test_a_measure_with_a_unit_is_a_mass_test() -> None:
    first = readings("Anything in this room heavier than 2 kilos goes onto the coffee table.")[0]
    assert "inside(Laptop, CoffeeTable)" in first
    assert not {"inside(Book, CoffeeTable)", "inside(Vase, CoffeeTable)", "inside(Statue, CoffeeTable)"} & first


def test_a_vague_property_offers_its_other_tests_as_alternatives() -> None:
    cands = readings("Everything small on the dining table goes into the box.")
    first = cands[0]
    assert {"inside(Book, Box)", "inside(Pen, Box)", "inside(CreditCard, Box)"} <= first
    assert "inside(Laptop, Box)" not in first
    # "small" as the lightest things only (a card, a pen): a later candidate, not the first
    lighter = [c for c in cands[1:] if "inside(Pen, Box)" in c and "inside(Book, Box)" not in c]
    assert lighter


@pytest.mark.parametrize(("text", "found"), [
    ("everything small on the stand", ["small"]),
    ("anything on it that runs on electricity", ["electric"]),
    ("anything over four kilos", ["mass_min"]),
    ("switch on the small lamp on the desk", []),          # an adjective of a thing named
    ("put the little box on the shelf", []),
])
def test_property_words_are_found_unless_they_describe_a_named_thing(text: str, found: list[str]) -> None:
    items = tag(text)
    picked = properties_in(items, 0, len(items), lambda j: items[j].noun is not None)
    assert [p.name for p in picked] == found


def test_a_malformed_property_file_is_an_error_naming_the_entry(tmp_path: Path) -> None:
    raw = json.loads(PROPERTIES_FILE.read_text(encoding="utf-8"))
    raw["properties"][0]["tests"][0]["types"].append("Spaceship")
    bad = tmp_path / "properties.json"
    bad.write_text(json.dumps(raw), encoding="utf-8")
    with pytest.raises(KnowledgeDataError, match="Spaceship"):
        load_properties(bad)


def test_a_property_after_an_excluder_leaves_its_things_alone() -> None:
    first = readings("Clear the dining table onto the coffee table, apart from anything you write with.")[0]
    assert {"inside(Book, CoffeeTable)", "inside(Plate, CoffeeTable)"} <= first
    assert not {"inside(Pen, CoffeeTable)", "inside(Pencil, CoffeeTable)"} & first


def test_a_keep_by_property_is_out_of_the_rest() -> None:
    first = readings("Anything on the dining table that runs on electricity stays where it is, and so does "
                     "the plate; everything else on the dining table goes onto the coffee table.")[0]
    assert {"inside(Book, CoffeeTable)", "inside(Laptop, DiningTable)", "inside(Plate, DiningTable)"} <= first
    assert not {"inside(Laptop, CoffeeTable)", "inside(Plate, CoffeeTable)"} & first


def test_a_list_after_a_colon_is_the_set_the_property_heads() -> None:
    """ "Everything small in here goes into the box: the pen and the pencil": the colon's
    list names the things; the property only describes them (the other small things stay)."""
    first = readings("Everything small in here goes into the box: the pen and the pencil.")[0]
    assert {"inside(Pen, Box)", "inside(Pencil, Box)"} <= first
    assert not {"inside(Book, Box)", "inside(CreditCard, Box)", "inside(KeyChain, Box)", "inside(Watch, Box)"} & first
