"""The reading-level points of doubt (pfg/offline/doubts: contents, exclusive,
next_place, stated, contradiction; self-corrections are pfg/offline/corrections.py), on sentences written for these
tests: each rule proposes the complete reading its words ask for, and stays silent where
the words do not ask it. Their words are data (doubts/rule_words.json), checked at load."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts import destination
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.rule_words import RULE_WORDS_FILE, RuleWords
from emboteam.pfg.offline.knowledge import KnowledgeDataError
from emboteam.pfg.offline.knowledge import read as read_data
from emboteam.pfg.offline.tagger import tag
from emboteam.pfg.reading import Reading
from emboteam.world.goals import Condition
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

_READER = OfflineFrontend()


def read(text: str, fp: int) -> Reading:
    scene = load_scene(f"FloorPlan{fp}")
    team = parse_team("1,2,3")
    return _READER.parse(text, scene, initial_state({}, scene, team), team)


def first(reading: Reading) -> set[str]:
    return {str(c) for c in reading.candidates[0].goals}


def offered(reading: Reading) -> list[set[str]]:
    return [{str(c) for c in cand.goals} for cand in reading.candidates]


# contents: "everything on X except Y goes in Z" (FloorPlan301: the shelf holds a tissue
# box and a watch; FloorPlan401: the side table a candle, a sponge, paper towels, a spray)
def test_everything_on_a_receptacle_except_one_thing_moves_the_rest_and_keeps_it() -> None:
    goals = first(read("Everything sitting on the shelf goes into the box, apart from the watch.", 301))
    assert "inside(TissueBox, Box)" in goals
    assert "inside(Watch, Box)" not in goals and "inside(Watch, Shelf)" in goals


def test_a_receptacles_contents_are_read_where_the_grammar_finds_nothing() -> None:
    goals = first(read("Everything on the side table except the candle goes onto the shelf.", 401))
    assert {"inside(SprayBottle, Shelf)", "inside(DishSponge, Shelf)", "inside(Candle, SideTable)"} <= goals
    assert "inside(Candle, Shelf)" not in goals


def test_a_chore_followed_by_a_list_is_the_list_not_the_contents() -> None:
    reading = read("Clear the desk: the mug goes on the bed.", 301)
    assert not any(d.kind == "contents" for d in reading.doubts)
    assert "inside(Mug, Bed)" in first(reading)


# exclusive purposes (FloorPlan201: a ceiling light, a desk lamp, a floor lamp, a TV, a laptop)
def test_the_only_light_on_switches_the_others_off() -> None:
    goals = first(read("Movie time: the television should be the only thing that is lit.", 201))
    assert {"switched_on(Television)", "switched_off(FloorLamp)", "switched_off(DeskLamp)",
            "switched_off(LightSwitch)"} <= goals


def test_only_after_a_switching_off_verb_is_restrictive() -> None:
    reading = read("Switch off only the floor lamp, please.", 201)
    assert not any(d.kind == "exclusive" for d in reading.doubts)
    assert "switched_off(FloorLamp)" in first(reading)


# next_place: where a thing's own words send it (doubts/destination.py)
def _ctx(text: str, fp: int, goals: tuple[str, ...]) -> DoubtContext:
    scene = load_scene(f"FloorPlan{fp}")
    team = parse_team("1,2,3")
    return DoubtContext(items=tag(text), goals=tuple(Condition.parse(g) for g in goals), scene=scene,
                        state=initial_state({}, scene, team))


def test_a_thing_given_another_things_place_gets_the_place_after_it() -> None:
    ctx = _ctx("The keys belong on the bed and the pen lives in the box.", 301,
               ("inside(KeyChain, Bed)", "inside(Pen, Bed)"))
    alts = [{str(c) for c in d.choices[1].add} for d in destination.doubts(ctx)]
    assert alts == [{"inside(Pen, Box)"}]


def test_where_a_thing_lies_is_not_where_it_goes() -> None:
    ctx = _ctx("The pen lying on the desk goes in the box.", 301, ("inside(Pen, Box)",))
    assert destination.doubts(ctx) == []


def test_a_negated_place_gives_way_to_the_next() -> None:
    ctx = _ctx("Pens don't live on the bed, their home is the box.", 301, ())
    assert destination.destination(ctx, 0, "Pen")[:1] == ("Box",)


# stated: a narrative says the end state; without one a bare state is a complaint
def test_a_narrative_states_the_end_state() -> None:
    goals = first(read("When I come home tonight the television is on and the laptop is closed.", 201))
    assert "switched_on(Television)" in goals and "switched_off(Television)" not in goals


def test_without_a_narrative_a_state_left_on_is_a_complaint() -> None:
    goals = first(read("The television is still on.", 201))
    assert "switched_off(Television)" in goals


# a self-correction of the thing (pfg/offline/corrections.py): the rejected side
def test_a_corrected_thing_replaces_the_rejected_one_which_stays() -> None:
    reading = read("Put the pencil - no, sorry, the pen, the pencil stays - in the box.", 301)
    assert any({"inside(Pen, Box)", "inside(Pencil, Desk)"} <= g and "inside(Pencil, Box)" not in g
               for g in offered(reading))


# contradiction: a self-correction or a condition settles two opposed requests
def test_a_corrected_switch_is_the_later_request_not_a_contradiction() -> None:
    # (read by the self-correction's slot, pfg/offline/corrections.py, before any
    # contradiction is found: the earlier request is called back)
    reading = read("Switch the floor lamp off - sorry, I mean leave it on.", 201)
    assert "switched_on(FloorLamp)" in first(reading) and "switched_off(FloorLamp)" not in first(reading)


# the data file
def _broken(tmp_path: Path, edit: dict[str, object], section: str) -> Path:
    raw = json.loads(RULE_WORDS_FILE.read_text())
    raw[section] |= edit
    path = tmp_path / "rule_words.json"
    path.write_text(json.dumps(raw))
    return path


def test_an_unknown_device_type_names_the_file_and_entry(tmp_path: Path) -> None:
    with pytest.raises(KnowledgeDataError, match=r"rule_words\.json.*lights"):
        read_data(_broken(tmp_path, {"lights": ["LightSwitch", "Lampp"]}, "exclusive"), RuleWords)


def test_a_misspelt_field_is_an_error_not_ignored(tmp_path: Path) -> None:
    with pytest.raises(KnowledgeDataError, match=r"rule_words\.json"):
        read_data(_broken(tmp_path, {"quantifers": ["everything"]}, "contents"), RuleWords)


def test_a_phrase_list_built_for_one_search_is_never_taken_for_an_earlier_one() -> None:
    # lists built for a call are freed after it and their id() reused by the next list: a
    # search once found the earlier list's phrases, so readings depended on what ran before
    from emboteam.pfg.offline.doubts.rule_words import find

    items = tag("the lamp stays on")
    assert find(items, 0, len(items), [["lamp"]]) == [(1, 2)]
    assert find(items, 0, len(items), [["stays"]]) == [(2, 3)]
    assert find(items, 0, len(items), [["on"], ["the"]]) == [(0, 1), (3, 4)]
