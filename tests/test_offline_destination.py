"""Where a thing goes, by the one destination finder (doubts/destination.py): a thing named
with no goal is read in its own window: a receptacle
there that it can go in, a home cue, a keep cue give its goal in the first reading, marked
unsure; a person a ramble names is chatter, not a missing thing. Sentences written for
this test (not round tasks)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.destination import DESTINATION_CUES_FILE, DestinationCues, destination
from emboteam.pfg.offline.errors import GroundingError
from emboteam.pfg.offline.knowledge import KnowledgeDataError, read
from emboteam.pfg.offline.tagger import tag
from emboteam.pfg.reading import Reading
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
from offline_reading import read_offline


@pytest.fixture(scope="module")
def frontend() -> OfflineFrontend:
    return OfflineFrontend()


def _read(frontend: OfflineFrontend, text: str, floor_plan: str) -> Reading:
    return read_offline(frontend, text, floor_plan)


def _goals(reading: Reading) -> set[str]:
    return {str(c) for c in reading.spec.goal().conditions}


@pytest.mark.parametrize(("text", "floor_plan", "wanted"), [
    # where it lies now is no destination; the place after "onto" is
    ("Teddy bear's on the floor, up onto the bed", "FloorPlan309", {"inside(TeddyBear, Bed)"}),
    # a home cue makes the place the destination under the negation of the description
    ("Put the candle on the counter. The spray bottle isn't in the cabinet where it belongs.", "FloorPlan403",
     {"inside(SprayBottle, Cabinet)"}),
    # a keep cue in the next sentence that names nothing else: where it is now
    ("Put the soap bar in the cabinet. And the cloth, is that on the toilet? Good, it stays.", "FloorPlan408",
     {"inside(Cloth, Toilet)", "inside(SoapBar, Cabinet)"}),
    # listed things share the window; a place after "from" is where they come from
    ("the keychain and the credit card, from the dining table into the box", "FloorPlan203",
     {"inside(KeyChain, Box)", "inside(CreditCard, Box)"}),
    # a narrative's end state: the state said beside the place
    ("by tonight the kettle is on the stove and the egg has been put into the fridge", "FloorPlan3",
     {"inside(Egg, Fridge)"}),
])
def test_the_window_gives_the_first_reading(frontend: OfflineFrontend, text: str, floor_plan: str,
                                            wanted: set[str]) -> None:
    reading = _read(frontend, text, floor_plan)
    assert wanted <= _goals(reading)


def test_a_goal_from_the_window_is_marked_unsure(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "Put the candle on the counter. The spray bottle isn't in the cabinet where it belongs.",
                    "FloorPlan403")
    assert "inside(SprayBottle, Cabinet)" in reading.unsure
    assert any(n.kind == "assumed" and "spray bottle" in n.span for n in reading.notes)


def test_a_negated_place_is_no_destination(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "Put the pencil in the box. The watch is not on the sofa, it never was.", "FloorPlan203")
    assert "inside(Watch, Sofa)" not in _goals(reading)


def test_a_person_in_a_ramble_is_chatter(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "You know my uncle, he takes the baseball bat all the time. "
                              "The bat is kept on the desk from now on.", "FloorPlan303")
    assert "inside(BaseballBat, Desk)" in _goals(reading)


def test_a_person_as_the_only_object_still_names_nothing(frontend: OfflineFrontend) -> None:
    with pytest.raises(GroundingError):
        _read(frontend, "pick up my cousin", "FloorPlan303")


def test_a_malformed_cue_file_names_file_and_entry(tmp_path: Path) -> None:
    raw = json.loads(DESTINATION_CUES_FILE.read_text(encoding="utf-8"))
    raw["reach"] = 0
    bad = tmp_path / "destination_cues.json"
    bad.write_text(json.dumps(raw), encoding="utf-8")
    with pytest.raises(KnowledgeDataError, match=r"destination_cues\.json: reach"):
        read(bad, DestinationCues)


def test_an_unknown_cue_field_names_file_and_entry(tmp_path: Path) -> None:
    raw = json.loads(DESTINATION_CUES_FILE.read_text(encoding="utf-8"))
    raw["toward"] = [["into"]]
    bad = tmp_path / "destination_cues.json"
    bad.write_text(json.dumps(raw), encoding="utf-8")
    with pytest.raises(KnowledgeDataError, match=r"destination_cues\.json: toward"):
        read(bad, DestinationCues)


# the one destination finder, on sentences written for it (dest25)
def _ctx(text: str, floor_plan: str) -> DoubtContext:
    scene = load_scene(floor_plan)
    return DoubtContext(items=tag(text), goals=(), scene=scene,
                        state=WorldState.from_scene(scene, parse_team("1,2,3")))


def _at(ctx: DoubtContext, word: str) -> int:
    return next(k for k, item, _ in ctx.mentions() if item.text == word)


@pytest.mark.parametrize(("text", "floor_plan", "word", "thing", "wanted"), [
    # a directional cue leads past a source word; a place led by a cue is inside the window
    ("the soap bar comes out onto the shelf", "FloorPlan401", "soap bar", "SoapBar", "Shelf"),
    ("Pencils don't belong on the bed, their home is the drawer.", "FloorPlan301", "pencils", "Pencil", "Drawer"),
    # a cue does not lead across a sentence mark ("on. the drawer" is no destination)
    ("the keychain goes in. the drawer is open.", "FloorPlan201", "keychain", "KeyChain", None),
    # an excepted thing goes only where its own words send it, past a mark or a pronoun
    ("everything but the pencil goes in the drawer", "FloorPlan301", "pencil", "Pencil", None),
    ("everything but the pencil, which goes in the drawer", "FloorPlan301", "pencil", "Pencil", "Drawer"),
])
def test_the_destination_a_things_words_give(text: str, floor_plan: str, word: str, thing: str,
                                            wanted: str | None) -> None:
    ctx = _ctx(text, floor_plan)
    assert next(iter(destination(ctx, _at(ctx, word), thing)), None) == wanted


def test_a_home_named_after_a_long_complaint_is_read(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "The remote keeps turning up everywhere; its home is the coffee table.", "FloorPlan201")
    assert "inside(RemoteControl, CoffeeTable)" in _goals(reading)
