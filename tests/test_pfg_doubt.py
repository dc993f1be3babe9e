"""The doubt detector (emboteam.pfg.doubt): what --llm-when doubt asks the model on. Its
weights are fitted on development rounds (benchmarks/fit_doubt.py); these tests hold the
properties a user relies on, not the weights."""

from __future__ import annotations

from emboteam.pfg.doubt import doubt_features, doubt_score, flags, needs_review
from emboteam.pfg.reading import Reading, ReadingNote
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Condition
from emboteam.world.state import WorldState


def reading(instruction: str, *conditions: str, notes: tuple[ReadingNote, ...] = ()) -> Reading:
    spec = TaskSpec.model_validate({"instruction": instruction, "subtasks": [
        {"id": f"s{i}", "description": c, "goal": [Condition.parse(c)]} for i, c in enumerate(conditions, 1)]})
    return Reading(spec=spec, notes=notes)


def test_a_plain_reading_of_a_plain_request_is_trusted(state1: WorldState) -> None:
    text = "Put the apple in the fridge."
    assert not needs_review(reading(text, "inside(Apple, Fridge)"), text, state1)


def test_a_failed_parse_is_always_flagged(state1: WorldState) -> None:
    features = doubt_features(None, "Ooh, is the match on yet?", state1, error="OfflineParseError: vague")
    assert flags(features) == {"notes": True, "detector": True}


def test_a_long_request_read_as_one_condition_is_flagged_without_any_note(state1: WorldState) -> None:
    text = ("For tea tonight I'd like the potato off the table cut up and a slice of it frying in the pan "
            "that's already on the stove, and do make sure the ring under it's on once the slice is in.")
    read = reading(text, "inside(PotatoSliced, Pan)")
    assert not read.doubtful  # the parser's own notes would not ask
    assert needs_review(read, text, state1)


def test_each_unexplained_scene_noun_adds_doubt(state1: WorldState) -> None:
    text = "Put the apple in the fridge and the tomato in the sink."
    partial = doubt_features(reading(text, "inside(Apple, Fridge)"), text, state1)
    full = doubt_features(reading(text, "inside(Apple, Fridge)", "inside(Tomato, Sink)"), text, state1)
    assert partial["unexplained"] == ["sink", "tomato"] and full["unexplained"] == []
    assert doubt_score(partial) > doubt_score(full)


def test_instruments_and_notes(state1: WorldState) -> None:
    text = "Slice the bread with the knife."
    plain = doubt_features(reading(text, "sliced(Bread)"), text, state1)
    assert plain["unexplained"] == []  # the knife is what slicing uses, not a forgotten goal
    noted = doubt_features(reading(text, "sliced(Bread)", notes=(ReadingNote("x", "unread"),) * 3), text, state1)
    assert doubt_score(noted) > doubt_score(plain)
