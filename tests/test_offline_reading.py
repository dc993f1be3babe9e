"""The offline parser degrades instead of failing (docs/offline_parser.md, "Reading"): what
it cannot read becomes a note and the rest is acted on; contradictions are a typed error;
time adjuncts and rejected alternatives are read by structure; the reading says which
conditions it chose with doubt."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from emboteam.bench.offline_accuracy import evaluate, initial_state, load_records
from emboteam.pfg.offline import GroundingError, OfflineFrontend, OfflineParseError
from emboteam.pfg.offline.consistency import ContradictoryInstruction
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
    reading = read("Blargh, the light is on again.")
    assert goal(reading) == {"switched_off(LightSwitch)"}
    assert [n.span for n in reading.notes] == ["blargh"]


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
    from emboteam.bench.offline_accuracy import goal_keys
    from emboteam.bench.suites import load_suite
    from emboteam.errors import EmboTeamError

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


@pytest.mark.parametrize(("text", "expected"), [
    ("If the fridge is open, close it.", {"closed(Fridge)"}),
    ("Close the fridge if it's open.", {"closed(Fridge)"}),
    ("If the light is on, switch it off.", {"switched_off(LightSwitch)"}),
    ("I'd appreciate it if the fridge were closed.", {"closed(Fridge)"}),
])
def test_a_state_under_if_is_the_condition_of_the_act_not_a_goal(text: str, expected: set[str]) -> None:
    reading = read(text)
    assert goal(reading) == expected and reading.notes == ()


def test_a_circumstance_without_objects_is_no_note() -> None:
    reading = read("If you have time, put the apple in the fridge.")
    assert goal(reading) == {"inside(Apple, Fridge)"} and reading.notes == ()


def test_a_question_names_what_a_later_pronoun_switches() -> None:
    assert goal(read("Is the stove on? Turn it off if so.")) == {"switched_off(StoveKnob)"}


def test_a_clause_the_grammar_cannot_read_is_read_from_its_cue_words_and_marked_unsure() -> None:
    # ("I just need the pan in the sink" is read by the grammar since round 35)
    reading = read("Leave everything else, the pan might as well live in the sink.")
    assert goal(reading) == {"inside(Pan, SinkBasin)"}
    assert reading.unsure == ("inside(Pan, SinkBasin)",)
    assert [n.kind for n in reading.notes] == ["assumed"]


def test_cue_reading_never_acts_on_an_excluded_object() -> None:
    with pytest.raises(GroundingError):
        read("Put everything except the apple in the fridge.")


def test_the_last_word_of_a_compound_name_names_its_type() -> None:
    assert goal(read("Put the mug in the coffee machine and switch the machine on.")) == {
        "inside(Mug, CoffeeMachine)", "switched_on(CoffeeMachine)"}


@pytest.mark.parametrize(("text", "expected"), [
    ("Chuck the apple in the fridge.", {"inside(Apple, Fridge)"}),
    ("Throw away the apple in the sink.", {"inside(Apple, GarbageCan)"}),
    ("Chuck the apple.", {"inside(Apple, GarbageCan)"}),
])
def test_a_throwing_verb_with_a_place_puts_it_there(text: str, expected: set[str]) -> None:
    assert goal(read(text)) == expected


@pytest.mark.parametrize(("text", "expected"), [
    ("I'd love it if the fridge were shut and the apple were on the counter when I get home.",
     {"closed(Fridge)", "inside(Apple, CounterTop)"}),
    ("When I come back I want the light off.", {"switched_off(LightSwitch)"}),
    ("Before you go put the apple in the fridge.", {"inside(Apple, Fridge)"}),
    ("After you slice the bread put it on a plate.", {"sliced(Bread)", "inside(Bread, Plate)"}),
])
def test_a_persons_own_doings_under_a_subordinator_are_a_time(text: str, expected: set[str]) -> None:
    reading = read(text)
    assert goal(reading) == expected and reading.notes == ()


def test_a_causative_with_a_participle_asks_for_the_participles_act() -> None:
    assert goal(read("Pot on the stove, get it heating.")) == {"inside(Pot, StoveBurner)", "hot(Pot)"}


def test_ordinals_number_the_steps_of_a_list() -> None:
    assert goal(read("First open the fridge, second take out the egg, third close the fridge again.")) \
        == {"held(Egg)", "closed(Fridge)"}
    assert goal(read("Slice the bread and put the first slice in the toaster.")) == {
        "sliced(Bread)", "inside(BreadSliced, Toaster)"}


def test_a_list_of_noun_phrases_names_each_for_a_later_pronoun() -> None:
    assert goal(read("Keys, watch and the credit card - pop all three in the box.", 201)) == {
        "inside(KeyChain, Box)", "inside(Watch, Box)", "inside(CreditCard, Box)"}


def test_holding_on_the_way_to_a_place_is_no_subtask() -> None:
    reading = read("Take the apple and the tomato out of the fridge and put them on the counter.")
    assert goal(reading) == {"inside(Apple, CounterTop)", "inside(Tomato, CounterTop)"}
    assert len(reading.spec.subtasks) == 2 and all(s.final for s in reading.spec.subtasks)


@pytest.mark.parametrize("text", ["There's no toilet paper on the holder.",
                                  "We're out of loo roll on the holder - there's one on the shelf."])
def test_something_missing_from_its_place_asks_to_put_it_there(text: str) -> None:
    assert goal(read(text, 414)) == {"inside(ToiletPaper, ToiletPaperHanger)"}


def test_a_sentence_adverb_after_but_does_not_hide_the_next_clause() -> None:
    assert goal(read("Put the apple in the fridge, but honestly the tomato should go in the bowl.")) == {
        "inside(Apple, Fridge)", "inside(Tomato, Bowl)"}


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Bed: pillow and phone. Desk: book and laptop.", 303,
     {"inside(Pillow, Bed)", "inside(CellPhone, Bed)", "inside(Book, Desk)", "inside(Laptop, Desk)"}),
    ("Things for the box: the pen, the pencil and the book.", 201,
     {"inside(Pen, Box)", "inside(Pencil, Box)", "inside(Book, Box)"}),
])
def test_a_place_before_a_colon_labels_the_objects_after_it(text: str, fp: int, expected: set[str]) -> None:
    reading = read(text, fp)
    assert goal(reading) == expected and reading.notes == ()


@pytest.mark.parametrize(("text", "expected"), [
    ("If you could get a potato cooked and onto a plate that'd be amazing.",
     {"cooked(Potato)", "inside(Potato, Plate)"}),
    ("Get the bread sliced and the egg into the fridge.", {"sliced(Bread)", "inside(Egg, Fridge)"}),
])
def test_a_state_and_a_place_each_go_to_their_own_objects(text: str, expected: set[str]) -> None:
    assert goal(read(text)) == expected


def test_where_something_is_said_to_be_is_no_request() -> None:
    reading = read("Make me a coffee, the mug's in one of the cupboards I think.")
    assert goal(reading) == {"filled(Mug, coffee)", "hot(Mug)"}
    with pytest.raises(OfflineParseError):
        read("The mug's in one of the cupboards, I think.")


@pytest.mark.parametrize(("text", "expected"), [
    ("Turn every light off except the desk lamp.", {"switched_off(LightSwitch)"}),
    ("Put all the vegetables except the potato in the fridge.",
     {"inside(Lettuce, Fridge)", "inside(Tomato, Fridge)"}),
])
def test_except_leaves_its_objects_out_of_a_quantified_phrase(text: str, expected: set[str]) -> None:
    fp = 303 if "lamp" in text else 1
    assert goal(read(text, fp)) == expected


def test_nothing_left_after_except_is_an_error_not_the_left_out_object() -> None:
    with pytest.raises(OfflineParseError):
        read("Put all the fruit except the apple in the fridge.")


@pytest.mark.parametrize("text", ["Put the apple in the fridge. Cheers love", "Put the apple in the fridge, love you!"])
def test_small_talk_is_no_note(text: str) -> None:
    reading = read(text)
    assert goal(reading) == {"inside(Apple, Fridge)"} and reading.notes == ()


def test_a_real_word_is_no_typo_outside_the_places_lexicon_words_stand() -> None:
    assert goal(read("I keep losing my keys. Put them in the box.", 201)) == {"inside(KeyChain, Box)"}
    assert goal(read("Then slcie the bread.")) == {"sliced(Bread)"}    # typos are still corrected


def test_a_participle_clause_asks_its_state_of_the_objects_before_it() -> None:
    assert goal(read("I'd like my mug washed and then filled with water.")) == {"clean(Mug)", "filled(Mug, water)"}


def test_a_stranded_preposition_points_at_the_place_just_mentioned() -> None:
    assert goal(read("Open a drawer, put the keychain and the credit card in, and close it.", 303)) == {
        "inside(KeyChain, Drawer)", "inside(CreditCard, Drawer)", "closed(Drawer)"}


def test_a_pointing_question_describes_and_its_pronoun_is_the_thing_not_the_landmark() -> None:
    reading = read("See the box on the coffee table? Put the watch and the keys in it.", 201)
    assert goal(reading) == {"inside(Watch, Box)", "inside(KeyChain, Box)"} and reading.notes == ()


def test_numbered_items_after_a_colon_are_each_a_request() -> None:
    reading = read("Three things: 1) the apple goes in the fridge, 2) the mug onto the counter, "
                   "3) switch the light off.")
    assert goal(reading) == {"inside(Apple, Fridge)", "inside(Mug, CounterTop)", "switched_off(LightSwitch)"}


def test_pieces_of_a_pronoun_are_pieces_of_its_antecedent() -> None:
    assert goal(read("Cut the lettuce up and put two pieces of it in the bowl.")) == {
        "sliced(Lettuce)", "inside(2 of LettuceSliced, Bowl)"}


@pytest.mark.parametrize(("text", "expected"), [
    ("The kettle is empty. Fill it at the sink, then put it on the stove and boil it.",
     {"filled(Kettle, water)", "inside(Kettle, StoveBurner)", "hot(Kettle)"}),
    ("Put the egg in the pot and boil it.", {"inside(Egg, Pot)", "cooked(Egg)"}),
])
def test_boiling_it_heats_water_in_a_vessel_and_cooks_food(text: str, expected: set[str]) -> None:
    assert goal(read(text)) == expected


def test_a_where_question_names_the_antecedent_of_later_pronouns() -> None:
    assert goal(read("Where's the pot? Oh right, it's in a cupboard. Get it out and put it on the stove.")) \
        == {"inside(Pot, StoveBurner)"}


@pytest.mark.parametrize(("text", "expected"), [
    ("Fill the kettle at the sink and put it on the stove to boil.",
     {"filled(Kettle, water)", "inside(Kettle, StoveBurner)", "hot(Kettle)"}),
    ("Put the potato in the microwave to heat it up.", {"inside(Potato, Microwave)", "hot(Potato)"}),
    ("Leave the mug in the sink to soak.", {"inside(Mug, SinkBasin)"}),
])
def test_a_purpose_infinitive_asks_its_act_of_what_was_placed(text: str, expected: set[str]) -> None:
    assert goal(read(text)) == expected


def test_a_guess_where_something_is_is_no_request() -> None:
    reading = read("I fancy a coffee. The mug should be in a cabinet somewhere.")
    assert goal(reading) == {"filled(Mug, coffee)", "hot(Mug)"}
    assert goal(read("The mug should be in the cabinet.")) == {"inside(Mug, Cabinet)"}


def test_a_fresh_one_is_another_instance_than_the_one_singled_out() -> None:
    reading = read("The loo roll on the floor should go in the bin and a fresh one on the holder.", 403)
    held = {c.subject.id for c in reading.spec.goal().conditions}
    assert len(held) == 2 and None not in held


def test_an_object_placed_twice_ends_where_it_is_placed_last() -> None:
    assert goal(read("Pick the pillow and the newspaper up off the floor - pillow on the sofa, paper on "
                     "the coffee table.", 209)) == {"inside(Pillow, Sofa)", "inside(Newspaper, CoffeeTable)"}
    assert goal(read("Put the potato in the pot. Then put the pot on the stove.")) == {
        "inside(Potato, Pot)", "inside(Pot, StoveBurner)"}       # a pot is no potato


def test_a_misread_object_does_not_stop_the_cue_reading() -> None:
    assert goal(read("Read a book with the lamp on.", 303)) >= {"switched_on(DeskLamp)"}


def test_on_and_off_again_is_a_sequence_ending_off() -> None:
    assert goal(read("Put the mug in the sink, turn the tap on and off again.")) == {
        "inside(Mug, SinkBasin)", "switched_off(Faucet)"}


def test_it_under_when_is_what_goes_in_not_the_place() -> None:
    assert goal(read("The apple goes in the bowl. Put the bowl in the fridge when it's in.")) >= {
        "inside(Apple, Bowl)"}
    assert "inside(Bowl, Bowl)" not in goal(read("The apple goes in the bowl. Close the fridge when it's in."))


def test_the_water_of_a_filled_vessel_is_the_vessel() -> None:
    assert goal(read("Fill the kettle at the sink and stick it on the stove so the water's hot.")) == {
        "filled(Kettle, water)", "inside(Kettle, StoveBurner)", "hot(Kettle)"}


def test_under_the_coffee_maker_is_in_it_and_under_a_table_is_no_goal() -> None:
    assert goal(read("Put the mug under the coffee maker and start it.")) == {
        "inside(Mug, CoffeeMachine)", "switched_on(CoffeeMachine)"}
    with pytest.raises(OfflineParseError):
        read("Put the mug under the table.")


def test_states_listed_before_sort_it_out_are_complaints() -> None:
    reading = read("Someone left the kitchen in a state: fridge door wide open, coffee machine still "
                   "running, light on. Sort it out before bed?")
    assert goal(reading) == {"closed(Fridge)", "switched_off(CoffeeMachine)", "switched_off(LightSwitch)"}
    assert reading.notes == ()


def test_that_before_an_adjective_and_a_noun_is_a_determiner() -> None:
    reading = read("The mug goes on the shelf, the bowl and the cup on the counter, and bin that old egg.")
    assert goal(reading) == {"inside(Mug, Shelf)", "inside(Bowl, CounterTop)", "inside(Cup, CounterTop)",
                             "inside(Egg, GarbageCan)"}


def test_a_real_word_ending_in_s_is_no_typo_either() -> None:
    assert goal(read("Put the keys in the box and close it, so nobody loses them.", 201)) == {
        "inside(KeyChain, Box)", "closed(Box)"}


def test_on_to_before_a_verb_is_the_particle_and_a_purpose() -> None:
    assert goal(read("Put the mug in the sink, turn the tap on to rinse it, then turn off the light.")) >= {
        "inside(Mug, SinkBasin)", "switched_on(Faucet)", "switched_off(LightSwitch)"}


def test_it_on_there_under_once_is_where_it_will_be_not_a_switch() -> None:
    reading = read("Put the pan on the stove. Put the egg in the pan once it's on there.")
    assert goal(reading) == {"inside(Pan, StoveBurner)", "inside(Egg, Pan)"}


def test_in_it_after_opening_a_drawer_is_the_drawer() -> None:
    assert "inside(KeyChain, Drawer)" in goal(read(
        "The pen goes on the desk. Then open a drawer and put the keychain in it.", 303))


def test_sorting_out_the_lamp_puts_it_in_the_other_state() -> None:
    # FloorPlan201's lamps are on at the start: sorting them out switches them off
    assert goal(read("Sort out the lamp, put the remote on the couch.", 201)) == {
        "switched_off(DeskLamp|FloorLamp)", "inside(RemoteControl, Sofa)"}


@pytest.mark.parametrize("text", [
    "Put the pan on the stove. Oh and the tomato that's sitting in the sink, that wants to go in the pan.",
    "Put the pan on the stove. The tomato that was left in the sink needs to go in the pan.",
])
def test_a_be_inside_a_relative_clause_makes_no_statement(text: str) -> None:
    # "that's sitting in the sink" only says which tomato: the clause is a wish, not a
    # description of the room, so it is read (or, failing that, noted), never dropped
    assert goal(read(text)) == {"inside(Pan, StoveBurner)", "inside(Tomato, Pan)"}


def test_a_thing_that_wants_to_go_somewhere_is_to_be_put_there() -> None:
    assert goal(read("The apple wants to go in the fridge.")) == {"inside(Apple, Fridge)"}


def test_a_statement_with_a_relative_clause_is_still_a_statement() -> None:
    reading = read("The tomato that's in the sink is mine. Put the apple in the fridge.")
    assert goal(reading) == {"inside(Apple, Fridge)"} and not reading.notes


def test_in_it_after_a_receptacle_put_on_a_surface_is_that_receptacle() -> None:
    assert "inside(EggCracked, Pan)" in goal(read("Get the pan on the stove and crack an egg into it, then cook it.", 5))
    # a container something was put *in* keeps the usual reading
    assert "inside(Apple, Fridge)" in goal(read("Put the bowl in the fridge and put the apple in it.", 5))


@pytest.mark.parametrize(("text", "expected"), [
    # the state of what is to hold something comes after it is put in
    ("I want the fridge shut with the apple in it.", ["inside(Apple, Fridge)", "closed(Fridge)"]),
    ("I want the fridge shut with the apple inside.", ["inside(Apple, Fridge)", "closed(Fridge)"]),
    # "goes in" with no place: in the one just named
    ("Once the fridge is open, the apple goes in.", ["open(Fridge)", "inside(Apple, Fridge)"]),
    ("Open the fridge, the apple goes back in there, then shut it.",
     ["open(Fridge)", "inside(Apple, Fridge)", "closed(Fridge)"]),
    # after a place, "and NP state" is a second subject with its own state
    ("The apple should end up in the fridge and the fridge door closed.", ["inside(Apple, Fridge)", "closed(Fridge)"]),
])
def test_outcomes_of_open_put_close_sequences(text: str, expected: list[str]) -> None:
    reading = read(text, 5)
    assert [str(c) for s in reading.spec.subtasks for c in s.goal] == expected
    assert not reading.notes


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Turn the tap on, then off again.", 1, ["switched_on(Faucet)", "switched_off(Faucet)"]),
    ("The cloth needs a rinse in the bath - tap on, then off again when you're done.", 403,
     ["clean(Cloth)", "switched_on(Faucet)", "switched_off(Faucet)"]),
    ("Open the fridge, then shut again.", 1, ["open(Fridge)", "closed(Fridge)"]),
])
def test_a_bare_state_after_then_is_asked_of_the_last_objects(text: str, fp: int, expected: list[str]) -> None:
    reading = read(text, fp)
    subtasks = reading.spec.subtasks
    assert [str(c) for s in subtasks for c in s.goal] == expected
    assert subtasks[-1].final and not any(s.final for s in subtasks if str(s.goal[0]).startswith(
        ("switched_on", "open")))


@pytest.mark.parametrize(("text", "expected"), [
    ("Put the lettuce in the fridge once it's been chopped.", ["sliced(Lettuce)", "inside(Lettuce, Fridge)"]),
    ("Put the lettuce in the fridge after it is sliced.", ["sliced(Lettuce)", "inside(Lettuce, Fridge)"]),
])
def test_a_made_state_under_once_is_asked_for_first(text: str, expected: list[str]) -> None:
    # unlike "once it's on there" (where it will be), a state an act makes is part of the task
    reading = read(text, 5)
    assert [str(c) for s in reading.spec.subtasks for c in s.goal] == expected
    assert reading.spec.subtasks[1].depends_on == ("s1",)


def test_back_before_a_place_in_a_terse_list_is_no_obstacle() -> None:
    assert goal(read("Before bed: phone on the side table, lamp off, and the book back on the shelf.", 312)) == {
        "inside(CellPhone, SideTable)", "switched_off(DeskLamp)", "inside(Book, Shelf)"}


def test_a_slice_cut_off_the_loaf_cuts_the_loaf_and_it_is_the_slice() -> None:
    reading = read("Toast please! Cut a slice off the loaf, pop it in the toaster and then switch the toaster on.", 14)
    assert goal(reading) == {"sliced(Bread)", "cooked(Bread)", "inside(BreadSliced, Toaster)", "switched_on(Toaster)"}
    assert goal(read("Cut two slices of bread and put them on the plate.", 14)) == {
        "sliced(Bread)", "inside(2 of BreadSliced, Plate)"}


def test_a_dash_between_a_list_and_its_place_is_no_boundary() -> None:
    assert goal(read("Teddy bear, book and mug - onto the coffee table, all three of them.", 315)) == {
        "inside(TeddyBear, CoffeeTable)", "inside(Book, CoffeeTable)", "inside(Mug, CoffeeTable)"}


def test_a_placement_an_appliance_then_works_on_is_a_step_not_dropped() -> None:
    reading = read("Potato in the microwave please, and switch it on. When it's done, put it on a plate.", 5)
    steps = [(str(c), s.final) for s in reading.spec.subtasks for c in s.goal]
    assert steps == [("inside(Potato, Microwave)", False), ("switched_on(Microwave)", True),
                     ("inside(Potato, Plate)", True)]


def test_a_place_right_after_a_wished_place_says_where_that_place_is() -> None:
    assert goal(read("I want the potato cooked in the pan on the stove.", 5)) == {"inside(Potato, Pan)", "cooked(Potato)"}


@pytest.mark.parametrize(("text", "expected"), [
    ("Could you lock my phone and keys in the safe?",
     {"inside(CellPhone, Safe)", "inside(KeyChain, Safe)", "closed(Safe)"}),
    ("The safe needs opening so my credit card and keys can go in, then lock it up again.",
     {"inside(CreditCard, Safe)", "inside(KeyChain, Safe)", "closed(Safe)"}),
    ("Make sure the safe is closed at the end with my keys in it.", {"inside(KeyChain, Safe)", "closed(Safe)"}),
])
def test_locking_things_in_a_safe(text: str, expected: set[str]) -> None:
    reading = read(text, 308)
    assert goal(reading) == expected and not reading.notes


@pytest.mark.parametrize(("text", "expected"), [
    ("Take the pillow off the sofa and put it on the armchair, and while you're at it switch the TV off.",
     {"inside(Pillow, ArmChair)", "switched_off(Television)"}),
    ("Candle in the box, box shut, lamp on.", {"inside(Candle, Box)", "closed(Box)", "switched_on(FloorLamp)"}),
    # the "was" of a relative clause makes no complaint of the wish
    ("I'd like the statue on the dining table and the drawer it was in shut.",
     {"inside(Statue, DiningTable)", "closed(Drawer)"}),
])
def test_living_room_orders(text: str, expected: set[str]) -> None:
    assert goal(read(text, 220)) == expected


def test_not_this_one_only_that_one_does_the_act_on_that_one() -> None:
    reading = read("Don't turn off the desk lamp, only the floor lamp.", 201)
    assert "switched_off(FloorLamp)" in goal(reading) and "switched_off(DeskLamp)" not in goal(reading)
    assert goal(read("Don't put the apple in the fridge, just the tomato.", 5)) == {"inside(Tomato, Fridge)"}


@pytest.mark.parametrize("text", ["I want the apple cold and the bread in slices.", "The bread should be in slices."])
def test_in_slices_is_a_state_not_a_place(text: str) -> None:
    reading = read(text, 5)
    assert "sliced(Bread)" in goal(reading) and not reading.notes


@pytest.mark.parametrize("text", ["Hiya! Put the apple in the fridge.", "Put the apple in the fridge. Ta.",
                                  "Careful, put the apple in the fridge."])
def test_an_interjection_is_no_unread_span(text: str) -> None:
    reading = read(text, 17)
    assert goal(reading) == {"inside(Apple, Fridge)"} and not reading.notes and not reading.doubtful


def test_a_sequenced_unknown_word_is_still_a_note() -> None:
    assert [n.span for n in read("Put the apple in the fridge. Then wibble.", 17).notes] == ["wibble"]


def test_a_perfect_under_when_is_the_persons_act_not_a_request() -> None:
    reading = read("Grab the egg from the fridge, crack it into the pan and fry it. "
                   "Close the fridge when you've got the egg out.", 17)
    assert goal(reading) == {"sliced(Egg)", "inside(EggCracked, Pan)", "cooked(Egg)", "closed(Fridge)"}
    assert not reading.notes


def test_a_number_before_a_full_stop_numbers_the_next_item() -> None:
    reading = read("Three things: 1. telly off 2. lamp on 3. remote on the sofa", 220)
    assert goal(reading) == {"switched_off(Television)", "switched_on(FloorLamp)", "inside(RemoteControl, Sofa)"}
    assert not reading.notes


def test_another_instance_undoes_nothing_done_to_the_first() -> None:
    # FloorPlan411 has two rolls: one goes in the bin, the other on the holder, both final
    reading = read("Bin the empty loo roll and put a new one on the holder.", 411)
    assert [(str(c), s.final) for s in reading.spec.subtasks for c in s.goal] == [
        ("inside(ToiletPaper, GarbageCan)", True), ("inside(ToiletPaper, ToiletPaperHanger)", True)]


@pytest.mark.parametrize("text", ["Put the apple in the fridge. Open it first.",
                                  "Put the apple in the fridge, the fridge needs opening first."])
def test_a_clause_ending_in_first_goes_before_the_one_before_it(text: str) -> None:
    subtasks = read(text, 5).spec.subtasks
    assert [str(s.goal[0]) for s in subtasks] == ["open(Fridge)", "inside(Apple, Fridge)"]
    assert subtasks[1].depends_on == ("s1",)


def test_who_should_carry_a_placed_object_adds_no_goal() -> None:
    reading = read("The wine bottle goes in the fridge - it's heavy, so the strong robot should carry it.", 20)
    assert [(str(c), s.final) for s in reading.spec.subtasks for c in s.goal] == [("inside(WineBottle, Fridge)", True)]
    assert not reading.notes
    # handing something over is a goal of its own
    assert "held(Apple)" in goal(read("Put the apple on the table, then pick it up and give it to me.", 20))


def test_it_after_pieces_can_be_the_whole_they_come_from() -> None:
    reading = read("Three slices of apple on the plate please - cut it first.", 20)
    assert [str(c) for s in reading.spec.subtasks for c in s.goal] == ["sliced(Apple)", "inside(3 of AppleSliced, Plate)"]


@pytest.mark.parametrize(("text", "expected"), [
    ("I don't want the lights on any more.", {"switched_off(LightSwitch)"}),
    ("Any chance the tomato could end up sliced and on a plate?", {"sliced(Tomato)", "inside(Tomato, Plate)"}),
    ("How about putting the bread in the toaster and switching it on?",
     {"inside(BreadSliced, Toaster)", "switched_on(Toaster)"}),
])
def test_indirect_requests(text: str, expected: set[str]) -> None:
    reading = read(text, 20)
    assert goal(reading) == expected and not reading.notes


def test_a_perfect_is_a_statement_and_a_past_intention_no_request() -> None:
    reading = read("Right, so I was going to bake this weekend, but honestly the egg and the apple "
                   "on the counter have both gone off, so chuck them in the bin.", 22, )
    assert goal(reading) == {"inside(Egg, GarbageCan)", "inside(Apple, GarbageCan)"}
    assert not reading.notes
    # a perfect that reports a state still is a complaint
    assert goal(read("The light has been left on, switch it off.")) == {"switched_off(LightSwitch)"}


def test_a_label_that_can_be_carried_goes_to_the_place_after_its_colon() -> None:
    reading = read("Apple: fridge. Tomato: sink. Light: off.", 5)
    assert goal(reading) == {"inside(Apple, Fridge)", "inside(Tomato, SinkBasin)", "switched_off(LightSwitch)"}
    # a place as the label keeps its reading
    assert goal(read("Fridge: apple and tomato.", 5)) == {"inside(Apple, Fridge)", "inside(Tomato, Fridge)"}


@pytest.mark.parametrize("text", ["I've left my phone on the bed, can it go on the desk?",
                                  "My phone is on the bed, can it go on the desk?"])
def test_what_i_have_done_is_a_report_and_a_question_after_a_comma_its_own_clause(text: str) -> None:
    assert goal(read(text, 318)) == {"inside(CellPhone, Desk)"}


@pytest.mark.parametrize(("text", "expected"), [
    ("The kitchen's a bit of a mess. Mug in the sink. Don't worry about the pan.", {"inside(Mug, SinkBasin)"}),
    ("Right, three jobs: slice the bread, then make sure the fridge is shut.", {"sliced(Bread)", "closed(Fridge)"}),
    ("Could you get the potato cooked - microwave's fine - and put the bread in the fridge?",
     {"cooked(Potato)", "inside(Bread, Fridge)"}),
])
def test_reassurance_headings_and_means_leave_no_note(text: str, expected: set[str]) -> None:
    reading = read(text, 26)
    assert goal(reading) == expected and not reading.notes


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Put the bar of soap on the side of the bath.", 404, {"inside(SoapBar, BathtubBasin)"}),
    ("Keys and watch: into the cardboard box on the floor, then fold the box shut.", 201,
     {"inside(KeyChain, Box)", "inside(Watch, Box)", "closed(Box)"}),
    ("Toilet paper: off the floor and onto the holder. Cloth: out of the tub, onto the counter. Candle: lit.", 423,
     {"inside(ToiletPaper, ToiletPaperHanger)", "inside(Cloth, CounterTop)", "switched_on(Candle)"}),
])
def test_parts_of_places_and_labels_with_places(text: str, fp: int, expected: set[str]) -> None:
    reading = read(text, fp)
    assert goal(reading) == expected and not reading.notes


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Use a knife on the bread, get one slice into the toaster and switch it on.", 4,
     {"sliced(Bread)", "inside(BreadSliced, Toaster)", "switched_on(Toaster)"}),
    ("Use the knife on the counter to slice the bread", 4, {"sliced(Bread)"}),
    ("mug to teh desk, phone on the bed, and kil the lights", 305,
     {"inside(Mug, Desk)", "inside(CellPhone, Bed)", "switched_off(LightSwitch)"}),
])
def test_tools_used_on_things_and_letter_slips(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_come_home_to_states_and_a_prohibition_after_a_parenthesis() -> None:
    assert goal(read("I'd love to come home to the telly already on, the floor lamp off and the remote "
                     "waiting for me on the coffee table.", 203)) == {
        "switched_on(Television)", "switched_off(FloorLamp)", "inside(RemoteControl, CoffeeTable)"}
    reading = read("There's a potato in the fridge. Take it out and heat it up in the microwave (leave the "
                   "microwave going), and don't leave the fridge door hanging open afterwards.", 28)
    assert goal(reading) >= {"hot(Potato)", "switched_on(Microwave)", "closed(Fridge)"}


def test_a_chain_of_arrows_is_a_sequence_and_a_bare_place_takes_the_last_object() -> None:
    reading = read("Tea time -> kettle out of the cupboard -> fill it with water at the sink -> onto a burner. "
                   "Don't turn the heat on yet.", 15)
    assert goal(reading) >= {"filled(Kettle, water)", "inside(Kettle, StoveBurner)"}
    assert goal(read("Apple -> fridge, bread -> counter.", 5)) == {"inside(Apple, Fridge)", "inside(Bread, CounterTop)"}


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("There are two cloths lying on the floor. Both of them belong in the laundry hamper; "
     "put the lid back down on the hamper once they're in.", 317, {"inside(2 of Cloth, LaundryHamper)", "closed(LaundryHamper)"}),
    ("salad prep: slice the lettuce and the tomato (both on the table), then one slice of each goes in the bowl", 23,
     {"sliced(Lettuce)", "sliced(Tomato)", "inside(LettuceSliced, Bowl)", "inside(TomatoSliced, Bowl)"}),
    ("Could you cook the potato? There's already a frying pan on the stove, so drop the potato in that pan "
     "and fire up the burner under it.", 18, {"cooked(Potato)", "inside(Potato, Pan)", "switched_on(StoveKnob)"}),
])
def test_lids_slices_of_each_and_the_burner_under_it(text: str, fp: int, expected: set[str]) -> None:
    reading = read(text, fp)
    assert goal(reading) == expected and not reading.notes


def test_open_after_a_determiner_is_an_adjective() -> None:
    assert goal(read("Put the watch in the open box on the floor.", 210)) == {"inside(Watch, Box)"}
    assert goal(read("Open the box.", 210)) == {"open(Box)"}


def test_a_broken_off_word_is_corrected_and_the_speakers_own_plan_is_no_request() -> None:
    reading = read("Frying pan is in one of the cupboards. Get it out, set it on the cooker, and crack- well, "
                   "just put the egg from the sink into it. I'll do the rest myself.", 27)
    assert goal(reading) == {"inside(Pan, StoveBurner)", "inside(Egg, Pan)"} and not reading.notes
    assert goal(read("I'll need the apple in the fridge.", 27)) == {"inside(Apple, Fridge)"}


def test_a_wish_for_objects_brought_somewhere_after_so_is_one_clause() -> None:
    reading = read("I'm working from the desk today, so I'd like my phone and the book from the coffee table "
                   "brought over to the desk. Not the keys, those can stay put. And the floor lamp can go off.", 229)
    # the keys "can stay put": kept on the coffee table (doubts/mention_cues.py)
    assert goal(reading) == {"inside(CellPhone, Desk)", "inside(Book, Desk)", "switched_off(FloorLamp)",
                             "inside(KeyChain, CoffeeTable)"}


def test_what_keeps_happening_is_a_statement() -> None:
    reading = read("My watch, keys and credit card keep going missing. Put all three in the box.", 210)
    assert goal(reading) == {"inside(Watch, Box)", "inside(KeyChain, Box)", "inside(CreditCard, Box)"}
    assert not reading.notes


def test_a_source_before_a_destination_is_no_vague_placement() -> None:
    reading = read("Loo roll off the floor and onto the holder, candle lit, and open the shower curtain, please.", 407)
    assert goal(reading) == {"inside(ToiletPaper, ToiletPaperHanger)", "switched_on(Candle)", "open(ShowerCurtain)"}
    assert not reading.notes


def test_a_new_subject_with_a_place_and_a_modal_after_a_comma_is_a_new_clause() -> None:
    reading = read("the statue off the shelf should sit on the counter instead, the egg in the sink wants to go in "
                   "the fridge before it goes off, and that ladle on the counter lives in a drawer.", 5)
    assert goal(reading) == {"inside(Statue, CounterTop)", "inside(Egg, Fridge)", "inside(Ladle, Drawer)"}


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("The fork and spoon sitting in the sink, well, they're clean actually, so they can go in a drawer, "
     "and the potato on the table by the coffee machine should really be in the fridge.", 19,
     {"inside(Fork, Drawer)", "inside(Spoon, Drawer)", "inside(Potato, Fridge)"}),
    ("Someone's left the egg and the lettuce in the sink, honestly, they both go in the fridge.", 12,
     {"inside(Egg, Fridge)", "inside(Lettuce, Fridge)"}),
    ("The fork is in the sink, it's clean, so it can go in a drawer.", 19, {"inside(Fork, Drawer)"}),
])
def test_things_they_go_somewhere_and_where_things_sit_is_no_goal(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_a_condition_the_scene_cannot_have_is_left_out_with_a_note() -> None:
    reading = read("Could you get the shower running so it's warm for me? And the candle on the side table goes up "
                   "on a shelf.", 401)
    assert goal(reading) == {"switched_on(ShowerHead)", "inside(Candle, Shelf)"}
    assert any("cannot have it" in n.reason for n in reading.notes)


def test_a_slice_off_it_is_a_slice_of_what_can_be_cut_and_that_is_the_slice() -> None:
    reading = read("The loaf's on the counter, so once you've found a knife cut a slice off it, pop that in the "
                   "toaster and switch it on.", 5)
    assert {"sliced(Bread)", "inside(BreadSliced, Toaster)", "switched_on(Toaster)"} <= goal(reading)


def test_a_question_with_two_subjects_one_off_a_table_and_one_lying_on_a_desk() -> None:
    reading = read("We've got the builders in tomorrow, so could my phone off the coffee table and the keys that "
                   "are lying on the desk go in the safe? Open it up, put them in, and then make sure it's shut "
                   "properly, not just pushed to.", 204)
    assert goal(reading) == {"inside(CellPhone, Safe)", "inside(KeyChain, Safe)", "closed(Safe)"}


def test_once_it_is_sliced_then_an_order_without_a_comma() -> None:
    reading = read("Can you cut up the tomato by the coffee machine, the knife's in one of the drawers I think, and "
                   "once it's sliced stick a couple of the slices in the fridge for my sandwich tomorrow?", 12)
    assert goal(reading) == {"sliced(Tomato)", "inside(2 of TomatoSliced, Fridge)"}
    assert "switched_on(StoveKnob)" in goal(read("Fill the pot at the sink, put it on the hob and turn that ring on.", 12))


def test_they_can_go_away_in_one_of_the_cupboards() -> None:
    reading = read("The frying pan and my mug are both cluttering up the counter by the bread, they can go away in "
                   "one of the cupboards, only they're all shut so you'll need to open one up first.", 14)
    assert {"inside(Pan, Cabinet)", "inside(Mug, Cabinet)"} <= goal(reading)


def test_would_look_nicer_on_and_an_adjective_in_a_new_subject() -> None:
    reading = read("Tidy-up time: my phone on the coffee table goes in the drawer, the vase on the dining table would "
                   "look nicer on the side table, and the big floor lamp's still on from last night, could you turn it off?", 211)
    assert {"inside(CellPhone, Drawer)", "switched_off(FloorLamp)"} <= goal(reading)
    assert any(c.startswith("inside(Vase") and c.endswith("SideTable)") for c in goal(reading))


def test_things_that_want_to_go_somewhere() -> None:
    assert goal(read("There are two cloths lying on the bedroom floor, they both want to go in the laundry basket.", 307)) \
        == {"inside(2 of Cloth, LaundryHamper)"}


def test_an_aside_between_commas_and_a_perfect_of_an_unknown_verb() -> None:
    reading = read("The salt and pepper have wandered over to the dining table again, put them back on the worktop "
                   "would you, and the knife in the sink, dry or not, goes in a drawer.", 9)
    assert goal(reading) == {"inside(SaltShaker, CounterTop)", "inside(PepperShaker, CounterTop)", "inside(Knife, Drawer)"}
    assert not reading.notes


def test_up_on_the_shelf_describes_the_subject() -> None:
    assert "inside(AlarmClock, SideTable)" in goal(read(
        "Can you put my phone and my keys off the desk in a drawer, and the alarm clock up on the shelf should "
        "really be on the bedside table where I can reach it.", 306))


def test_the_one_next_to_the_bowl_corrects_which_ladle() -> None:
    assert goal(read("that ladle on the counter, sorry, the one next to the bowl, lives in a drawer.", 5)) == {
        "inside(Ladle, Drawer)"}


def test_coordinated_subjects_with_places_after_a_persons_clause() -> None:
    reading = read("Before you go, my phone off the desk and the keys on the other desk should go in the safe, with "
                   "the door shut properly once they're in, and then could you switch the desk lamp off?", 308)
    assert goal(reading) == {"inside(CellPhone, Safe)", "inside(KeyChain, Safe)", "closed(Safe)", "switched_off(DeskLamp)"}
    assert not reading.notes


@pytest.mark.parametrize(("text", "fp", "expected"), [
    # a report before "so" and a request is the reason, not a complaint
    ("The soap and the spray bottle are cluttering up the counter, could they both go in a drawer please? The "
     "drawers are all shut, so one of you will have to open one before they can go in.", 410,
     {"inside(SprayBottle, Drawer)", "open(Drawer)"}),
    # "shut it" after a named object that can be shut is that object, not where things went
    ("The CD and the pen on the desk can go in the box that's there with them, the laptop's been left open "
     "so shut it, and could you pull the blinds open?", 310,
     {"inside(CD, Box)", "inside(Pen, Box)", "closed(Laptop)", "open(Blinds)"}),
])
def test_reasons_and_what_shut_it_means(text: str, fp: int, expected: set[str]) -> None:
    reading = goal(read(text, fp))
    assert expected <= reading and "open(6 of Drawer)" not in reading and "closed(Box)" not in reading


def test_things_come_down_onto_places_and_the_remotes_down_the_side() -> None:
    reading = read("The two vases on the same shelf together, could they come down onto the coffee table? The "
                   "remote's down the side of the armchair, it can go in the box so it stops getting lost, and the "
                   "lamp can go off.", 206)
    assert {"inside(2 of Vase, CoffeeTable)", "inside(RemoteControl, Box)", "switched_off(FloorLamp)"} <= goal(reading)


def test_into_the_fridge_with_that() -> None:
    assert "inside(WineBottle, Fridge)" in goal(read("The wine wants chilling, so into the fridge with that.", 17))


def test_the_little_one_on_the_desk_is_the_other_lamp_not_a_contradiction() -> None:
    reading = read("Film night! Get the telly on, switch on the tall lamp in the corner and turn off the little one "
                   "on the desk, it glares on the screen.", 204)
    # (the only desk lamp: by its kind or by its id)
    assert goal(reading) & {"switched_off(DeskLamp_1)", "switched_off(DeskLamp)"}
    assert {"switched_on(Television)", "switched_on(FloorLamp)"} <= goal(reading) and len(goal(reading)) == 3
    # a real contradiction is still one
    with pytest.raises(ContradictoryInstruction):
        read("Open and close the fridge.")


# round 13: the round-8, round-9 and round-12 held-out sets, measured, became development
# data (docs/unseen_suite.md); these are paraphrases of what they taught
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # a relative clause or a participle of posture says where a thing is, not where it goes
    ("The pen that's sitting on the side table and the credit card on the dining table go in the drawer.", 221,
     {"inside(Pen, Drawer)", "inside(CreditCard, Drawer)"}),
    ("Put the vase that's on the shelf and the key chain into the box.", 208,
     {"inside(Vase, Box)", "inside(KeyChain, Box)"}),
    ("My phone, which is lying on a shelf, should go in a drawer.", 324, {"inside(CellPhone, Drawer)"}),
    # a verb that is also a noun still ends its clause ("bin the bottle, and the candle ...")
    ("Bin the spray bottle, and the candle on the toilet should go on a side table.", 429,
     {"inside(SprayBottle, GarbageCan)", "inside(Candle, SideTable)"}),
    # "that empty bottle": a demonstrative before an adjective that could be a verb
    ("Set the tomato on the counter and toss that empty bottle in the bin.", 30,
     {"inside(Tomato, CounterTop)", "inside(Bottle, GarbageCan)"}),
    # "one ... and the other ...": one each
    ("There are two toilet rolls in the cabinet: put one on the holder and the other on the counter.", 425,
     {"inside(ToiletPaper, ToiletPaperHanger)", "inside(ToiletPaper, CounterTop)"}),
    # frying happens in the pan
    ("Could you fry an egg for me?", 19, {"inside(Egg, Pan)", "cooked(Egg)", "inside(Pan, StoveBurner)"}),
    # a named place in "when it's on ..." is a step the request needs
    ("Get the frying pan out of the cupboard. Once it's on a burner, put the potato in it and cook it.", 21,
     {"inside(Pan, StoveBurner)", "inside(Potato, Pan)", "cooked(Potato)"}),
    # "... and the box closed once they're in": a subject with its state before a subordinate clause
    ("I want the statues packed into the box, and the box closed once they are in.", 223,
     {"inside(2 of Statue, Box)", "closed(Box)"}),
    # a circumstance said without its comma, and "can go off"
    ("While you're at it the desk lamp can go off.", 224, {"switched_off(DeskLamp)"}),
    # "with the cabinet door shut"
    ("I want the book in the cabinet, with the cabinet door shut.", 224, {"inside(Book, Cabinet)", "closed(Cabinet)"}),
    # "same with X": the act before, on X too; "rather than V-ing ...": a rejected alternative
    ("The mug goes in the sink. Same with the bowl.", 15, {"inside(Mug, SinkBasin)", "inside(Bowl, SinkBasin)"}),
    ("The apple should be in the bowl rather than sitting next to the coffee maker.", 15, {"inside(Apple, Bowl)"}),
    # "shut away inside the box": in the box, the box shut
    ("I'd like my credit card shut away inside the box.", 218, {"inside(CreditCard, Box)", "closed(Box)"}),
    # "n" for "and", numbered items with a bracket
    ("cd n pen into a drawer", 321, {"inside(CD, Drawer)", "inside(Pen, Drawer)"}),
    ("1) light off 2) ladle in the sink", 14, {"switched_off(LightSwitch)", "inside(Ladle, SinkBasin)"}),
    # "... and the shower door left open so it dries": a subject with its state
    ("I'd like the cloth in a drawer and the shower door left open so it dries out.", 416,
     {"inside(Cloth, Drawer)", "open(ShowerDoor)"}),
    # a label with its place, and where things are "right now"
    ("Things for the side table: my keys and my watch, both on the coffee table at the moment.", 228,
     {"inside(KeyChain, SideTable)", "inside(Watch, SideTable)"}),
    # "for the armchair" after a taking verb is where it goes ("pinch" takes)
    ("Pinch the cushion off the sofa for the armchair.", 204, {"inside(Pillow, ArmChair)"}),
    # an aside naming where each one is
    ("Both CDs, the one on the bedside table and the one on the shelf, go in the box.", 303,
     {"inside(2 of CD, Box)"}),
    # a question's later subject takes the base form
    ("Could the mug go onto the dresser, and the book that's on the dresser go on the bed?", 315,
     {"inside(Mug, Dresser)", "inside(Book, Bed)"}),
])
def test_round_13_structures(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_shut_away_orders_the_shutting_after_the_placing() -> None:
    spec = read("I'd like the remote and my credit card shut away inside the box.", 218).spec
    shut = next(s for s in spec.subtasks if "closed(Box)" in {str(c) for c in s.goal})
    placed = {s.id for s in spec.subtasks if any(str(c).startswith("inside(") for c in s.goal)}
    assert placed and placed <= set(shut.depends_on)


# round 14: what the round-15 and round-16 development sets taught (paraphrases)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # a relabelled placement, a dash before a last short phrase as a colon
    ("the rags on the floor - laundry basket please", 307, {"inside(2 of Cloth, LaundryHamper)"}),
    # bullets
    ("Before the guests come: \u2022 a new toilet roll on the holder \u2022 shower curtain pulled open "
     "\u2022 light off", 401,
     {"inside(ToiletPaper, ToiletPaperHanger)", "open(ShowerCurtain)", "switched_off(LightSwitch)"}),
    # a third-person subordinate clause is what will happen; "same for X" repeats the request
    ("The egg on the counter needs to go in the fridge before it goes off. Same for the tomato.", 2,
     {"inside(Egg, Fridge)", "inside(Tomato, Fridge)"}),
    # "I'd love it if ...": the wish, whatever else the sentence asks; a reason is dropped
    ("I'd love it if the floor lamp was on when I get home, and the tissues moved over to the dresser "
     "because I keep knocking them off.", 220, {"switched_on(FloorLamp)", "inside(TissueBox, Dresser)"}),
    # "..., with the remote on the sofa": and the remote on the sofa
    ("I'd like the television on when I get back, with the remote waiting for me on the sofa.", 220,
     {"switched_on(Television)", "inside(RemoteControl, Sofa)"}),
    # a participle with its state as a coordinated subject
    ("Both toilet rolls should be stored in the cabinet, and the light switched off.", 422,
     {"inside(2 of ToiletPaper, Cabinet)", "switched_off(LightSwitch)"}),
    # "not the one in the bin": which one, not where
    ("Put the roll from the toilet on the holder, not the one in the bin.", 420,
     {"inside(ToiletPaper_2, ToiletPaperHanger)"}),
    # a thing described by its use
    ("The thing for unblocking the toilet goes in the cabinet.", 407, {"inside(Plunger, Cabinet)"}),
    # states typed without commas; "end state"
    ("end state soap in the sink tap running light off", 430,
     {"inside(SoapBar, SinkBasin)", "switched_on(Faucet)", "switched_off(LightSwitch)"}),
    # a list without commas before its "and"
    ("put the book pen and pencil in the box", 317, {"inside(Book, Box)", "inside(Pen, Box)", "inside(Pencil, Box)"}),
    # one subject, two third-person acts
    ("robot 2 closes the drawer and turns off the light", 410, {"closed(Drawer)", "switched_off(LightSwitch)"}),
    # words heard for others
    ("put the toilet paper on the holder and through the old cloth away", 421,
     {"inside(ToiletPaper, ToiletPaperHanger)", "inside(Cloth, GarbageCan)"}),
    ("to slices of tomato on the plate", 27, {"inside(2 of TomatoSliced, Plate)"}),
    # "the side table with the lamp on it": which table
    ("pop my watch on the side table with the lamp on it", 210, {"inside(Watch, SideTable)"}),
    # "get the lights": switch them the other way
    ("could you get the lights?", 11, {"switched_off(LightSwitch)"}),
])
def test_round_14_structures(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_the_old_one_on_the_toilet_is_the_one_there() -> None:
    reading = read("We're out of loo roll on the holder, there's a spare in the cabinet. Put it on the holder "
                   "and bin the old one that's on the toilet.", 424)
    assert goal(reading) == {"inside(ToiletPaper, ToiletPaperHanger)", "inside(ToiletPaper_1, GarbageCan)"}
    assert all(s.final for s in reading.spec.subtasks)


# round 14, continued: non-native word order and words (round 17), benchmark style (round 18)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # the object before its verb
    ("television turn on, the book put on sofa, desk lamp make off", 224,
     {"switched_on(Television)", "inside(Book, Sofa)", "switched_off(DeskLamp)"}),
    ("please the wine bottle bring to fridge", 13, {"inside(WineBottle, Fridge)"}),
    ("laptop close it and put on sofa", 205, {"closed(Laptop)", "inside(Laptop, Sofa)"}),
    ("cut tomato w/ knife and 1 slice put on the plate", 13, {"sliced(Tomato)", "inside(TomatoSliced, Plate)"}),
    # ... but a participle after a noun is no verb ("the card shut away inside the box")
    ("I'd like the remote and my credit card shut away inside the box", 218,
     {"inside(RemoteControl, Box)", "inside(CreditCard, Box)", "closed(Box)"}),
    # "open/close" of what only switches
    ("close the light and open the desk lamp", 305, {"switched_off(LightSwitch)", "switched_on(DeskLamp)"}),
    ("the cloth put in sink and open the water", 422, {"inside(Cloth, SinkBasin)", "switched_on(Faucet)"}),
    # "is to warm" is too warm: a complaint, not a request to heat
    ("the wine bottle, put it in the fridge please, is to warm", 17, {"inside(WineBottle, Fridge)"}),
    ("the lamp on and tv also on please", 220, {"switched_on(FloorLamp)", "switched_on(Television)"}),
    ("take the statue from shelf to coffee table + tv on", 207,
     {"inside(Statue, CoffeeTable)", "switched_on(Television)"}),
    # washing what is clean already, in the sink named: the washing itself
    ("Rinse the cloth in the sink.", 428, {"inside(Cloth, SinkBasin_1)", "switched_on(Faucet_1)"}),
])
def test_round_14_word_order_and_words(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# round 14, indirect speech (round 20): hints, complaints and wishes said sideways
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # a temperature foretold or complained of, for food and drink
    ("That wine is going to be warm by dinner.", 13, {"cold(WineBottle)"}),
    ("Who left the wine out on the dining table? It'll be warm by tonight.", 17, {"cold(WineBottle)"}),
    ("Oh no, my tea's gone cold again.", 5, {"hot(Mug)"}),
    ("That tomato's going soft on the counter.", 2, {"cold(Tomato)"}),
    # wishes said sideways
    ("I could really use a coffee.", 11, {"filled(Mug, coffee)", "hot(Mug)"}),
    ("A baked potato would be lovely.", 20, {"cooked(Potato)"}),
    ("I was hoping for the potato, you know, baked.", 13, {"cooked(Potato)"}),
    # a screen that is dark or won't come on is off
    ("The picture box is all dark.", 203, {"switched_on(Television)"}),
    ("Mummy, the telly won't come on!", 311, {"switched_on(Television)"}),
    # nobody using things: what opens is shut, what switches is off
    ("Nobody's using the laptop or those lamps now, are they?", 205,
     {"closed(Laptop)", "switched_off(DeskLamp)", "switched_off(FloorLamp)"}),
    ("The laptop's just sitting open on the coffee table.", 222, {"closed(Laptop)"}),
    # gloom without a lamp, a glaring lamp, a thingy
    ("Bit gloomy in here without the floor lamp.", 227, {"switched_on(FloorLamp)"}),
    ("The desk lamp's glaring right in my eyes.", 326, {"switched_off(DeskLamp)"}),
    ("The light thingy's far too bright.", 403, {"switched_off(LightSwitch)"}),
    ("The bath could do with running.", 403, {"switched_on(Faucet)"}),
    # things that keep happening explain; "they'd be better off in ..." asks
    ("The pen and the pencil keep rolling off the side table, they'd be better off tucked in a drawer.", 305,
     {"inside(Pen, Drawer)", "inside(Pencil, Drawer)"}),
    ("The plunger is by the loo. Could it be hidden away in a cabinet?", 417, {"inside(Plunger, Cabinet)"}),
    ("Don't forget the bin, that grotty old cloth is still on the floor.", 326, {"inside(Cloth, GarbageCan)"}),
    ("I've finished with the newspaper, dear, it can go in the bin.", 203, {"inside(Newspaper, GarbageCan)"}),
    ("Yes please, the egg in the fridge, and the lettuce too.", 5, {"inside(Egg, Fridge)", "inside(Lettuce, Fridge)"}),
])
def test_round_14_indirect_speech(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# round 14, quantities and sets (round 19)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # "in it" is never the thing put in it; "along with" is "and"
    ("Open the cabinet and put the bowl from the coffee table in it, along with two of the vases.", 206,
     {"open(Cabinet)", "inside(Bowl, Cabinet)", "inside(2 of Vase, Cabinet)"}),
    # "the two remaining ones", "the other": as many more of the kind as said
    ("One vase can stay on the shelf; the two remaining ones go on the dining table.", 216,
     {"inside(Vase, Shelf)", "inside(2 of Vase, DiningTable)"}),
    ("There are two toilet rolls on the toilet: hang one on the holder and put the other in the drawer.", 419,
     {"inside(ToiletPaper, ToiletPaperHanger)", "inside(ToiletPaper, Drawer)"}),
    # "either sink": any one of them
    ("Put the cloth in either sink.", 424, {"inside(Cloth, SinkBasin)"}),
])
def test_round_14_quantities(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_the_bottle_after_the_spray_bottle_is_that_bottle() -> None:
    reading = read("Throw out the spray bottle that's in the cabinet. Robot 1, open it; robot 2, take the bottle and "
                   "toss it in the trash.", 417)
    assert "inside(SprayBottle, GarbageCan)" in goal(reading)
    assert not any("SoapBottle" in c for c in goal(reading))


# round 14, cooking (round 22) and tidying (round 23)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Two slices of toast please.", 1, {"sliced(Bread)", "cooked(2 of BreadSliced)"}),
    ("Make a coffee in the mug, and once the mug's full switch the coffee maker off again.", 11,
     {"filled(Mug, coffee)", "hot(Mug)", "switched_off(CoffeeMachine)"}),
    ("Bung a spud in the microwave.", 19, {"inside(Potato, Microwave)"}),
    ("Put the kettle on, would you? Fill it at the tap first.", 29,
     {"filled(Kettle, water)", "hot(Kettle)", "inside(Kettle, StoveBurner)"}),
    # a lamp by its size
    ("Leave the big lamp on and switch off the little lamp.", 217, {"switched_on(FloorLamp)", "switched_off(DeskLamp)"}),
    # "on the bed, next to the teddy": where on the bed; the teddy, a landmark, stays
    ("My book can go on the bed, next to the teddy.", 306, {"inside(Book, Bed)", "inside(TeddyBear, Bed)"}),
    # what someone threw somewhere is there now; "the spare" is another one
    ("Someone threw a loo roll in the bin, fish it out and stand it on the counter. Then get the spare out of "
     "the drawer and put that one on the holder.", 409,
     {"inside(ToiletPaper_2, CounterTop)", "inside(ToiletPaper_1, ToiletPaperHanger)"}),
    # "the soap on the bath" stands on the bathtub
    ("The soap on the bath goes in the sink.", 419, {"inside(SoapBar, SinkBasin)"}),
    # "actually no, leave X, just Y" takes X back
    ("The soap on the bath goes in the sink, and the spray bottle on the toilet too. Actually no, leave the "
     "spray bottle, just the soap.", 419, {"inside(SoapBar, SinkBasin)"}),
])
def test_round_14_cooking_and_tidying(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_crack_it_in_there_is_into_the_pan_not_the_stove_it_stands_on() -> None:
    reading = read("The egg's in the fridge and the pan's already sitting on the stove, so just crack it in there "
                   "and cook it through.", 26)
    assert {"sliced(Egg)", "inside(EggCracked, Pan)"} <= goal(reading)
    assert not any("StoveBurner" in c and "EggCracked" in c for c in goal(reading))


# round 14, vocabulary (round 25): regional words, nicknames and phrasal verbs
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Crack open the chiller and chuck the loaf in the dustbin.", 11, {"open(Fridge)", "inside(Bread, GarbageCan)"}),
    ("Stand the beaker in the espresso machine.", 20, {"inside(Mug, CoffeeMachine)"}),
    ("Turn on the set and chuck the keyring onto the settee.", 202,
     {"switched_on(Television)", "inside(KeyChain, Sofa)"}),
    ("Drop the mobile into the cardboard box, then fold the flaps shut.", 211, {"inside(CellPhone, Box)", "closed(Box)"}),
    ("Lay the newspaper over an armchair.", 212, {"inside(Newspaper, ArmChair)"}),
    ("Switch off the reading lamp and the floor light.", 225, {"switched_off(DeskLamp)", "switched_off(FloorLamp)"}),
    ("Stash the house keys in the strongbox.", 204, {"inside(KeyChain, Safe)"}),
    ("Put the bowl away in the press.", 206, {"inside(Bowl, Cabinet)"}),
    ("Do me a round of toast, would you?", 25, {"sliced(Bread)", "cooked(Bread)"}),
    ("Bung both rags in the wash basket.", 307, {"inside(2 of Cloth, LaundryHamper)"}),
    ("Fold the laptop closed.", 313, {"closed(Laptop)"}),
    ("Put the biro in the box.", 316, {"inside(Pen, Box)"}),
    ("Stow the facecloth in a cupboard.", 402, {"inside(Cloth, Cabinet)"}),
    ("Pull back the shower curtain.", 408, {"open(ShowerCurtain)"}),
    ("Lift the loo lid.", 420, {"open(Toilet)"}),
    ("Pop the soap on the basin.", 406, {"inside(SoapBar, SinkBasin)"}),
])
def test_round_14_vocabulary(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# round 14, notes left for the robots (round 24)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # asides in brackets that correct or say where things are
    ("Put my phone (dining table) and my keys (by the lamp on the side table) in the box on the coffee table.", 218,
     {"inside(CellPhone, Box)", "inside(KeyChain, Box)"}),
    ("Cut a slice off the loaf (the big knife is next to it), pop it in the toaster.", 7,
     {"sliced(Bread)", "inside(BreadSliced, Toaster)"}),
    # "rather than on the side table": the rejected place; "for tonight's salad": a purpose
    ("Keep his pen and pencil in the box rather than on the side table.", 212,
     {"inside(Pen, Box)", "inside(Pencil, Box)"}),
    ("The tomato and lettuce can go together in the bowl for tonight's salad.", 19,
     {"inside(Tomato, Bowl)", "inside(Lettuce, Bowl)"}),
    # "they" skips the places named with a pronoun subject; "lock away"
    ("Could you lock away my phone and my keys? They're both on the desk next to the laptop. They go in the safe.",
     302, {"inside(CellPhone, Safe)", "inside(KeyChain, Safe)", "inside(Laptop, Desk)"}),   # the landmark kept
    # "the bar of soap and the soap bottle": two names, no ellipsis
    ("Put the bar of soap and the soap bottle in the cabinet.", 405, {"inside(SoapBar, Cabinet)", "inside(SoapBottle, Cabinet)"}),
    # "put it on" what cannot switch: on the holder named before
    ("The holder by the loo is empty - take a spare toilet roll from the shelf and put it on.", 401,
     {"inside(ToiletPaper, TowelHolder|HandTowelHolder|ToiletPaperHanger)"}),
    ("Coffee please, lights off.", 3, {"filled(Mug, coffee)", "hot(Mug)", "switched_off(LightSwitch)"}),
    ("The paper on the sofa is finished with - straight in the bin.", 228, {"inside(Newspaper, GarbageCan)"}),
])
def test_round_14_notes(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Toast me one slice of the bread (a slice, not the whole loaf).", 25, {"sliced(Bread)", "cooked(Bread)"}),
    ("That cloth on the counter is worn out, throw it in the bin.", 409, {"inside(Cloth, GarbageCan)"}),
    ("There are two toilet rolls, one on the toilet and one on the counter. Store both in a cabinet.", 413,
     {"inside(2 of ToiletPaper, Cabinet)"}),
    # a noun of furniture before a noun of a thing says where the thing is
    ("Switch that side-table lamp on please.", 218, {"switched_on(DeskLamp_1)"}),
])
def test_round_14_notes_continued(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# round 14, general mixes (rounds 26 and 27)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Put the watch on the coffee table. No wait, put it in the box.", 222, {"inside(Watch, Box)"}),
    ("The laundry lying on the floor goes in the hamper.", 317, {"inside(2 of Cloth, LaundryHamper)"}),
    ("The spray bottle shouldn't be on the toilet; the side table is better.", 420, {"inside(SprayBottle, SideTable)"}),
    ("Restock the toilet paper holder.", 427, {"inside(ToiletPaper, ToiletPaperHanger)"}),
    ("Could the plunger and the scrub brush go in the cabinet, please? They look messy on the floor.", 403,
     {"inside(Plunger, Cabinet)", "inside(ScrubBrush, Cabinet)"}),
    ("Put the spray bottle on the side table. Oh wait, the soap bar too, on the side table.", 420,
     {"inside(SprayBottle, SideTable)", "inside(SoapBar, SideTable)"}),
    ("The lettuce is sitting in the sink and the tomato's out on a plate. Both of those belong in the fridge.", 5,
     {"inside(Lettuce, Fridge)", "inside(Tomato, Fridge)"}),
    ("Grab the mug and get the machine going.", 8, {"held(Mug)", "switched_on(CoffeeMachine)"}),
])
def test_round_14_general(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# rounds 28 and 29
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # (the microwave is the means: not part of the final goal)
    ("I fancy a jacket potato, do the one sitting in the sink in the microwave.", 11, {"cooked(Potato)"}),
    ("Clear the soap bar and the spray bottle off the counter into the drawers.", 410,
     {"inside(SoapBar, Drawer)", "inside(SprayBottle, Drawer)"}),
    ("There should be a slice of toast ready when I get back.", 13, {"sliced(Bread)", "cooked(Bread)"}),
    ("Lock my phone and my keys away somewhere secure.", 302, {"inside(CellPhone, Safe)", "inside(KeyChain, Safe)"}),
    ("Get the apple into the fridge, and we won't need the light anymore.", 7,
     {"inside(Apple, Fridge)", "switched_off(LightSwitch)"}),
    ("Shut the laptop, and the newspaper on the dining table, move that to the coffee table.", 230,
     {"closed(Laptop)", "inside(Newspaper, CoffeeTable)"}),
    ("Then put the desk lamp out, please.", 316, {"switched_off(DeskLamp)"}),
])
def test_rounds_28_and_29(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# rounds 30 and 31: probes of a sceptical reader
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("It's the cellphone that has to go in the safe, nothing else.", 308, {"inside(CellPhone, Safe)"}),
    ("The vase sitting on the dining table is what has to go into the box, and the lid must be closed after it.",
     203, {"inside(Vase, Box)", "closed(Box)"}),
    ("Whats needed is the bar of soap put away inside a cabinet.", 403, {"inside(SoapBar, Cabinet)"}),
    ("Into the box on the desk goes the alarm clock, and after that the box gets closed.", 310,
     {"inside(AlarmClock, Box)", "closed(Box)"}),
    ("The teddy bear goes on the desk, no wait, not the desk but the side table.", 313, {"inside(TeddyBear, SideTable)"}),
    ("If the desk lamp's still on, could you switch it off?", 302, {"switched_off(DeskLamp)"}),
    ("The empty holder needs a roll of toilet paper.", 407, {"inside(ToiletPaper, ToiletPaperHanger)"}),
    ("Those two little things, the key chain and the credit card, belong in one of the drawers.", 205,
     {"inside(KeyChain, Drawer)", "inside(CreditCard, Drawer)"}),
    ("Anyway, the potato on the table needs to go in the trash, and if it's not too much trouble turn the coffee "
     "machine on.", 17, {"inside(Potato, GarbageCan)", "switched_on(CoffeeMachine)"}),
])
def test_rounds_30_and_31(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("I'd kill for a coffee right now.", 10, {"filled(Mug, coffee)", "hot(Mug)"}),
    ("Cook the potato in the pot that's already on the stove, please.", 4,
     {"inside(Potato, Pot)", "cooked(Potato)", "inside(Pot, StoveBurner)"}),
])
def test_round_30_wishes_and_pots(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_a_counter_is_not_in_the_bin_but_a_safe_stands_on_a_dresser() -> None:
    assert goal(read("Toss the toilet paper roll on the counter in the bin.", 411)) == {"inside(ToiletPaper_1, GarbageCan)"}
    assert {"inside(KeyChain, Safe)"} <= goal(read("Put the keys in the safe on the dresser.", 323))


# round 32: the first fresh sets of the session before (13 and 14), read after their one
# measurement; paraphrases of what they taught
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # a drink "in" its vessel is the fill, never the vessel in itself
    ("Coffee in the mug that's on the counter, please.", 1, {"filled(Mug, coffee)", "hot(Mug)"}),
    # "don't bother V-ing" calls the act off; "brew a cup in it" is coffee
    ("The mug's on the counter. Don't bother washing it, just brew me a cup in it.", 1,
     {"filled(Mug, coffee)", "hot(Mug)"}),
    # a state after a comma is the noun's; "at least three" counts three; a tool that
    # "lives in one of the drawers" is where it is found
    ("Bread from the counter, sliced, at least three slices on the plate.", 1,
     {"sliced(Bread)", "inside(3 of BreadSliced, Plate)"}),
    ("Put the apple in the fridge. The knife lives in one of the drawers.", 1, {"inside(Apple, Fridge)"}),
    # a container named by what it holds
    ("Put the keys in the place we keep our valuables and shut it.", 204, {"inside(KeyChain, Safe)", "closed(Safe)"}),
    ("Stick my phone where we keep the cash.", 204, {"inside(CellPhone, Safe)"}),
    # coming home to a dark room; a thing wanted "gone"
    ("I want to come home to a nice dark living room.", 201,
     {"switched_off(DeskLamp)", "switched_off(FloorLamp)", "switched_off(LightSwitch)"}),
    ("I want the newspaper on the sofa gone.", 201, {"inside(Newspaper, GarbageCan)"}),
    # ", but there's ..." starts a clause; the lid put down is the hamper closed
    ("The room's a mess, but there's a cloth on the floor and it goes in the hamper. Put the lid down after.", 307,
     {"inside(Cloth, LaundryHamper)", "closed(LaundryHamper)"}),
    # boxing up is putting in the box
    ("The book and the pen on the desk need boxing up.", 317, {"inside(Book, Box)", "inside(Pen, Box)"}),
    # "the box" in a room whose only box is a tissue box
    ("Where are the tissues? Bring the box to the toilet.", 402, {"inside(TissueBox, Toilet)"}),
    # a posture after "love" is the wished place; "while I have a bath" is the person's
    ("I'd love the candle sitting on the toilet while I have a bath.", 402, {"inside(Candle, Toilet)"}),
    # a list item without a verb: "away in a cabinet"
    ("- towel away in a cabinet\n- light off", 402, {"inside(Towel, Cabinet)", "switched_off(LightSwitch)"}),
    # "once it's done" ends a state clause before the request
    ("Toast the bread and once it's done put it on the plate.", 1,
     {"sliced(Bread)", "cooked(Bread)", "inside(Bread, Plate)"}),
    # a subjectless "and then end up in ..." inside a polite "if" is the if's subject's
    ("If the apple could get chilled and then end up on the plate, that'd be great.", 1,
     {"cold(Apple)", "inside(Apple, Plate)"}),
    # the typed "id", "ive", "wont"; an aside that counts what was named
    ("id like the vase and the statue, both of them, moved onto the shelf", 201,
     {"inside(Vase, Shelf)", "inside(Statue, Shelf)"}),
    ("ive left the fridge open, wont you close it", 1, {"closed(Fridge)"}),
])
def test_round_32_structures(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Put the mug in the coffee machine but don't turn it on yet.", 1,
     {"inside(Mug, CoffeeMachine)", "switched_off(CoffeeMachine)"}),
    ("Put the remote on the sofa, and don't switch the TV on.", 201,
     {"inside(RemoteControl, Sofa)", "switched_off(Television)"}),
])
def test_a_refused_switch_with_its_particle_after_the_object_is_off(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


def test_lock_away_still_shuts_the_container() -> None:
    assert goal(read("My keys should be locked away in the safe.", 204)) == {"inside(KeyChain, Safe)", "closed(Safe)"}


# rounds 34 and 35: chat and voice transcripts, and sentence structure (development sets)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # "it" after two things put on it is where they went, not one of them
    ("grab a bowl from the cupboard and put the apple and the egg in it, then leave it on the table", 1,
     {"inside(Apple, Bowl)", "inside(Egg, Bowl)", "inside(Bowl, CounterTop)"}),
    # hesitations do not hide where a clause starts; "this time" is a time
    ("um switch the toaster on and uh put the egg in the fridge", 1, {"switched_on(Toaster)", "inside(Egg, Fridge)"}),
    ("put the apple on the counter. and dont leave the fridge open this time", 1,
     {"inside(Apple, CounterTop)", "closed(Fridge)"}),
    # "some of each" after cutting are pieces of each
    ("chop the lettuce and the tomato and put some of each on the plate", 1,
     {"sliced(Lettuce)", "sliced(Tomato)", "inside(LettuceSliced, Plate)", "inside(TomatoSliced, Plate)"}),
    # "empty" after a determiner is an adjective
    ("that empty mug on the counter can go in the sink", 1, {"inside(Mug, SinkBasin)"}),
    # run-ons: a statement then "can you ...", a request then "put it ..."
    ("the apple is on the counter can you put it in the fridge", 1, {"inside(Apple, Fridge)"}),
    ("take the book from the desk put it on the bed", 305, {"inside(Book, Bed)"}),
    # "put the kettle on" boils it
    ("put the kettle on, its on the stove already", 1,
     {"filled(Kettle, water)", "hot(Kettle)", "inside(Kettle, StoveBurner)"}),
    # "the ones on the desk I mean" says which, not where to
    ("put the pen and the pencil in a drawer the ones on the desk i mean", 311,
     {"inside(Pen, Drawer)", "inside(Pencil, Drawer)"}),
    ("kitchen lights been on all day, turn them off", 1, {"switched_off(LightSwitch)"}),
    # "the plate that's on the counter" is no verb "plate"
    ("set the apple on the plate that's on the counter", 1, {"inside(Apple, Plate)"}),
    # two states of one thing; a participle after a place is the placed thing's
    ("The fridge should be left shut and the microwave switched off and closed.", 1,
     {"closed(Fridge)", "switched_off(Microwave)", "closed(Microwave)"}),
    ("the laptop goes on the bed, closed.", 305, {"inside(Laptop, Bed)", "closed(Laptop)"}),
    # a pronoun named after it
    ("Put them in the fridge: the apple and the tomato, I mean.", 1, {"inside(Apple, Fridge)", "inside(Tomato, Fridge)"}),
    ("put the apple in the fridge, with its door shut afterwards", 1, {"inside(Apple, Fridge)", "closed(Fridge)"}),
    # acts called off are no goals, not their opposites
    ("slice the bread. No need to close the fridge.", 1, {"sliced(Bread)"}),
    # "don't move X" keeps X where it is: no move, its start place a goal
    ("put the book on the desk. Don't move the laptop, she still needs it.", 305,
     {"inside(Book, Desk)", "inside(Laptop, Desk)"}),
    # "No, throw X away instead": the request said again replaces the one before
    ("Throw the pen away. No, throw the pencil away instead, I still need the pen, so leave it on the desk.", 305,
     {"inside(Pencil, GarbageCan)", "inside(Pen, Desk)"}),
])
def test_rounds_34_and_35(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# round 37: non-native and careless English (development set)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # "at" names where an object-first clause puts it, so "and light off" is a new clause
    ("the egg put at bowl and light off", 1, {"inside(Egg, Bowl)", "switched_off(LightSwitch)"}),
    # "the light of kitchen", "light of the floor lamp": the room's light, the lamp
    ("the apple put in the fridge and the light of kitchen turn off please", 1,
     {"inside(Apple, Fridge)", "switched_off(LightSwitch)"}),
    ("light of the floor lamp off, and the remote put on the sofa", 201,
     {"switched_off(FloorLamp)", "inside(RemoteControl, Sofa)"}),
    ("the tissues box put at the toilet", 402, {"inside(TissueBox, Toilet)"}),
    # an object-first "take out and put on X" is not given the next clause's object
    ("apple from fridge take out and put on the counter, close fridge", 1,
     {"inside(Apple, CounterTop)", "closed(Fridge)"}),
    ("the mug put in sink and water open", 1, {"inside(Mug, SinkBasin)", "switched_on(Faucet)"}),
    # "one slice of it" before its verb
    ("Bread cut to slices and one slice of it put in the toaster", 1, {"sliced(Bread)", "inside(BreadSliced, Toaster)"}),
    ("Lamp and light off, please.", 302, {"switched_off(DeskLamp)", "switched_off(LightSwitch)"}),
    ("I need the egg for baking, could you put it in the bowl?", 1, {"inside(Egg, Bowl)"}),
])
def test_round_37_non_native_english(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# round 36: peer-benchmark imperatives and vague variants (development set)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # "clear the X: everything on it ..." is everything on X
    ("Clear the dining table: everything on it goes in the fridge.", 11,
     {"inside(Bowl, Fridge)", "inside(Mug, Fridge)", "inside(Pot, Fridge)"}),
    # candlelight is the candle lit; "instead of the ceiling light" puts that light off
    ("Let's have candlelight tonight instead of the main light.", 220, {"switched_on(Candle)", "switched_off(LightSwitch)"}),
    # an empty holder wants a roll
    ("The loo roll holder is empty.", 401, {"inside(ToiletPaper, ToiletPaperHanger)"}),
])
def test_round_36_vague_variants(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# round 39: benchmark style and natural requests (development set)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # replacing the loo roll is a roll on the holder
    ("Restock the loo roll and turn off the light", 406, {"inside(ToiletPaper, ToiletPaperHanger)", "switched_off(LightSwitch)"}),
    # "no wait, don't" calls the act before off
    ("Turn on the faucet - no wait, don't, just switch off the light.", 407, {"switched_off(LightSwitch)"}),
    # the writing things are pens and pencils
    ("Put the writing things in the drawer.", 212, {"inside(Pen, Drawer)", "inside(Pencil, Drawer)"}),
    # "need it for noodles" is a purpose
    ("boil some water in the pot. need it for noodles", 1,
     {"filled(Pot, water)", "hot(Pot)", "inside(Pot, StoveBurner)"}),
])
def test_round_39_requests(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected


# round 38: forty imagined people (development set)
@pytest.mark.parametrize(("text", "fp", "expected"), [
    # a run-on request after a complete one
    ("turn off the light put the apple in the fridge and the egg in the bowl", 1,
     {"switched_off(LightSwitch)", "inside(Apple, Fridge)", "inside(Egg, Bowl)"}),
    # chat: "em", "outta"
    ("can u take the fork n spoon outta the sink and put em in a drawer", 1, {"inside(Fork, Drawer)", "inside(Spoon, Drawer)"}),
    # "in there" is where the thing named before stands, when nothing else can take it
    ("The tomato's already in the fridge. Put the egg in there with it.", 1, {"inside(Egg, Fridge)"}),
    # a request broken off by "no wait" and said again
    # the kept apple stays where it is (doubts/mention_cues.py: its start place is a goal)
    ("Put the apple on the - no wait, leave the apple where it is. Put the egg in the bowl.", 1,
     {"inside(Egg, Bowl)", "inside(Apple, CounterTop)"}),
    ("I would like a cup of coffee from the machine, in my mug.", 1, {"filled(Mug, coffee)", "hot(Mug)"}),
    # "no heat" is no correction
    ("the kettle goes on the stove (just put it there, no heat)", 1, {"inside(Kettle, StoveBurner)"}),
])
def test_round_38_forty_people(text: str, fp: int, expected: set[str]) -> None:
    assert goal(read(text, fp)) == expected
