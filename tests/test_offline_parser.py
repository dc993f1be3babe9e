"""The offline parser, phenomenon by phenomenon: verbs to conditions, ordering, pronouns,
counts, categories, negation and complaints, typos, robots, intermediate steps, errors."""

from __future__ import annotations

import pytest

from emboteam.errors import EmboTeamError, UnknownRobotError
from emboteam.pfg.offline import GroundingError, OfflineFrontend, OfflineParseError
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


def parse(text: str, fp: int = 1, robots: str = "1,2", state: WorldState | None = None) -> TaskSpec:
    scene = load_scene(fp)
    team = parse_team(robots)
    return OfflineFrontend().decompose(text, scene, state or WorldState.from_scene(scene, team), team)


def goal(text: str, fp: int = 1) -> set[str]:
    return {str(c) for c in parse(text, fp).goal().conditions}


def ids(spec: TaskSpec) -> dict[str, str]:
    """condition -> id of the subtask holding it"""
    return {str(c): s.id for s in spec.subtasks for c in s.goal}


def deps(spec: TaskSpec, cond: str) -> set[str]:
    """conditions of the subtasks the one holding ``cond`` depends on"""
    sid = ids(spec)[cond]
    before = set(spec.subtask(sid).depends_on)
    return {c for c, s in ids(spec).items() if s in before}


# ---- verbs to conditions -------------------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("put the apple in the fridge", 1, {"inside(Apple, Fridge)"}),
    ("store the bread on the counter", 1, {"inside(Bread, CounterTop)"}),
    ("trash the egg", 1, {"inside(Egg, GarbageCan)"}),
    ("throw away the fork", 1, {"inside(Fork, GarbageCan)"}),
    ("dice the potato", 1, {"sliced(Potato)"}),
    ("smash the vase", 1, {"broken(Vase)"}),
    ("shut the fridge", 1, {"closed(Fridge)"}),
    ("switch on the microwave", 1, {"switched_on(Microwave)"}),
    ("turn the toaster off", 1, {"switched_off(Toaster)"}),
    ("warm up the potato", 1, {"hot(Potato)"}),
    ("fry the egg", 1, {"inside(Egg, Pan)", "cooked(Egg)", "inside(Pan, StoveBurner)"}),
    ("refrigerate the tomato", 1, {"cold(Tomato)"}),
    ("wash the bowl", 1, {"clean(Bowl)"}),
    ("fill the cup with water", 1, {"filled(Cup, water)"}),
    ("fill the pot", 1, {"filled(Pot, water)"}),
    ("pour wine into the mug", 1, {"filled(Mug, wine)"}),
    ("grab the spatula", 1, {"held(Spatula)"}),
    ("dirty the pan", 1, {"dirty(Pan)"}),
    ("make coffee", 1, {"filled(Mug, coffee)", "hot(Mug)"}),
    ("toast the bread", 1, {"sliced(Bread)", "cooked(Bread)"}),
    ("water the plant", 209, {"filled(HousePlant, water)"}),
    ("watch tv", 201, {"switched_on(Television)"}),
    ("light the candle", 414, {"switched_on(Candle)"}),
    ("open the laptop", 303, {"open(Laptop)"}),
])
def test_verbs_map_to_conditions(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_microwave_names_the_means_as_an_intermediate_step() -> None:
    spec = parse("microwave the potato")
    assert {str(c) for c in spec.goal().conditions} == {"hot(Potato)"}
    means = [s for s in spec.subtasks if not s.final]
    assert [str(c) for c in means[0].goal] == ["inside(Potato, Microwave)", "switched_on(Microwave)"]
    assert deps(spec, "hot(Potato)") == {"inside(Potato, Microwave)", "switched_on(Microwave)"}


def test_coffee_machine_and_switch_it_on() -> None:
    spec = parse("put the mug in the coffee machine and switch it on")
    assert {str(c) for c in spec.goal().conditions} == {"inside(Mug, CoffeeMachine)",
                                                         "switched_on(CoffeeMachine)"}
    assert deps(spec, "switched_on(CoffeeMachine)") == {"inside(Mug, CoffeeMachine)"}


def test_containers_with_contents() -> None:
    spec = parse("microwave a plate containing an egg and a tomato", 15)
    assert {str(c) for c in spec.goal().conditions} == {
        "inside(Egg, Plate)", "inside(Tomato, Plate)", "hot(Plate)"}
    assert deps(spec, "hot(Plate)") >= {"inside(Egg, Plate)", "inside(Tomato, Plate)"}
    assert goal("bring me the bowl with the apple in it") == {"inside(Apple, Bowl)", "held(Bowl)"}


def test_liquids_as_objects() -> None:
    assert goal("fill water in the kettle") == {"filled(Kettle, water)"}
    assert goal("put some water in the pot") == {"filled(Pot, water)"}
    assert goal("pour coffee in the mug") == {"filled(Mug, coffee)"}


def test_bread_goes_into_the_toaster_as_slices() -> None:
    assert goal("put the bread in the toaster") == {"inside(BreadSliced, Toaster)"}


# ---- washing: clean or rinse -----------------------------------------------------------
def test_wash_dirtyable_is_clean_and_non_dirtyable_is_an_intermediate_rinse() -> None:
    assert goal("wash the plate") == {"clean(Plate)"}
    spec = parse("wash the lettuce and then put it on the counter")
    rinse = next(s for s in spec.subtasks if not s.final)
    assert {str(c) for c in rinse.goal} == {"inside(Lettuce, SinkBasin)", "switched_on(Faucet)"}
    assert {str(c) for c in spec.goal().conditions} == {"inside(Lettuce, CounterTop)"}
    assert deps(spec, "inside(Lettuce, CounterTop)") >= {"inside(Lettuce, SinkBasin)"}


def test_a_rinse_is_always_an_intermediate_step() -> None:
    """A non-dirtyable object is never dirty: rinsing it is a process, not an end state."""
    spec = parse("rinse the tomato")
    (rinse,) = spec.subtasks
    assert not rinse.final and {str(c) for c in rinse.goal} == {
        "inside(Tomato, SinkBasin)", "switched_on(Faucet)"}
    assert spec.goal().conditions == ()


def test_rinse_in_a_bathroom_with_two_faucets_names_the_sink_faucet() -> None:
    spec = parse("wash the soap bar", 414)
    (rinse,) = spec.subtasks
    faucet = next(c for c in rinse.goal if c.predicate.value == "switched_on")
    scene = load_scene(414)
    assert faucet.subject.id is not None
    basin = next(c for c in rinse.goal if c.predicate.value == "inside").receptacle
    assert basin is not None and basin.id in scene.get(faucet.subject.id).controls


# ---- ordering ------------------------------------------------------------------------
@pytest.mark.parametrize("text", [
    "slice the apple, then put it in the fridge",
    "slice the apple and then put it in the fridge",
    "first slice the apple, then put it in the fridge",
    "slice the apple. After that, put it in the fridge.",
    "after slicing the apple, put it in the fridge",
    "put the apple in the fridge after slicing it",
    "once the apple is sliced, put it in the fridge",
    "before putting the apple in the fridge, slice it",
    "slice the apple before you put it in the fridge",
    "slice the apple and put it in the fridge",
])
def test_ordering_constructions(text: str) -> None:
    spec = parse(text)
    assert {str(c) for c in spec.goal().conditions} == {"sliced(Apple)", "inside(Apple, Fridge)"}
    assert deps(spec, "inside(Apple, Fridge)") == {"sliced(Apple)"}
    assert deps(spec, "sliced(Apple)") == set()


def test_then_orders_unrelated_actions_but_and_does_not() -> None:
    spec = parse("turn off the light, then open the fridge")
    assert deps(spec, "open(Fridge)") == {"switched_off(LightSwitch)"}
    spec = parse("turn off the light and open the fridge")
    assert deps(spec, "open(Fridge)") == set()


def test_a_step_waits_for_every_subtask_of_the_step_before() -> None:
    spec = parse("slice the apple and the tomato, then put them in the bowl")
    assert deps(spec, "inside(Apple, Bowl)") == {"sliced(Apple)", "sliced(Tomato)"}
    assert deps(spec, "inside(Tomato, Bowl)") == {"sliced(Apple)", "sliced(Tomato)"}


def test_objects_of_one_clause_are_separate_parallel_subtasks() -> None:
    spec = parse("put the apple, the tomato and the potato in the fridge")
    assert len(spec.subtasks) == 3 and all(not s.depends_on for s in spec.subtasks)


# ---- pronouns -------------------------------------------------------------------------
def test_it_resolves_to_what_the_verb_can_act_on() -> None:
    assert goal("put the apple in the fridge and close it") == {"inside(Apple, Fridge)", "closed(Fridge)"}
    assert goal("open the fridge and put the egg in it") == {"open(Fridge)", "inside(Egg, Fridge)"}
    assert goal("put the lettuce in the fridge after washing it") == {"inside(Lettuce, Fridge)"}


def test_them_refers_to_the_coordinated_objects() -> None:
    assert goal("pick up the fork and the spoon and put them in the drawer") == {
        "inside(Fork, Drawer)", "inside(Spoon, Drawer)"}


def test_pronoun_across_sentences_and_the_slices() -> None:
    assert goal("Slice the tomato. Put the slices on the plate.") == {
        "sliced(Tomato)", "inside(TomatoSliced, Plate)"}


# ---- counts, plurals, categories -----------------------------------------------------------
def test_counts_and_categories() -> None:
    assert goal("put two vegetables in the fridge") == {"inside(2 of Lettuce|Potato|Tomato, Fridge)"}
    assert goal("put the vegetables in the fridge") == {
        "inside(Lettuce, Fridge)", "inside(Potato, Fridge)", "inside(Tomato, Fridge)"}
    assert goal("put all the vases on the dresser", 209) == {"inside(4 of Vase, Dresser)"}
    assert goal("put a vase in the box", 209) == {"inside(Vase, Box)"}
    assert goal("put both CDs in the box", 303) == {"inside(2 of CD, Box)"}
    assert goal("close all the drawers", 209) == {"closed(4 of Drawer)"}


def test_categories_are_restricted_to_the_types_of_the_scene() -> None:
    # FloorPlan303 has a baseball bat, a tennis racket and a dumbbell, no basketball
    assert goal("put the sports equipment on the bed", 303) == {
        "inside(BaseballBat, Bed)", "inside(TennisRacket, Bed)", "inside(Dumbbell, Bed)"}
    assert goal("put the dishes in the sink", 6) == {
        "inside(Plate, SinkBasin)", "inside(Bowl, SinkBasin)", "inside(Cup, SinkBasin)",
        "inside(Mug, SinkBasin)"}


def test_heating_appliance_and_trash_synonyms() -> None:
    # of the heating appliances, the ones the object fits in
    assert goal("put the potato in a heating appliance") == {"inside(Potato, Microwave)"}
    assert goal("put the pan on a heating appliance") == {"inside(Pan, StoveBurner)"}
    assert goal("put the potato and the pan on a heating appliance") == {
        "inside(Potato, Microwave)", "inside(Pan, StoveBurner)"}
    for word in ("trash", "bin", "garbage", "trash can", "wastebasket"):
        assert goal(f"put the fork in the {word}") == {"inside(Fork, GarbageCan)"}


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("turn off the lights", 201, {"switched_off(LightSwitch)"}),
    ("turn off all the lights", 201, {"switched_off(LightSwitch)", "switched_off(DeskLamp)",
                                      "switched_off(FloorLamp)"}),
    ("turn off the lamp", 209, {"switched_off(FloorLamp)"}),
    ("turn on the tv", 201, {"switched_on(Television)"}),
    ("put the phone on the couch", 203, {"inside(CellPhone, Sofa)"}),
    ("put the mobile on the sofa", 203, {"inside(CellPhone, Sofa)"}),
    ("put the breadloaf on the countertop", 1, {"inside(Bread, CounterTop)"}),
    ("put the dishsponge in the sink", 1, {"inside(DishSponge, SinkBasin)"}),
    ("put the book on the CoffeeTable", 201, {"inside(Book, CoffeeTable)"}),
    ("put the book on the coffeetable", 201, {"inside(Book, CoffeeTable)"}),
    ("turn on the stove", 1, {"switched_on(StoveKnob)"}),
    ("turn on the sink", 1, {"switched_on(Faucet)"}),
    ("put the plate on the table", 15, {"inside(Plate, DiningTable)"}),
    ("put the book on the table", 209, {"inside(Book, CoffeeTable)"}),
])
def test_synonyms_ground_to_scene_types(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_adjectives_pick_object_ids_from_the_state() -> None:
    scene = load_scene(1)
    team = parse_team("1,2")
    state = WorldState.from_scene(scene, team)
    state.objects["Mug_1"].is_dirty = True
    spec = OfflineFrontend().decompose("wash the dirty mug", scene, state, team)
    assert {str(c) for c in spec.goal().conditions} == {"clean(Mug)"}   # the only mug
    scene = load_scene(209)
    state = WorldState.from_scene(scene, team)
    state.objects["Vase_3"].is_broken = True
    spec = OfflineFrontend().decompose("throw away the broken vase", scene, state, team)
    assert {str(c) for c in spec.goal().conditions} == {"inside(Vase_3, GarbageCan)"}


# ---- negation, complaints, wishes ------------------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("don't leave the lights on", 1, {"switched_off(LightSwitch)"}),
    ("make sure the fridge is not open", 1, {"closed(Fridge)"}),
    ("make the room dark", 201, {"switched_off(LightSwitch)", "switched_off(DeskLamp)",
                                 "switched_off(FloorLamp)"}),
    ("make the room bright", 303, {"switched_on(LightSwitch)"}),   # the main light suffices
    ("open the book in a well lit room", 303, {"open(Book)", "switched_on(LightSwitch)"}),
    ("the room should be well lit", 1, {"switched_on(LightSwitch)"}),
    ("somebody left the microwave open", 1, {"closed(Microwave)"}),
    ("the tv is on", 201, {"switched_off(Television)"}),
    ("it is too dark in here", 1, {"switched_on(LightSwitch)"}),
    ("the fridge should be closed", 1, {"closed(Fridge)"}),
    ("I want the tv on", 201, {"switched_on(Television)"}),
    ("don't turn on the tv", 201, {"switched_off(Television)"}),
    ("nobody needs the lights on", 1, {"switched_off(LightSwitch)"}),
])
def test_negation_and_states(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_a_prohibition_that_has_no_opposite_state_adds_nothing() -> None:
    assert goal("don't break the vase and put the apple in the fridge") == {"inside(Apple, Fridge)"}


# ---- typos ---------------------------------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("put the tomatoe in the frigde", 1, {"inside(Tomato, Fridge)"}),
    ("place the Labtop on the sofa", 209, {"inside(Laptop, Sofa)"}),
    ("slcie the potatoe", 1, {"sliced(Potato)"}),
    ("turn of the televison", 201, {"switched_off(Television)"}),
    ("trun on the coffe machine", 1, {"switched_on(CoffeeMachine)"}),
    ("heat the potato in the micro wave", 1, {"hot(Potato)"}),
    ("put the bred on the plat", 1, {"inside(Bread, Plate)"}),
])
def test_typos_are_corrected_against_the_lexicon(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


# ---- robots ----------------------------------------------------------------------------
def test_named_robots_are_assigned_and_others_left_to_the_planner() -> None:
    spec = parse("robot 2 should slice the bread and robot 1 should open the fridge. "
                 "Turn off the light.")
    assignment = {str(c): s.robot for s in spec.subtasks for c in s.goal}
    assert assignment == {"sliced(Bread)": "robot2", "open(Fridge)": "robot1",
                          "switched_off(LightSwitch)": None}
    spec = parse("Have robot 5 open the fridge", robots="5,7")
    assert spec.subtasks[0].robot == "robot5"
    spec = parse("the second robot should open the fridge", robots="5,7")
    assert spec.subtasks[0].robot == "robot7"
    spec = parse("robot 1: slice the apple and put it in the fridge", robots="4,9")
    assert {s.robot for s in spec.subtasks} == {"robot4"}


def test_unknown_robot_is_a_typed_error() -> None:
    with pytest.raises(UnknownRobotError, match="robot 9"):
        parse("robot 9 should open the fridge", robots="1,2")


# ---- intermediate (non-final) subtasks ------------------------------------------------------
def test_undone_conditions_are_intermediate() -> None:
    spec = parse("open the fridge, take out the apple and close the fridge")
    final = {str(c) for s in spec.subtasks if s.final for c in s.goal}
    assert final == {"held(Apple)", "closed(Fridge)"}
    assert not next(s for s in spec.subtasks if str(s.goal[0]) == "open(Fridge)").final
    spec = parse("pick up the knife and put it in the drawer")
    assert {str(c) for c in spec.goal().conditions} == {"inside(Knife, Drawer)"}


# ---- errors --------------------------------------------------------------------------
def test_unknown_noun_names_the_phrase_and_suggests_scene_types() -> None:
    with pytest.raises(GroundingError) as err:
        parse("put the flux capacitor in the fridge")
    assert err.value.phrase == "flux capacitor"
    # nothing in the scene is spelt like it: no unrelated "closest objects" (issue 24)
    assert "flux capacitor" in str(err.value) and err.value.suggestions == ()


def test_type_missing_from_the_scene() -> None:
    with pytest.raises(GroundingError, match="FloorPlan414 has no apple") as err:
        parse("put the apple in the fridge", 414)
    assert err.value.suggestions == ()  # a bathroom has nothing spelt like an apple


def test_misspelled_type_missing_from_the_scene_says_it_is_missing() -> None:
    with pytest.raises(GroundingError, match="FloorPlan1 has no candle") as err:
        parse("put the candel on the counter", 1)
    assert err.value.suggestions == ()


def test_suggestions_are_close_spellings_never_the_very_object() -> None:
    from emboteam.pfg.offline.grounding import Grounder
    from emboteam.world.scene import load_scene
    from emboteam.world.state import WorldState

    scene = load_scene(1)
    grounder = Grounder(scene, WorldState.from_scene(scene))
    assert grounder.suggestions("spatual") == ["Spatula"]
    assert grounder.suggestions("the red aple") == ["Apple"]
    assert grounder.suggestions("fridge") == []           # the object itself: not a spelling problem
    assert grounder.suggestions("bathtub") == []          # nothing like it in a kitchen
    assert grounder.suggestions("toilet paper") == []


@pytest.mark.parametrize(("text", "fp", "error", "match"), [
    ("", 1, OfflineParseError, "empty"),
    ("dance", 1, OfflineParseError, "no action"),
    ("tidy up the living room", 209, OfflineParseError, "vague"),
    ("make the bed", 303, OfflineParseError, "vague"),
    ("get dinner started", 1, OfflineParseError, "vague"),
    ("set the table", 15, OfflineParseError, "vague"),
    ("clean the kitchen", 1, OfflineParseError, "vague"),
    ("put it in the fridge", 1, OfflineParseError, "refers to nothing"),
    ("put the apple", 1, OfflineParseError, "where should"),
    ("put three eggs in the bowl", 1, GroundingError, "only 1"),
    ("open the window", 1, GroundingError, "opened"),
    ("put the houseplant on the table", 209, GroundingError, "picked up"),
    ("slice the apple", 201, GroundingError, "no apple"),
])
def test_errors_are_typed_and_clear(text: str, fp: int, error: type[EmboTeamError], match: str) -> None:
    with pytest.raises(error, match=match):
        parse(text, fp)


def test_every_error_is_an_emboteam_error_never_a_crash() -> None:
    weird = ["??", "the the the", "put put put", "and then", "robot 1", "it", "1 2 3",
             "put the apple in", "in the fridge", "turn", "slice", "not", "x" * 3000,
             "put the apple in the fridge " * 40, "open the fridge, then, then, then"]
    for text in weird:
        try:
            spec = parse(text)
        except EmboTeamError as exc:
            assert str(exc)          # a message, one line
            assert "\n" not in str(exc)
        else:
            assert spec.subtasks


def test_deterministic() -> None:
    text = "Put the apple and the tomato in the fridge, then slice the bread and toast it."
    assert parse(text).model_dump() == parse(text).model_dump()
