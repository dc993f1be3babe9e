"""The offline parser degrades instead of failing (docs/offline_parser.md, "Reading"): what
it cannot read becomes a note and the rest is acted on; contradictions are a typed error;
time adjuncts and rejected alternatives are read by structure; the reading says which
conditions it chose with doubt."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from emboteam.pfg.offline import GroundingError, OfflineFrontend, OfflineParseError
from emboteam.pfg.offline.consistency import ContradictoryInstruction
from emboteam.pfg.offline.evaluate import evaluate, initial_state, load_records
from emboteam.pfg.reading import Reading
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

FRONTEND = OfflineFrontend()
DATA = Path(__file__).parent / "data"


def read(text: str, fp: int = 1, setup: list[dict[str, Any]] | None = None) -> Reading:
    scene = load_scene(fp)
    team = parse_team("1,2")
    return FRONTEND.parse(text, scene, initial_state({"setup": setup or []}, scene, team), team)


def goal(reading: Reading) -> set[str]:
    return {str(c) for c in reading.spec.goal().conditions}


@pytest.mark.parametrize(("text", "fp", "expected", "span"), [
    ("Put the apple in the frobnicator and the tomato in the fridge.", 1,
     {"inside(Tomato, Fridge)"}, "frobnicator"),
    ("Put the apple in the fridge and the xylophone on the counter.", 1,
     {"inside(Apple, Fridge)"}, "xylophone"),
    ("Put the apple in the fridge. Then wibble the tomato.", 1,
     {"inside(Apple, Fridge)"}, "wibble the tomato"),
])
def test_an_unreadable_part_is_a_note_and_the_rest_is_acted_on(
        text: str, fp: int, expected: set[str], span: str) -> None:
    reading = read(text, fp)
    assert goal(reading) == expected
    assert [n.span for n in reading.notes] == [span]
    assert reading.notes[0].reason and reading.doubtful


@pytest.mark.parametrize(("text", "fp", "expected", "span"), [
    ("I reckon you should chuck the egg in the bin.", 1, {"inside(Egg, GarbageCan)"},
     "i reckon you should"),
    ("Swap the TV off.", 201, {"switched_off(Television)"}, "swap"),
    ("No rush, but the potato should be cooked.", 1, {"cooked(Potato)"}, "no rush but"),
])
def test_words_before_what_can_be_read_are_a_note_and_the_reading_is_unsure(
        text: str, fp: int, expected: set[str], span: str) -> None:
    reading = read(text, fp)
    assert goal(reading) == expected
    assert [n.span for n in reading.notes] == [span]
    assert set(reading.unsure) == expected


def test_an_instruction_with_nothing_readable_is_still_an_error() -> None:
    with pytest.raises(GroundingError, match="frobnicator"):
        read("put the apple in the frobnicator")
    with pytest.raises(OfflineParseError):
        read("wibble wobble")


@pytest.mark.parametrize(("text", "fp"), [
    ("Open and close the fridge.", 1),
    ("Turn on and turn off the TV.", 201),
    ("Switch the lamp on and off.", 303),
    ("Switch on the coffee machine and switch it off.", 6),
])
def test_a_contradiction_is_a_typed_error_naming_both_readings(text: str, fp: int) -> None:
    with pytest.raises(ContradictoryInstruction) as err:
        read(text, fp)
    first, second = err.value.readings
    assert first != second
    assert first in str(err.value) and second in str(err.value)


@pytest.mark.parametrize(("text", "expected"), [
    ("First open the fridge, then take out the apple, and finally close the fridge.",
     {"held(Apple)", "closed(Fridge)"}),
    ("Turn off the light, then turn it back on.", {"switched_on(LightSwitch)"}),
    ("Open the microwave and then shut the microwave.", {"closed(Microwave)"}),
    ("Cook the potato in the microwave and switch the microwave off when it's done.",
     {"cooked(Potato)", "switched_off(Microwave)"}),
])
def test_a_sequence_of_opposite_states_is_no_contradiction(text: str, expected: set[str]) -> None:
    assert goal(read(text)) == expected


def test_a_complaint_about_states_asks_for_the_opposite() -> None:
    reading = read("The fridge is wide open and the light is still on, sort it out.", 1,
                   [{"object": "Fridge_1", "is_open": True}])
    assert goal(reading) == {"closed(Fridge)", "switched_off(LightSwitch)"}


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Put the tomato in the fridge, not the apple.", 1, {"inside(Tomato, Fridge)"}),
    ("Put the tomato, not the apple, in the fridge.", 1, {"inside(Tomato, Fridge)"}),
    ("Grab the mug, not the cup, and put it in the sink.", 1, {"inside(Mug, SinkBasin)"}),
    ("Put the mug instead of the cup in the sink.", 1, {"inside(Mug, SinkBasin)"}),
    ("Put the pen and the pencil in the drawer, but not the CD.", 303,
     {"inside(Pen, Drawer)", "inside(Pencil, Drawer)"}),
])
def test_a_rejected_alternative_is_neither_object_nor_antecedent(
        text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


@pytest.mark.parametrize(("text", "expected"), [
    ("Could you pop the apple in the fridge for me tonight?", {"inside(Apple, Fridge)"}),
    ("Put the apple in the fridge before lunch and the tomato in the microwave after dinner.",
     {"inside(Apple, Fridge)", "inside(Tomato, Microwave)"}),
    ("Slice the bread by noon, please.", {"sliced(Bread)"}),
    ("Later tonight, could you slice the tomato?", {"sliced(Tomato)"}),
])
def test_time_adjuncts_say_when_not_what(text: str, expected: set[str]) -> None:
    reading = read(text)
    assert goal(reading) == expected and reading.notes == ()


def test_a_duration_is_kept() -> None:
    spec = read("Microwave the potato for two minutes.").spec
    assert "hot(Potato)" in {str(c) for c in spec.goal().conditions}


def test_fillers_before_the_verb_and_a_leading_also() -> None:
    assert goal(read("Could you, um, maybe throw the CD in the bin?", 303)) == {
        "inside(CD, GarbageCan)"}
    assert goal(read("Put the soap bar in the sink. After that, also the candle.", 414)) == {
        "inside(SoapBar, SinkBasin)", "inside(Candle, SinkBasin)"}


def test_a_list_item_with_its_own_place_is_a_placement() -> None:
    reading = read("I need three things: the apple in the fridge, the bread sliced and the light off.")
    assert goal(reading) == {"inside(Apple, Fridge)", "sliced(Bread)", "switched_off(LightSwitch)"}


def test_a_clear_reading_is_sure_and_a_fallback_choice_is_unsure() -> None:
    sure = read("Put the apple in the fridge.")
    assert sure.unsure == () and not sure.doubtful
    # FloorPlan1 has no dining table: "the table" falls back to the counter, a default the
    # hybrid front end should have checked
    unsure = read("Put the mug on the table and the apple in the fridge.")
    assert goal(unsure) == {"inside(Mug, CounterTop)", "inside(Apple, Fridge)"}
    assert unsure.unsure == ("inside(Mug, CounterTop)",) and unsure.doubtful


def test_the_natural_development_set_stays_read() -> None:
    """tests/data/offline_dev_natural.jsonl (written before the parser was changed for it,
    docs/unseen_suite.md): at least 90 % of its goals read exactly."""
    outcomes = evaluate(load_records(DATA / "offline_dev_natural.jsonl"))
    assert sum(o.correct for o in outcomes) / len(outcomes) >= 0.9, json.dumps(
        [o.id for o in outcomes if not o.correct])


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Nobody closed the fridge.", 1, {"closed(Fridge)"}),
    ("No one turned off the light.", 1, {"switched_off(LightSwitch)"}),
    ("The bread isn't sliced yet.", 1, {"sliced(Bread)"}),
    ("Why is the fridge open?", 1, {"closed(Fridge)"}),
    ("Nobody is watching the TV.", 201, {"switched_off(Television)"}),
])
def test_a_complaint_about_what_was_not_done_asks_for_it(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_an_unreadable_object_of_a_state_list_does_not_sink_the_others() -> None:
    reading = read("Ugh, the light is on again.")
    assert goal(reading) == {"switched_off(LightSwitch)"}
    assert [n.span for n in reading.notes] == ["ugh"]


def test_except_rejects_and_a_bare_topic_is_no_note() -> None:
    with pytest.raises(GroundingError):        # "everything" alone is too vague, never the apple
        read("Put everything except the apple in the fridge.")
    reading = read("The bread. Slice it, please.")
    assert goal(reading) == {"sliced(Bread)"} and reading.notes == ()


def test_a_new_sentence_is_a_new_request_not_a_contradiction() -> None:
    assert goal(read("Hmm, the floor lamp's off. Turn it on please.", 201)) == {"switched_on(FloorLamp)"}


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Not the pen - the pencil goes in the drawer.", 303, {"inside(Pencil, Drawer)"}),
    ("Don't forget the TV is still on.", 201, {"switched_off(Television)"}),
    ("Don't forget to turn off the light.", 1, {"switched_off(LightSwitch)"}),
    ("The faucet's dripping, turn it off.", 414, {"switched_off(Faucet)"}),
])
def test_a_rejected_topic_a_reminder_and_a_contracted_is(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_a_yes_no_question_names_the_referent_of_a_later_pronoun() -> None:
    reading = read("Is the laptop still open? Close it if so.", 201)
    assert goal(reading) == {"closed(Laptop)"} and reading.notes == ()


@pytest.mark.parametrize(("text", "expected"), [
    ("Put the apple in the fridge, then the tomato.", {"inside(Apple, Fridge)", "inside(Tomato, Fridge)"}),
    ("Put the apple in the fridge. Then the tomato.", {"inside(Apple, Fridge)", "inside(Tomato, Fridge)"}),
    ("Get the fridge closed and the light switched off.", {"closed(Fridge)", "switched_off(LightSwitch)"}),
])
def test_gapped_objects_and_a_state_per_object(text: str, expected: set[str]) -> None:
    assert goal(read(text)) == expected


def test_mace_thor_goals_read_exactly_do_not_regress() -> None:
    """The degrade rules must not cost the benchmark: at least 32 of MACE-THOR's 42 goals
    are read exactly (30 before round 3; "the remote, my watch and my keys keep going
    missing" is a statement naming objects, not a clause to reread without them)."""
    from emboteam.bench.suites import load_suite
    from emboteam.errors import EmboTeamError
    from emboteam.pfg.offline.evaluate import goal_keys

    exact = 0
    for task in load_suite("mace-thor").tasks:
        state, team = task.initial_state(), task.team()
        scene = load_scene(task.floor_plan)
        try:
            spec = FRONTEND.decompose(task.instruction, scene, state, team)
        except EmboTeamError:
            continue
        exact += goal_keys(spec.goal().conditions, scene) == goal_keys(task.goal.conditions, scene)
    assert exact >= 32


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Someone left the light on all night.", 11, {"switched_off(LightSwitch)"}),
    ("The TV has been on all day, turn it off will you.", 201, {"switched_off(Television)"}),
    ("Please make sure the fridge and the microwave are both closed.", 4,
     {"closed(Fridge)", "closed(Microwave)"}),
])
def test_a_time_adjunct_keeps_the_particle_and_a_wish_covers_its_coordinated_subjects(
        text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_by_an_object_is_beside_it() -> None:
    assert goal(read("Put the remote by the TV.", 201)) == {"inside(RemoteControl, TVStand)"}
    assert goal(read("By the way, slice the bread.")) == {"sliced(Bread)"}
