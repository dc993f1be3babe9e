"""Candidates the scene allows beside the reading as read (doubts/switches.py,
doubts/placed_instead.py): a device the words name without a switch goal, or its knob,
may be switched; a switch goal may have been read the wrong way round; a carried thing read
as held or switched may be placed where the words point. A word that is also a verb names
a thing after a determiner (doubts/context.py). The reading as read stays first.
Sentences written for this test (not round tasks)."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.priors import load_priors
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


def _goal_sets(reading: Reading) -> list[set[str]]:
    return [{str(c) for c in cand.goals} for cand in reading.candidates]


def test_a_burner_named_with_no_switch_offers_its_knob_on(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "the pan on the front burner with the flame going, and the apple in the fridge",
                    "FloorPlan5")
    first = {str(c) for c in reading.spec.goal().conditions}
    assert first == {"inside(Pan, StoveBurner)", "inside(Apple, Fridge)"}    # as read, first
    assert first | {"switched_on(StoveKnob)"} in _goal_sets(reading)


def test_a_switch_read_the_wrong_way_round_is_a_candidate_not_the_reading(frontend: OfflineFrontend) -> None:
    # the floor lamp is on at the start: read as "on", its other way (off) asks for a change
    reading = _read(frontend, "floor lamp on, keychain in the box", "FloorPlan205")
    assert {str(c) for c in reading.spec.goal().conditions} == {"switched_on(FloorLamp)", "inside(KeyChain, Box)"}
    assert {"switched_off(FloorLamp)", "inside(KeyChain, Box)"} in _goal_sets(reading)


def test_a_switch_is_not_flipped_to_the_state_it_is_in(frontend: OfflineFrontend) -> None:
    """"Still on" says what is: the lamp on is no request, so no candidate asks for it."""
    reading = _read(frontend, "why is the floor lamp still on? put the keychain in the box", "FloorPlan205")
    assert {str(c) for c in reading.spec.goal().conditions} == {"switched_off(FloorLamp)", "inside(KeyChain, Box)"}
    assert not any("switched_on(FloorLamp)" in goals for goals in _goal_sets(reading))


def test_the_switch_doubt_has_its_priors_and_they_keep_the_reading_first() -> None:
    table = load_priors().priors["switch"]
    assert table["as_read"] > max(table["flip"], table["mentioned"])


def test_a_carried_thing_read_as_switched_may_be_placed_where_the_words_point(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "laptop closed, desk lamp switched off, the phone charging on the desk", "FloorPlan311")
    assert any("inside(CellPhone, Desk)" in goals for goals in _goal_sets(reading))


@pytest.mark.parametrize(("text", "floor_plan", "thing"), [
    ("the spare roll, put it on the counter please", "FloorPlan410", "ToiletPaper"),
    ("my watch and the keys sleep in the drawer", "FloorPlan205", "Watch"),
])
def test_a_word_that_is_also_a_verb_names_a_thing_after_a_determiner(text: str, floor_plan: str, thing: str) -> None:
    scene = load_scene(floor_plan)
    team = parse_team("1,2,3")
    ctx = DoubtContext(items=tag(text), goals=(), scene=scene, state=WorldState.from_scene(scene, team))
    assert any(thing in types for _, _, types in ctx.mentions())


def test_a_verb_with_no_determiner_names_no_thing() -> None:
    scene = load_scene("FloorPlan205")
    team = parse_team("1,2,3")
    ctx = DoubtContext(items=tag("watch the television"), goals=(), scene=scene,
                       state=WorldState.from_scene(scene, team))
    assert not any("Watch" in types for _, _, types in ctx.mentions())
