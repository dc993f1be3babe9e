"""A thing the reading gave no goal is read in its own words (doubts/mention_cues.py):
a keeping cue keeps it as it is, a state word or participle asks that state, a chatter
cue explains it; the alternative a clear cue gives is the first candidate."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.check import FeasibilityCheck
from emboteam.pfg.offline.doubts.mention_words import MENTION_CUES_FILE, load_mention_cues
from emboteam.pfg.offline.knowledge import KnowledgeDataError
from emboteam.world.goals import Condition, ObjectRef, Predicate
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


@pytest.fixture(scope="module")
def frontend() -> OfflineFrontend:
    return OfflineFrontend()


def _first(frontend: OfflineFrontend, text: str, floor_plan: str) -> tuple[set[str], list[set[str]], tuple[str, ...]]:
    """The first candidate's goals, every candidate's goals, the unexplained mentions."""
    scene = load_scene(floor_plan)
    team = parse_team("1,2,3")
    reading = frontend.parse(text, scene, WorldState.from_scene(scene, team), team)
    cands = [{str(c) for c in cand.goals} for cand in reading.candidates]
    assert {str(c) for c in reading.spec.goal().conditions} == cands[0]   # the reading run is the first
    return cands[0], cands, reading.unexplained


@pytest.mark.parametrize(("text", "floor_plan", "wanted"), [
    # a keeping cue after the thing: its start place
    ("Put the apple in the fridge and leave the tomato where it is.", "FloorPlan1", "inside(Tomato, CounterTop)"),
    ("Put the remote on the sofa. The laptop stays too.", "FloorPlan201", "inside(Laptop, DiningTable)"),
    # a keeping cue with a state after it: that state
    ("Put the remote on the sofa. The floor lamp stays on for the cat.", "FloorPlan201", "switched_on(FloorLamp)"),
    # a state said by a participle in a verbless list
    ("remote on the sofa, the floor lamp glowing", "FloorPlan201", "switched_on(FloorLamp)"),
    # a negated state is its opposite
    ("Put the pen in the box. The desk lamp is never left burning at night.", "FloorPlan301",
     "switched_off(DeskLamp)"),
    # "stays" as an exception to a group's switch: the other state than the group's
    ("desktop on, lights off (desk lamp can stay), phone on the bed", "FloorPlan326", "switched_on(DeskLamp)"),
])
def test_a_clear_cue_gives_the_first_reading(frontend: OfflineFrontend, text: str, floor_plan: str,
                                            wanted: str) -> None:
    first, _, _ = _first(frontend, text, floor_plan)
    assert wanted in first


@pytest.mark.parametrize("text", [
    "Put the remote on the sofa. Last time it was my laptop, don't ask.",
    "Put the remote on the sofa. We used to have a second laptop, long story.",
    "Put the remote on the sofa; we had a laptop once, long story.",
])
def test_a_ramble_in_the_past_tense_asks_nothing(frontend: OfflineFrontend, text: str) -> None:
    first, cands, unexplained = _first(frontend, text, "FloorPlan201")
    assert first == {"inside(RemoteControl, Sofa)"}
    assert "laptop" not in unexplained
    # without a chatter cue the same mention is unexplained and proposes goals
    _, cands, unexplained = _first(frontend, "Put the remote on the sofa. And my laptop!", "FloorPlan201")
    assert "laptop" in unexplained and any("Laptop" in g for goals in cands for g in goals)


def test_an_adjective_of_the_thing_asks_nothing(frontend: OfflineFrontend) -> None:
    first, _, _ = _first(frontend, "Put the pen in the box, the open laptop is fine.", "FloorPlan301")
    assert "open(Laptop)" not in first


def test_a_thing_is_wanted_in_one_place_only() -> None:
    scene = load_scene("FloorPlan1")
    team = parse_team("1,2")
    check = FeasibilityCheck(scene, WorldState.from_scene(scene, team), team)

    def placed(thing: str, place: str) -> Condition:
        return Condition(predicate=Predicate.inside, subject=ObjectRef(types=(thing,)),
                         receptacle=ObjectRef(types=(place,)))
    assert check((placed("Apple", "Fridge"),))
    assert not check((placed("Apple", "Fridge"), placed("Apple", "CounterTop")))


def test_a_malformed_cue_file_names_file_and_entry(tmp_path: Path) -> None:
    raw = json.loads(MENTION_CUES_FILE.read_text())
    raw["keep"][0]["side"] = "glowing"        # no such side (the state words are state_words.json)
    bad = tmp_path / "mention_cues.json"
    bad.write_text(json.dumps(raw))
    with pytest.raises(KnowledgeDataError) as err:
        load_mention_cues.__wrapped__(bad)
    assert "mention_cues.json" in str(err.value) and "keep" in str(err.value)
    raw = json.loads(MENTION_CUES_FILE.read_text())
    raw["groups"][0].append("Lampshade")
    bad.write_text(json.dumps(raw))
    with pytest.raises(KnowledgeDataError) as err:
        load_mention_cues.__wrapped__(bad)
    assert "groups" in str(err.value)
