"""The kept_place point of doubt (issue 25, candidate recall): a thing the reading acts on
(lit, shut) but gives no place may be asked to keep its place or to go to one its words
name; the alternative is a candidate beside the reading as read."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline.doubts import destination
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.kept_place import KIND, KeptPlaceCues, load_kept_place
from emboteam.pfg.offline.knowledge import KnowledgeDataError
from emboteam.pfg.offline.knowledge import read as read_knowledge
from emboteam.pfg.offline.tagger import tag
from emboteam.world.goals import Condition
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from test_offline_reading import goal, read


def _alternatives(text: str, fp: int) -> list[set[str]]:
    reading = read(text, fp)
    return [{str(c) for c in cand.goals} for cand in reading.candidates]


def _kept_doubts(text: str, fp: int) -> list[str]:
    return [str(c) for d in read(text, fp).doubts if d.kind == KIND for ch in d.choices for c in ch.add]


@pytest.mark.parametrize(("text", "fp", "place"), [
    # a keep cue after the thing: its start place (FloorPlan427: the candle on the counter)
    ("Light the candle, but it stays where it is.", 427, "inside(Candle, CounterTop)"),
    ("Please light the candle and then leave it alone.", 427, "inside(Candle, CounterTop)"),
    ("Light the candle and then it remains where it is.", 427, "inside(Candle, CounterTop)"),
])
def test_an_acted_thing_may_keep_its_place(text: str, fp: int, place: str) -> None:
    assert "switched_on(Candle)" in goal(read(text, fp))
    assert _kept_doubts(text, fp) == [place]
    readings = _alternatives(text, fp)
    # both readings are candidates: the act alone, and the act with the place kept
    assert {"switched_on(Candle)"} in readings
    assert {"switched_on(Candle)", place} in readings


def test_a_thing_with_a_place_is_no_doubt() -> None:
    assert _kept_doubts("Put the candle in the cabinet and light it.", 427) == []


def test_a_thing_nothing_acts_on_is_no_doubt() -> None:
    # no act read, no state said, no landmark, no keep: nothing to keep
    assert _kept_doubts("Put the soap bar in the cabinet, then light the candle.", 427) == []


def test_a_landmark_keeps_its_place() -> None:
    # the candle is a landmark (keepall25): where it stands is a condition, never an act
    assert _kept_doubts("Put the soap bar next to the candle.", 427) == ["inside(Candle, CounterTop)"]


def test_the_cue_file_is_checked_at_load(tmp_path: Path) -> None:
    assert load_kept_place().keep_after
    bad = tmp_path / "kept_place.json"
    bad.write_text(json.dumps({"keep_after": [["stays"]], "place_preps": [], "reach": 8}), encoding="utf-8")
    with pytest.raises(KnowledgeDataError):
        read_knowledge(bad, KeptPlaceCues)


def test_a_carried_thing_its_words_keep_is_put_down_where_it_is() -> None:
    # FloorPlan211: the keys lie on a shelf; "hold" reads them carried, "leave them where
    # they are" keeps them: the alternative puts them down there instead of carrying them
    text = "Hold the keys, then leave them where they are."
    doubt = next(d for d in read(text, 211).doubts if d.kind == KIND)
    assert [str(c) for c in doubt.choices[1].drop] == ["held(KeyChain)"]
    assert [str(c) for c in doubt.choices[1].add] == ["inside(KeyChain, Shelf)"]
    assert {"inside(KeyChain, Shelf)"} in _alternatives(text, 211)


def _ctx(text: str, fp: int, goals: tuple[str, ...]) -> DoubtContext:
    scene = load_scene(f"FloorPlan{fp}")
    return DoubtContext(items=tag(text), goals=tuple(Condition.parse(g) for g in goals), scene=scene,
                        state=initial_state({}, scene, parse_team("1,2,3")))


def test_a_placed_and_lit_thing_sent_elsewhere_keeps_its_state() -> None:
    # next_place: a thing the reading placed and lit, sent elsewhere by its words: only its
    # place is replaced, the state read beside it stays
    # (FloorPlan427: the candle on the counter)
    ctx = _ctx("Light the candle and put it onto the toilet.", 427,
               ("inside(Candle, Cabinet)", "switched_on(Candle)"))
    doubt = next(d for d in destination.doubts(ctx) if d.span == "candle")
    assert [str(c) for c in doubt.choices[1].drop] == ["inside(Candle, Cabinet)"]
    assert [str(c) for c in doubt.choices[1].add] == ["inside(Candle, Toilet)"]
