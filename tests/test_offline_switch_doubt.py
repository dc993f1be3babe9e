"""The switch doubt (doubts/switches.py): a device the words name without a switch goal,
or its knob, may be switched; a switch goal may have been read the wrong way round. Both
only add candidates: the reading as read stays first. Sentences written for this test
(not round tasks)."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.priors import load_priors
from emboteam.pfg.reading import Reading
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


@pytest.fixture(scope="module")
def frontend() -> OfflineFrontend:
    return OfflineFrontend()


def _read(frontend: OfflineFrontend, text: str, floor_plan: str) -> Reading:
    scene = load_scene(floor_plan)
    team = parse_team("1,2,3")
    return frontend.parse(text, scene, WorldState.from_scene(scene, team), team)


def _goal_sets(reading: Reading) -> list[set[str]]:
    return [{str(c) for c in cand.goals} for cand in reading.candidates]


def test_a_burner_named_with_no_switch_offers_its_knob_on(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "the pan on the front burner with the flame going, and the apple in the fridge",
                    "FloorPlan5")
    first = {str(c) for c in reading.spec.goal().conditions}
    assert first == {"inside(Pan, StoveBurner)", "inside(Apple, Fridge)"}    # as read, first
    assert first | {"switched_on(StoveKnob)"} in _goal_sets(reading)


def test_a_switch_read_the_wrong_way_round_is_a_candidate_not_the_reading(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "why is the floor lamp still on? put the keychain in the box", "FloorPlan205")
    assert {str(c) for c in reading.spec.goal().conditions} == {"switched_off(FloorLamp)", "inside(KeyChain, Box)"}
    assert {"switched_on(FloorLamp)", "inside(KeyChain, Box)"} in _goal_sets(reading)


def test_the_switch_doubt_has_its_priors_and_they_keep_the_reading_first() -> None:
    table = load_priors().priors["switch"]
    assert table["as_read"] > max(table["flip"], table["mentioned"])
