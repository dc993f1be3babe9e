"""The offline parser's second round of linguistic coverage, one test group per phenomenon
(docs/offline_parser.md, "Phenomena"): locative modifiers, motion predicates and gapping,
vague umbrella verbs, verbless state lists, wishes and dishes, discourse reference and
instance binding, "everything", darkness, measure nouns, instruments, light verbs,
verb particles, politeness, self-corrections; and robustness (no crash on any input)."""

from __future__ import annotations

import contextlib
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from emboteam.bench.offline_accuracy import initial_state
from emboteam.errors import EmboTeamError
from emboteam.pfg.offline import GroundingError, OfflineFrontend, OfflineParseError
from emboteam.pfg.reading import Reading
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

FRONTEND = OfflineFrontend()


def run(text: str, fp: int = 1, setup: list[dict[str, Any]] | None = None) -> Reading:
    scene = load_scene(fp)
    team = parse_team("1,2")
    state = initial_state({"setup": setup or []}, scene, team)
    return FRONTEND.parse(text, scene, state, team)


def goal(text: str, fp: int = 1, setup: list[dict[str, Any]] | None = None) -> set[str]:
    return {str(c) for c in run(text, fp, setup).spec.goal().conditions}


def subtask_of(spec: TaskSpec, condition: str) -> Any:
    return next(s for s in spec.subtasks if condition in {str(c) for c in s.goal})


# ---- 1. locative modifiers vs destinations ------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("the mug on the counter needs to go in the sink", 1, {"inside(Mug, SinkBasin)"}),
    ("the cup in the cabinet belongs on the dining table", 15, {"inside(Cup, DiningTable)"}),
    ("the apple on the counter should be in the fridge", 7, {"inside(Apple, Fridge)"}),
    ("the book on the desk has to end up on the bed", 303, {"inside(Book, Bed)"}),
    ("could the remote on the coffee table go in the box?", 201, {"inside(RemoteControl, Box)"}),
    ("the lettuce sitting on the counter should really be in the fridge", 2,
     {"inside(Lettuce, Fridge)"}),
    ("the bread on the counter and the egg on the table need to go in the fridge", 4,
     {"inside(Bread, Fridge)", "inside(Egg, Fridge)"}),
])
def test_a_place_inside_the_subject_is_where_it_is_not_where_it_goes(
        text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_a_locative_modifier_picks_the_instance() -> None:
    # FloorPlan209 has four vases; Vase_1 is the one on the coffee table
    assert goal("the vase on the coffee table goes in the box", 209) == {"inside(Vase_1, Box)"}


def test_without_a_predicate_the_place_is_the_destination() -> None:
    assert goal("bread on the plate", 1) == {"inside(Bread, Plate)"}
    assert goal("put the apple on the counter into the fridge", 7) == {"inside(Apple, Fridge)"}


# ---- 2. motion predicates without "put", gapping ---------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("the fork goes in the drawer, the spoon in the sink, and the spatula on the counter", 11,
     {"inside(Fork, Drawer)", "inside(Spoon, SinkBasin)", "inside(Spatula, CounterTop)"}),
    ("potato and tomato belong in the fridge", 12,
     {"inside(Potato, Fridge)", "inside(Tomato, Fridge)"}),
    ("the keys should live in the drawer from now on", 212, {"inside(KeyChain, Drawer)"}),
    ("leave the laptop on the desk and the phone on the bed", 310,
     {"inside(Laptop, Desk)", "inside(CellPhone, Bed)"}),
    ("plate, bowl and cup into the sink, please", 22,
     {"inside(Plate, SinkBasin)", "inside(Bowl, SinkBasin)", "inside(Cup, SinkBasin)"}),
    ("pack both CDs into the box", 303, {"inside(2 of CD, Box)"}),
    ("stow the pan in the cabinet", 6, {"inside(Pan, Cabinet)"}),
    ("drop the sponge in the sink", 1, {"inside(DishSponge, SinkBasin)"}),
    ("the egg and the lettuce go back in the fridge, the ladle in the drawer", 25,
     {"inside(Egg, Fridge)", "inside(Lettuce, Fridge)", "inside(Ladle, Drawer)"}),
    ("I left a book on the sofa. Could you shelve it?", 201, {"inside(Book, Shelf)"}),
])
def test_motion_predicates_and_gapping(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_objects_of_one_clause_moved_to_two_places_are_both_final() -> None:
    """"the toilet paper on the holder, the spare roll on the shelf": two objects, not one
    object moved twice (which would make the first placement intermediate)."""
    assert goal("The toilet paper goes on the holder, and the spare roll on the shelf.", 401) == {
        "inside(ToiletPaper, ToiletPaperHanger)", "inside(ToiletPaper, Shelf)"}


# ---- 3. vague umbrella verbs followed by specifics ---------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Tidy up: the book goes on the shelf, the remote in the box.", 201,
     {"inside(Book, Shelf)", "inside(RemoteControl, Box)"}),
    ("Sort out the kitchen - fridge shut, lights off.", 1,
     {"closed(Fridge)", "switched_off(LightSwitch)"}),
    ("Clean up the desk: pen and pencil in the drawer.", 305,
     {"inside(Pen, Drawer)", "inside(Pencil, Drawer)"}),
    ("Could you tidy the kitchen a bit? The apple goes in the fridge.", 3,
     {"inside(Apple, Fridge)"}),
    ("Make the bed and turn off the lamp.", 303, {"switched_off(DeskLamp)"}),
])
def test_a_vague_clause_is_skipped_with_a_note_when_others_say_what_to_do(
        text: str, fp: int, expected: set[str]) -> None:
    result = run(text, fp)
    assert {str(c) for c in result.spec.goal().conditions} == expected
    assert result.notes and all(n.kind == "vague" and "vague" in n.reason for n in result.notes)


def test_a_clear_instruction_has_no_notes() -> None:
    assert run("put the apple in the fridge").notes == ()


@pytest.mark.parametrize("text", ["tidy up the kitchen", "sort out the living room",
                                  "clean up the desk", "organise things"])
def test_nothing_actionable_is_still_an_error(text: str) -> None:
    with pytest.raises(OfflineParseError, match="vague"):
        run(text, 303)


# ---- 4. verbless state lists -------------------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("lights off, blinds down, fridge closed", 15,
     {"switched_off(LightSwitch)", "closed(Blinds)", "closed(Fridge)"}),
    ("blinds up, lights on", 303, {"open(Blinds)", "switched_on(LightSwitch)"}),
    ("TV off, desk lamp off and the laptop shut", 201,
     {"switched_off(Television)", "switched_off(DeskLamp)", "closed(Laptop)"}),
    ("I'm heading to bed: lamp off, blinds down, TV off.", 226,
     {"switched_off(FloorLamp)", "closed(3 of Blinds)", "switched_off(Television)"}),
    ("fridge door shut and the blinds up, please", 28, {"closed(Fridge)", "open(Blinds)"}),
])
def test_verbless_state_lists(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_a_wish_reaches_over_commas_and_is_not_read_as_a_complaint() -> None:
    """"make sure X is closed, Y is off": Y is wished too (a bare "Y is off" would be a
    complaint and become "on")."""
    assert goal("Would someone please make sure the fridge is closed, the stove is off and "
                "the blinds are down?", 18) == {
        "closed(Fridge)", "switched_off(StoveKnob)", "closed(Blinds)"}


# ---- 5. wishes, results, dishes --------------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("I'd like a cold apple.", 1, {"cold(Apple)"}),
    ("I want my coffee hot.", 6, {"filled(Mug, coffee)", "hot(Mug)"}),
    ("Get a hot potato ready.", 2, {"hot(Potato)"}),
    ("A cooked egg would be great.", 3, {"cooked(Egg)"}),
    ("Bring me a chilled tomato on a plate.", 4, {"cold(Tomato)", "inside(Tomato, Plate)"}),
    ("Bring me a cold apple.", 1, {"cold(Apple)", "held(Apple)"}),
    ("A boiled egg, please.", 8, {"cooked(Egg)"}),
    ("Make me a boiled egg, please.", 15, {"cooked(Egg)"}),
    ("I need a clean plate on the counter.", 13, {"clean(Plate)", "inside(Plate, CounterTop)"}),
    ("I fancy a baked potato.", 22, {"cooked(Potato)"}),
    ("I'd like an apple.", 1, {"held(Apple)"}),
    ("I'd love some toast with my coffee.", 18,
     {"sliced(Bread)", "cooked(Bread)", "filled(Mug, coffee)", "hot(Mug)"}),
])
def test_wishes_name_states_to_reach(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_a_definite_adjective_picks_the_object_it_does_not_ask_for_the_state() -> None:
    scene = load_scene(209)
    team = parse_team("1,2")
    state = initial_state({}, scene, team)
    state.objects["Vase_3"].is_broken = True
    spec = FRONTEND.decompose("bring me the broken vase", scene, state, team)
    assert {str(c) for c in spec.goal().conditions} == {"held(Vase_3)"}


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("I'd love two slices of toast.", 7, {"sliced(Bread)", "cooked(2 of BreadSliced)"}),
    ("Toast 2 slices of bread and put them on the plate.", 1,
     {"sliced(Bread)", "cooked(2 of BreadSliced)", "inside(2 of BreadSliced, Plate)"}),
    ("I'd like my toast on a plate please.", 28,
     {"sliced(Bread)", "cooked(Bread)", "inside(BreadSliced, Plate)"}),
    # boiling and frying happen on a burner, and the pot, kettle or pan stays there (the
    # ground truth of the round-14 and round-22 blind sets)
    ("Boil water in the pot.", 12, {"filled(Pot, water)", "hot(Pot)", "inside(Pot, StoveBurner)"}),
    ("Boil some water.", 17, {"filled(Kettle, water)", "hot(Kettle)", "inside(Kettle, StoveBurner)"}),
    ("Boil the kettle.", 17, {"filled(Kettle, water)", "hot(Kettle)", "inside(Kettle, StoveBurner)"}),
    ("Bring me a coffee.", 1, {"filled(Mug, coffee)", "hot(Mug)", "held(Mug)"}),
])
def test_dishes_toast_coffee_and_boiled_water(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_a_wish_a_later_clause_fulfils_adds_no_subtask() -> None:
    """"a warm slice of bread - toast some": toasting heats it; the wish introduced it."""
    assert goal("I'd love a warm slice of bread - toast some for me, would you?", 21) == {
        "sliced(Bread)", "cooked(Bread)"}
    assert goal("I'd love a warm slice of bread.", 21) == {"hot(BreadSliced)"}


def test_more_toast_than_the_bread_gives_is_a_grounding_error() -> None:
    with pytest.raises(GroundingError):
        run("I'd love five slices of toast", 7)     # a loaf gives three


# ---- 6. discourse reference and instance binding ------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("There's a bottle of wine in the cupboard. Put it in the fridge.", 1,
     {"inside(WineBottle, Fridge)"}),
    ("There's a bottle of wine in the cupboard; can you chill it?", 1, {"cold(WineBottle)"}),
    ("There is an apple in the bowl. Put it in the fridge.", 1, {"inside(Apple, Fridge)"}),
    ("Wash the plate, the bowl and the mug and put all three in the cabinet.", 4,
     {"clean(Plate)", "clean(Bowl)", "clean(Mug)", "inside(Plate, Cabinet)",
      "inside(Bowl, Cabinet)", "inside(Mug, Cabinet)"}),
    ("Grab the fork and the spoon and put both of them in the drawer.", 5,
     {"inside(Fork, Drawer)", "inside(Spoon, Drawer)"}),
    ("The pen, the pencil and the book: put them all on the desk.", 305,
     {"inside(Pen, Desk)", "inside(Pencil, Desk)", "inside(Book, Desk)"}),
    ("Collect the CDs and the keychain and put the lot in the box.", 303,
     {"inside(2 of CD, Box)", "inside(KeyChain, Box)"}),
    ("Put the book, the pen and the pencil in the drawer and then close it.", 310,
     {"inside(Book, Drawer)", "inside(Pen, Drawer)", "inside(Pencil, Drawer)",
      "closed(Drawer)"}),
])
def test_referents_introduced_by_statements_and_lists(text: str, fp: int,
                                                      expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_the_drawer_is_the_one_that_holds_the_object() -> None:
    """closed(Drawer) may already hold for another drawer: the parse names the one the
    remote is in, found in the state."""
    setup = [{"object": "RemoteControl_1", "parent": "Drawer_2"}]
    text = ("The remote is in one of the drawers. Get it out and put it on the sofa, then "
            "close the drawer again.")
    assert goal(text, 201, setup) == {"inside(RemoteControl, Sofa)", "closed(Drawer_2)"}
    # with the remote elsewhere, no drawer is singled out
    assert "closed(Drawer)" in goal(text, 201)


@pytest.mark.parametrize(("text", "fp", "setup", "expected"), [
    ("Grab the spoon out of the drawer it's in and shut that drawer.", 1,
     [{"object": "Spoon_1", "parent": "Drawer_4"}], {"held(Spoon)", "closed(Drawer_4)"}),
    ("Open the drawer the pen is in.", 8, [{"object": "Pen_1", "parent": "Drawer_6"}],
     {"open(Drawer_6)"}),
    ("The wine is somewhere in the cupboards. Take it out, put it in the fridge and close "
     "the cupboard.", 7, [{"object": "WineBottle_1", "parent": "Cabinet_3"}],
     {"inside(WineBottle, Fridge)", "closed(Cabinet_3)"}),
])
def test_instance_binding(text: str, fp: int, setup: list[dict[str, Any]],
                          expected: set[str]) -> None:
    assert goal(text, fp, setup) == expected


def test_a_destination_stays_a_type() -> None:
    """Only the receptacle acted on is bound to an instance; "put it in the drawer" may use
    any drawer."""
    setup = [{"object": "Spoon_1", "parent": "Drawer_4"}]
    assert goal("Take the spoon out of the drawer, wash it, and put the fork in the drawer.",
                1, setup) == {"inside(Fork, Drawer)"}


# ---- 7. universal quantifiers -----------------------------------------------------------
def test_everything_off_is_what_is_on_now() -> None:
    # FloorPlan201: the light switch and both lamps are on, the TV and laptop are off
    assert goal("turn everything off", 201) == {
        "switched_off(DeskLamp)", "switched_off(FloorLamp)", "switched_off(LightSwitch)"}
    # one of four burners on: that knob, by id
    assert goal("make sure everything is switched off", 1,
                [{"object": "StoveKnob_2", "is_on": True}]) == {
        "switched_off(LightSwitch)", "switched_off(StoveKnob_2)"}


def test_close_everything_is_what_is_open_now() -> None:
    assert goal("close everything, please", 209) == {"closed(Box)", "closed(Laptop)"}


def test_everything_when_nothing_is_on_is_a_grounding_error() -> None:
    with pytest.raises(GroundingError, match="nothing"):
        run("turn everything off", 1, [{"object": "LightSwitch_1", "is_on": False}])


def test_all_the_objects_of_a_type_is_every_instance() -> None:
    assert goal("put all the foil in the drawer", 21) == {"inside(3 of AluminumFoil, Drawer)"}
    assert goal("put every vase on the coffee table", 209) == {"inside(4 of Vase, CoffeeTable)"}


# ---- 8. darkness and daylight -------------------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("make it dark in here", 15, {"switched_off(LightSwitch)", "closed(Blinds)"}),
    ("it's way too bright in here", 226, {"switched_off(LightSwitch)",
                                          "switched_off(FloorLamp)", "closed(3 of Blinds)"}),
    ("make it dark, I want to watch a movie", 205,
     {"switched_off(LightSwitch)", "switched_off(DeskLamp)", "switched_off(FloorLamp)"}),
    ("dim the lights", 15, {"switched_off(LightSwitch)"}),
    ("let some light in", 303, {"open(Blinds)"}),
    ("open up the blinds", 226, {"open(3 of Blinds)"}),
])
def test_dark_closes_the_blinds_where_there_are_some(text: str, fp: int,
                                                     expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_curtains_that_cannot_close_are_the_blinds_where_there_are_some() -> None:
    assert goal("draw the curtains and turn off the lamp", 303) == {
        "closed(Blinds)", "switched_off(DeskLamp)"}
    with pytest.raises(GroundingError, match="curtains"):
        run("close the curtains", 201)      # curtains only: AI2-THOR's do not close


# ---- 9. container nouns and measure phrases ------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("put the rolls of foil in the drawer", 21, {"inside(3 of AluminumFoil, Drawer)"}),
    ("put two rolls of foil on the counter", 21, {"inside(2 of AluminumFoil, CounterTop)"}),
    ("put the foil rolls on the shelf", 21, {"inside(3 of AluminumFoil, Shelf)"}),
    ("put a head of lettuce in the fridge", 4, {"inside(Lettuce, Fridge)"}),
    ("put a roll of toilet paper on the shelf", 401, {"inside(ToiletPaper, Shelf)"}),
    ("put both rolls of toilet paper on the shelf", 401, {"inside(2 of ToiletPaper, Shelf)"}),
    ("put a bar of soap in the cabinet", 405, {"inside(SoapBar, Cabinet)"}),
    ("put the pair of boots in the box", 203, {"inside(Boots, Box)"}),
    ("put a bottle of wine in the fridge", 23, {"inside(WineBottle, Fridge)"}),
])
def test_measure_words_name_what_follows_of(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_more_bottles_than_the_scene_has_is_a_grounding_error() -> None:
    with pytest.raises(GroundingError, match="only 1"):
        run("chill two bottles of wine", 13)


# ---- 10. instruments and manner ------------------------------------------------------------
@pytest.mark.parametrize("text", [
    "cook the potato, the microwave is fine",
    "cook the potato in the microwave",
    "cook the potato using the microwave",
    "use the microwave to cook the potato",
])
def test_the_named_appliance_is_the_means_never_a_goal(text: str) -> None:
    spec = run(text, 1).spec
    assert {str(c) for c in spec.goal().conditions} == {"cooked(Potato)"}
    means = [s for s in spec.subtasks if not s.final]
    assert [str(c) for c in means[0].goal] == ["inside(Potato, Microwave)", "switched_on(Microwave)"]
    assert means[0].id in subtask_of(spec, "cooked(Potato)").depends_on


def test_switching_the_appliance_off_when_done_is_a_final_state_after_the_cooking() -> None:
    spec = run("Cook the potato in the microwave and switch the microwave off when it's done.",
               5).spec
    assert {str(c) for c in spec.goal().conditions} == {"cooked(Potato)",
                                                         "switched_off(Microwave)"}
    off = subtask_of(spec, "switched_off(Microwave)")
    assert subtask_of(spec, "cooked(Potato)").id in off.depends_on


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("slice the bread with the big knife", 3, {"sliced(Bread)"}),
    ("slice the tomato with the knife on the counter", 10, {"sliced(Tomato)"}),
    ("use the stove to fry the egg", 2, {"cooked(Egg)"}),
    # cooking in a pan leaves the food in it (the ground truth of two blind sets): the
    # pan is where the egg goes, not a goal object of its own
    ("can you cook the egg? Use the pan on the stove.", 6, {"inside(Egg, Pan)", "cooked(Egg)", "inside(Pan, StoveBurner)"}),
    ("pop the potato in the microwave for a couple of minutes", 17, {"hot(Potato)"}),
])
def test_tools_are_not_goal_objects(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


# ---- 11. light verbs -------------------------------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("give the plate a rinse", 7, {"clean(Plate)"}),
    ("give the mug a good wash", 8, {"clean(Mug)"}),
    ("the pan could do with a scrub", 10, {"clean(Pan)"}),
    ("the pan on the stove needs a good scrub", 6, {"clean(Pan)"}),
    ("the cup could use a rinse", 13, {"clean(Cup)"}),
    ("leave the cup to dry on the counter", 11, {"inside(Cup, CounterTop)"}),
    ("give the bowl a quick clean and leave it to dry on the counter", 12,
     {"clean(Bowl)", "inside(Bowl, CounterTop)"}),
])
def test_light_verbs_are_the_verb_they_name(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


# ---- 12. verb-particle placement -------------------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("put the book up on the shelf", 201, {"inside(Book, Shelf)"}),
    ("put the knife away in the drawer", 17, {"inside(Knife, Drawer)"}),
    ("tuck the credit card into the drawer", 10, {"inside(CreditCard, Drawer)"}),
    ("take the apple out of the fridge, slice it and put it back", 18,
     {"sliced(Apple)", "inside(Apple, Fridge)"}),
    ("open the box, put the remote inside, and close it again", 201,
     {"inside(RemoteControl, Box)", "closed(Box)"}),
    ("crack an egg into the pan", 23, {"sliced(Egg)", "inside(EggCracked, Pan)"}),
    ("microwave the potato and then put it on a plate on the table", 17,
     {"hot(Potato)", "inside(Potato, Plate)"}),
])
def test_particles_and_places(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_put_back_without_a_known_origin_is_skipped_or_an_error() -> None:
    with pytest.raises(OfflineParseError, match="back"):
        run("put the apple back", 1)


# ---- politeness, justifications, team subjects, ellipsis, self-corrections -----------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Would you be able to put the salt and pepper in the cabinet?", 20,
     {"inside(SaltShaker, Cabinet)", "inside(PepperShaker, Cabinet)"}),
    ("I was wondering if you could slice the tomato?", 22, {"sliced(Tomato)"}),
    ("Turn off the TV, it's giving me a headache.", 212, {"switched_off(Television)"}),
    ("Turn off the desk lamp before bed.", 301, {"switched_off(DeskLamp)"}),
    ("Put the apple in the fridge and, while you're at it, slice the bread.", 3,
     {"inside(Apple, Fridge)", "sliced(Bread)"}),
    ("Could one robot put the apple in the fridge while another turns off the light?", 6,
     {"inside(Apple, Fridge)", "switched_off(LightSwitch)"}),
    ("Put the apple in the fridge. Oh, and the tomato too.", 1,
     {"inside(Apple, Fridge)", "inside(Tomato, Fridge)"}),
    ("Wash the lettuce and put in the fridge.", 11, {"inside(Lettuce, Fridge)"}),
    ("Turn the TV on and the lights off - movie time!", 218,
     {"switched_on(Television)", "switched_off(LightSwitch)"}),
])
def test_framing_that_is_not_a_goal(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("The lettuce goes into the fridge and so does the tomato.", 4,
     {"inside(Lettuce, Fridge)", "inside(Tomato, Fridge)"}),
    ("Put the egg in the fridge. The tomato should too.", 4,
     {"inside(Egg, Fridge)", "inside(Tomato, Fridge)"}),
    ("Straighten up in here - laptop on the dresser, remote on the sofa.", 205,
     {"inside(Laptop, Dresser)", "inside(RemoteControl, Sofa)"}),
    ("Fry the egg - use the pan on the stove.", 27, {"inside(Egg, Pan)", "cooked(Egg)", "inside(Pan, StoveBurner)"}),
    ("Leave the fridge closed and the light on.", 10,
     {"closed(Fridge)", "switched_on(LightSwitch)"}),
    ("Could I have a cold glass of water?", 12,
     {"filled(Cup, water)", "cold(Cup)", "held(Cup)"}),
])
def test_elliptical_and_coordinated_requests(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_it_for_an_object_the_scene_lacks_names_that_object() -> None:
    """FloorPlan20 has no phone: the error is about the phone, not about "it"."""
    with pytest.raises(GroundingError) as err:
        run("My phone is on the counter somewhere. Could you get it?", 20)
    assert err.value.phrase == "phone"


def test_so_it_is_cold_keeps_the_state_it_names() -> None:
    """A purpose naming a state of the object just moved is kept: it is what the fridge is
    for (``cold(X)`` and ``inside(X, Fridge)`` are equivalent in the evaluation)."""
    assert goal("Put the tomato in the fridge so it's cold for dinner.", 27) == {
        "inside(Tomato, Fridge)", "cold(Tomato)"}


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Put the bread in the fridge? No, on the counter.", 3, {"inside(Bread, CounterTop)"}),
    ("Put the phone on the desk... I mean, put the phone in the drawer.", 10,
     {"inside(CellPhone, Drawer)"}),
    ("Put the tennis racket in the box, no wait, on the bed.", 310,
     {"inside(TennisRacket, Bed)"}),
])
def test_self_corrections_replace_what_they_correct(text: str, fp: int,
                                                    expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_no_is_not_a_correction_inside_a_sentence() -> None:
    assert goal("nobody needs the lights on", 1) == {"switched_off(LightSwitch)"}
    assert goal("no one is watching the tv, turn it off", 201) == {"switched_off(Television)"}


# ---- robustness --------------------------------------------------------------------------------
def test_a_repeated_object_in_a_chain_is_a_valid_spec_not_a_cycle() -> None:
    """held(Mug), filled(Mug), held(Mug) again: the duplicate depends on something after
    the first; merging them would make a cycle."""
    spec = run("Take the mug, fill it with coffee and bring it to me.", 15).spec
    assert {str(c) for c in spec.goal().conditions} == {"filled(Mug, coffee)", "held(Mug)"}
    assert len({s.id for s in spec.subtasks}) == len(spec.subtasks)


#: words of the phenomena above, for the word-salad robustness test
_WORDS = [
    "put", "the", "apple", "in", "fridge", "slice", "it", "them", "all", "three",
    "both", "of", "lot", "there", "is", "a", "bottle", "wine", "cupboard", "no", "wait",
    "i", "mean", "on", "the", "counter", "everything", "off", "blinds", "down",
    "lights", "dark", "toast", "two", "slices", "coffee", "boil", "water", "pot",
    "give", "rinse", "the", "drawer", "it's", "in", "tidy", "up", ",", ".", "?", "-",
    "and", "then", "before", "after", "while", "so", "close", "shut", "open", "back",
    "away", "one", "of", "you", "the", "other", "roll", "rolls", "foil", "head",
    "lettuce", "pair", "boots", "microwave", "is", "fine", "use", "to", "would", "like",
    "cold", "warm", "hot"
]


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.sampled_from(_WORDS), min_size=1, max_size=16),
       st.sampled_from([1, 15, 21, 201, 303, 414]))
def test_any_word_salad_gives_a_spec_or_a_typed_error(words: list[str], fp: int) -> None:
    try:
        spec = run(" ".join(words), fp).spec
    except EmboTeamError as exc:
        assert str(exc) and "\n" not in str(exc)
    else:
        assert spec.subtasks


@pytest.mark.parametrize("text", ["use everything", "use all the things on the table"])
def test_use_with_no_tool_type_gives_a_spec_or_a_typed_error(text: str) -> None:
    # a word salad once found it: "use" before a noun of no object type ("everything")
    # raised an IndexError where a tool was looked up
    with contextlib.suppress(EmboTeamError):
        assert run(text).spec.subtasks


# ---- pronoun chains -------------------------------------------------------------------------
@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Put the pen and the pencil into the box, close it, and put it on the bed.", 303,
     {"inside(Pen, Box)", "inside(Pencil, Box)", "closed(Box)", "inside(Box, Bed)"}),
    ("put the apple in the fridge and close it, then slice it", 1,  # a fridge cannot be sliced
     {"inside(Apple, Fridge)", "closed(Fridge)", "sliced(Apple)"}),
])
def test_a_chain_of_it_keeps_its_referent_while_it_fits(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected
