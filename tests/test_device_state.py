"""The end state a device is asked to be in, read from its own words (doubts/device_state.py,
state words in doubts/state_words.json): a particle after a pronoun, calques, kept states,
a misheard "of", a state carried to the next device or said to be as it is now, purposes
and complaints; a described state stays a complaint, a condition's state is no goal."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.state_words import STATE_WORDS_FILE, StateWords
from emboteam.pfg.offline.knowledge import KnowledgeDataError, read
from offline_reading import read_offline


@pytest.fixture(scope="module")
def frontend() -> OfflineFrontend:
    return OfflineFrontend()


def _read(frontend: OfflineFrontend, text: str, floor_plan: str) -> tuple[set[str], list[set[str]]]:
    """The first reading's goals and every candidate's."""
    reading = read_offline(frontend, text, floor_plan)
    return {str(c) for c in reading.spec.goal().conditions}, [{str(c) for c in k.goals} for k in reading.candidates]


@pytest.mark.parametrize(("text", "floor_plan", "wanted"), [
    # a particle after the pronoun that stands for the device
    ("The floor lamp, you turn it off, and the television you put it on.", "FloorPlan201",
     {"switched_off(FloorLamp)", "switched_on(Television)"}),
    # "of" heard for "off" at a clause's end
    ("Leave the remote on the sofa and the floor lamp of thanks", "FloorPlan201",
     {"switched_off(FloorLamp)", "inside(RemoteControl, Sofa)"}),
    # a state kept, beside a state asked
    ("The floor lamp can stay on, but the big ceiling light goes off.", "FloorPlan201",
     {"switched_on(FloorLamp)", "switched_off(LightSwitch)"}),
    # as it is now
    ("The television is off, just like it is now.", "FloorPlan201", {"switched_off(Television)"}),
    # carried to the next device ("and so is")
    ("When I come home the telly is off and so is the floor lamp.", "FloorPlan201",
     {"switched_off(Television)", "switched_off(FloorLamp)"}),
    # a complaint about the state the words say
    ("A desk lamp burning all night in an empty bedroom is a waste of electricity.", "FloorPlan301",
     {"switched_off(DeskLamp)"}),
    # open words for blinds
    ("Draw the curtains back so I get some daylight.", "FloorPlan315", {"open(Blinds)"}),
    # a participle after a place: the device's state
    ("The laptop goes back on the desk, shut.", "FloorPlan301", {"inside(Laptop, Desk)", "closed(Laptop)"}),
    # the later state settles it
    ("The cupboard: open it first, close it after.", "FloorPlan1", {"closed(Cabinet)"}),
    # a condition's state is no goal, the request after it is
    ("If the laptop is open, it has to be closed.", "FloorPlan301", {"closed(Laptop)"}),
    # state_words.json, words: "beaming" (the worked example of docs/teach_a_phrasing.md)
    ("remote on the sofa, the floor lamp beaming", "FloorPlan201",
     {"inside(RemoteControl, Sofa)", "switched_on(FloorLamp)"}),
    # a negation before the device
    ("Make me a slice of toast, please. And don't leave the toaster on.", "FloorPlan1",
     {"switched_off(Toaster)"}),
])
def test_a_device_is_read_to_the_state_its_words_give(frontend: OfflineFrontend, text: str, floor_plan: str,
                                                      wanted: set[str]) -> None:
    first, _ = _read(frontend, text, floor_plan)
    assert wanted <= first


@pytest.mark.parametrize(("text", "floor_plan", "wanted", "not_wanted"), [
    # a thing that comes off the bed is moved, not switched
    ("Take the laptop off the bed and put it on the desk.", "FloorPlan301", "inside(Laptop, Desk)",
     "switched_off(Laptop)"),
    # a described state with a request after it: the request
    ("The sink tap is running, turn it off.", "FloorPlan1", "switched_off(Faucet)", "switched_on(Faucet)"),
    # a complaint ("somebody left ... open") asks the opposite
    ("Somebody left the fridge open.", "FloorPlan1", "closed(Fridge)", "open(Fridge)"),
    # "whoever opens drawers" is a role, not an end state
    ("Put the pen in a drawer; whoever opens drawers opens them.", "FloorPlan301", "inside(Pen, Drawer)",
     "open(Drawer)"),
    # "shut off the light": the verb's particle takes the light, not the toilet before it
    ("Soap bar on the toilet, and shut off the light.", "FloorPlan401", "switched_off(LightSwitch)",
     "closed(Toilet)"),
])
def test_words_that_are_no_device_state_leave_the_reading(frontend: OfflineFrontend, text: str, floor_plan: str,
                                                          wanted: str, not_wanted: str) -> None:
    first, _ = _read(frontend, text, floor_plan)
    assert wanted in first and not_wanted not in first


def test_a_described_state_keeps_both_polarities_among_the_candidates(frontend: OfflineFrontend) -> None:
    # "is on and keeps me awake": a complaint first, the state as said still a candidate
    first, cands = _read(frontend, "The desk lamp is on and it keeps me awake.", "FloorPlan301")
    assert "switched_off(DeskLamp)" in first
    assert any("switched_on(DeskLamp)" in c for c in cands)


def test_a_malformed_state_word_names_the_file_and_entry(tmp_path: Path) -> None:
    data = json.loads(STATE_WORDS_FILE.read_text())
    data["words"][0]["family"] = "lit"
    bad = tmp_path / "state_words.json"
    bad.write_text(json.dumps(data))
    with pytest.raises(KnowledgeDataError, match=r"state_words\.json: words\[0\].*family"):
        read(bad, StateWords)


def test_an_unknown_device_type_is_refused(tmp_path: Path) -> None:
    data = json.loads(STATE_WORDS_FILE.read_text())
    data["calque_types"].append("Lampshade")
    bad = tmp_path / "state_words.json"
    bad.write_text(json.dumps(data))
    with pytest.raises(KnowledgeDataError, match="Lampshade"):
        read(bad, StateWords)
