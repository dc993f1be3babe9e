"""Goal conditions: the text syntax, the checker (per-condition results, GCR), validation."""

from __future__ import annotations

import pytest

from emboteam.errors import EmboTeamError, GoalSyntaxError
from emboteam.sim import apply_action, check_action
from emboteam.world import (
    Action,
    Condition,
    Goal,
    GoalValidationError,
    ObjectRef,
    Predicate,
    Skill,
    WorldState,
    check_goal,
    load_scene,
    validate_goal,
)

# ---- the parser ------------------------------------------------------------------------


@pytest.mark.parametrize(("text", "predicate", "subject", "receptacle"), [
    ("inside(Apple, Fridge)", Predicate.inside, "Apple", "Fridge"),
    ("in(Apple, Fridge)", Predicate.inside, "Apple", "Fridge"),
    ("on(Plate, DiningTable)", Predicate.inside, "Plate", "DiningTable"),
    ("contains(Fridge, Apple)", Predicate.inside, "Apple", "Fridge"),  # the fridge contains it
    ("INSIDE( Apple_1 , Fridge_1 )", Predicate.inside, "Apple_1", "Fridge_1"),
    ("on(LightSwitch)", Predicate.switched_on, "LightSwitch", None),
    ("turned_on(Television)", Predicate.switched_on, "Television", None),
    ("off(LightSwitch)", Predicate.switched_off, "LightSwitch", None),
    ("turned_off(Faucet)", Predicate.switched_off, "Faucet", None),
    ("opened(Fridge)", Predicate.open, "Fridge", None),
    ("closed(Box)", Predicate.closed, "Box", None),
    ("picked(Pillow)", Predicate.held, "Pillow", None),
    ("sliced(Lettuce_1)", Predicate.sliced, "Lettuce_1", None),
    ("cooked(Apple_1_Slice_2)", Predicate.cooked, "Apple_1_Slice_2", None),
    ("hot(Mug)", Predicate.hot, "Mug", None),
    ("dirty(Bowl)", Predicate.dirty, "Bowl", None),
])
def test_parse_aliases(text: str, predicate: Predicate, subject: str, receptacle: str | None) -> None:
    c = Condition.parse(text)
    assert c.predicate is predicate
    assert str(c.subject) == subject
    assert (str(c.receptacle) if c.receptacle else None) == receptacle


def test_parse_ids_types_and_unions() -> None:
    assert Condition.parse("broken(Vase_2)").subject == ObjectRef(id="Vase_2")
    assert Condition.parse("broken(Vase)").subject == ObjectRef(types=("Vase",))
    c = Condition.parse("inside(Potato|Lettuce|Tomato, Fridge|Bowl)")
    assert c.subject.types == ("Potato", "Lettuce", "Tomato")
    assert c.receptacle is not None and c.receptacle.types == ("Fridge", "Bowl")


@pytest.mark.parametrize("text", ["inside(2 of Apple, Fridge)", "inside(2x Apple, Fridge)",
                                  "inside(2 * Apple, Fridge)", "contains(Fridge, 2 of Apple)"])
def test_parse_counts(text: str) -> None:
    c = Condition.parse(text)
    assert c.count == 2 and c.subject.types == ("Apple",)


def test_parse_filled_with_a_liquid() -> None:
    assert Condition.parse("filled(Mug, Coffee)").liquid == "coffee"
    assert Condition.parse("filled(Mug)").liquid is None


@pytest.mark.parametrize("text", [
    "inside(Apple, Fridge)", "inside(2 of Apple|Tomato, CounterTop)", "switched_off(LightSwitch)",
    "filled(Mug_1, coffee)", "sliced(Bread_1)",
])
def test_text_form_round_trips(text: str) -> None:
    c = Condition.parse(text)
    assert Condition.parse(str(c)) == c


@pytest.mark.parametrize(("text", "match"), [
    ("fly(Apple)", "unknown predicate 'fly'"),
    ("inside(Apple)", "two arguments"),
    ("sliced(Apple, Knife)", "one argument"),
    ("inside(Apple, )", "empty object reference"),
    ("Apple in Fridge", "not a condition"),
    ("sliced(Apple-1)", "not an object id or type"),
    ("inside(2 of Apple_1, Fridge)", "count applies to a type"),
    ("inside(0 of Apple, Fridge)", "greater than or equal to 1"),
    ("", "not a condition"),
])
def test_parse_errors_are_typed(text: str, match: str) -> None:
    with pytest.raises(GoalSyntaxError, match=match):
        Condition.parse(text)
    assert issubclass(GoalSyntaxError, EmboTeamError)


def test_goal_parse_splits_conjunctions() -> None:
    g = Goal.parse("sliced(Lettuce) & inside(Lettuce, Fridge); off(LightSwitch)")
    assert [c.predicate for c in g.conditions] == [Predicate.sliced, Predicate.inside, Predicate.switched_off]
    assert Goal.parse(str(g)) == g
    assert Goal.parse(["open(Fridge)", "hot(Potato)"]).conditions[1].predicate is Predicate.hot


# ---- the checker -----------------------------------------------------------------------


@pytest.fixture
def state() -> WorldState:
    from emboteam.world import parse_team
    return WorldState.from_scene(load_scene("FloorPlan1"), parse_team("1"))


def _do(state: WorldState, skill: Skill, target: str, receptacle: str | None = None) -> None:
    """Walk to the target (or receptacle) and do the action, which must be allowed."""
    where = receptacle or target
    if state.objects[where].held_by is None:
        apply_action(state, "robot1", Action(skill=Skill.GoToObject, target=where))
    action = Action(skill=skill, target=target, receptacle=receptacle)
    assert check_action(state, "robot1", action) is None, action
    apply_action(state, "robot1", action)


def _holds(state: WorldState, text: str) -> bool:
    return check_goal(Goal.parse(text), state).success


def test_inside_over_types_and_ids_transitively(state: WorldState) -> None:
    assert _holds(state, "inside(Egg, Fridge)") and _holds(state, "inside(Egg_1, Fridge_1)")
    assert not _holds(state, "inside(Apple, Fridge)")
    # an apple on a plate in the fridge is in the fridge
    _do(state, Skill.PickupObject, "Apple_1")
    state.move_object("Plate_1", "CounterTop_2")
    _do(state, Skill.PutObject, "Apple_1", "Plate_1")
    _do(state, Skill.PickupObject, "Plate_1")
    _do(state, Skill.OpenObject, "Fridge_1")
    _do(state, Skill.PutObject, "Plate_1", "Fridge_1")
    assert _holds(state, "inside(Apple, Fridge)") and _holds(state, "on(Apple_1, Plate)")
    assert _holds(state, "contains(Fridge_1, Apple_1)")


def test_sink_and_sinkbasin_are_the_same_place(state: WorldState) -> None:
    _do(state, Skill.PickupObject, "Apple_1")
    _do(state, Skill.PutObject, "Apple_1", "SinkBasin_1")
    for text in ("inside(Apple, Sink)", "inside(Apple, SinkBasin)", "inside(Apple_1, Sink_1)",
                 "inside(Apple_1, SinkBasin_1)"):
        assert _holds(state, text), text


def test_counts_give_partial_credit(state: WorldState) -> None:
    goal = Goal.parse("inside(2 of Apple|Tomato, Fridge) & off(LightSwitch)")
    report = check_goal(goal, state)
    assert [r.satisfied for r in report.results] == [0, 0]
    assert report.gcr == 0.0 and not report.success
    _do(state, Skill.OpenObject, "Fridge_1")
    _do(state, Skill.PickupObject, "Tomato_1")
    _do(state, Skill.PutObject, "Tomato_1", "Fridge_1")
    report = check_goal(goal, state)
    assert report.results[0].satisfied == 1 and report.results[0].required == 2
    assert report.results[0].witnesses == ("Tomato_1",) and not report.results[0].holds
    assert report.gcr == pytest.approx(1 / 3)
    assert report.unmet() == list(goal.conditions)
    _do(state, Skill.PickupObject, "Apple_1")
    _do(state, Skill.PutObject, "Apple_1", "Fridge_1")
    _do(state, Skill.SwitchOff, "LightSwitch_1")
    report = check_goal(goal, state)
    assert report.success and report.gcr == 1.0 and report.unmet() == []
    assert "ok " in str(report.results[0]) and "(2/2)" in str(report.results[0])


def test_gcr_never_exceeds_one_with_surplus_instances(state: WorldState) -> None:
    _do(state, Skill.SwitchOff, "LightSwitch_1")
    report = check_goal(Goal.parse("off(StoveKnob)"), state)  # 4 knobs off, 1 required
    assert report.results[0].satisfied == 4 and report.gcr == 1.0


def test_slices_match_their_whole(state: WorldState) -> None:
    _do(state, Skill.PickupObject, "ButterKnife_1")
    assert not _holds(state, "sliced(Bread)")
    _do(state, Skill.SliceObject, "Bread_1")
    assert _holds(state, "sliced(Bread)") and _holds(state, "sliced(Bread_1)")
    # sliced counts wholes, not their pieces
    assert check_goal(Goal.parse("sliced(Bread)"), state).results[0].satisfied == 1
    # the pieces stand for the bread on the counter; the deactivated whole does not
    report = check_goal(Goal.parse("inside(Bread, CounterTop)"), state)
    assert set(report.results[0].witnesses) == {f"Bread_1_Slice_{k}" for k in (1, 2, 3)}
    assert _holds(state, "inside(2 of Bread, CounterTop)")
    assert _holds(state, "inside(BreadSliced, CounterTop)")
    # a toasted slice makes the bread cooked, by type and by the whole's id
    _do(state, Skill.PutObject, "ButterKnife_1", "CounterTop_2")
    _do(state, Skill.PickupObject, "Bread_1_Slice_1")
    _do(state, Skill.PutObject, "Bread_1_Slice_1", "Toaster_1")
    _do(state, Skill.SwitchOn, "Toaster_1")
    assert _holds(state, "cooked(Bread)") and _holds(state, "cooked(Bread_1)")
    assert _holds(state, "cooked(Bread_1_Slice_1)") and not _holds(state, "cooked(Bread_1_Slice_2)")


@pytest.mark.parametrize(("before", "skill", "target", "after"), [
    ("closed(Fridge_1)", Skill.OpenObject, "Fridge_1", "open(Fridge)"),
    ("switched_on(LightSwitch_1)", Skill.SwitchOff, "LightSwitch_1", "off(LightSwitch)"),
    ("switched_off(Faucet)", Skill.SwitchOn, "Faucet_1", "on(Faucet)"),
    ("clean(Vase_1)", Skill.BreakObject, "Vase_1", "broken(Vase)"),
    ("closed(Microwave)", Skill.PickupObject, "Mug_1", "held(Mug)"),
])
def test_unary_predicates(state: WorldState, before: str, skill: Skill, target: str, after: str) -> None:
    assert _holds(state, before)
    assert not _holds(state, after)
    _do(state, skill, target)
    assert _holds(state, after)


def test_temperature_dirt_and_liquids(state: WorldState) -> None:
    mug = state.objects["Mug_1"]
    assert _holds(state, "cold(Egg)") and not _holds(state, "hot(Mug)")
    mug.is_dirty = True
    assert _holds(state, "dirty(Mug)") and not _holds(state, "clean(Mug_1)")
    mug.liquid = "coffee"
    assert _holds(state, "filled(Mug)") and _holds(state, "filled(Mug, coffee)")
    assert not _holds(state, "filled(Mug, water)")
    state.objects["Potato_1"].is_cooked = True
    assert _holds(state, "cooked(Potato)")


# ---- validation against a scene ---------------------------------------------------------


@pytest.mark.parametrize("text", [
    "inside(Apple, Fridge) & sliced(Lettuce) & off(LightSwitch)",
    "cooked(Bread)",                   # bread cooks as toast
    "inside(3 of AppleSliced, Plate)",  # pieces an apple can be cut into
    "cooked(Potato_1_Slice_2)",         # a piece that will exist
    "inside(Apple, Sink)",              # FloorPlan1's Sink is no receptacle; its basin is
    "filled(Mug, coffee) & hot(Mug) & clean(Mug) & held(Mug)",
    "inside(Egg_1, Fridge_1)",
])
def test_valid_goals_pass(text: str) -> None:
    validate_goal(Goal.parse(text), load_scene("FloorPlan1"))


@pytest.mark.parametrize(("text", "match"), [
    ("inside(Pillow, Fridge)", "has no Pillow"),
    ("inside(Apple, Bathtub)", "has no Bathtub"),
    ("sliced(Mug)", "no Mug here is sliceable"),
    ("cooked(Apple_1_Slice_2)", "no Apple_1_Slice_2 here is cookable"),  # apples do not cook
    ("open(Apple)", "no Apple here is openable"),
    ("on(Apple)", "toggleable"),
    ("inside(Apple, Knife)", "Knife is not a receptacle"),
    ("inside(5 of Apple, Fridge)", "has only 1 Apple"),
    ("broken(Apple_7)", "has no Apple_7"),
])
def test_validation_errors_name_the_problem(text: str, match: str) -> None:
    with pytest.raises(GoalValidationError, match=match):
        validate_goal(Goal.parse(text), load_scene("FloorPlan1"))


def test_validation_reports_every_problem_at_once() -> None:
    with pytest.raises(GoalValidationError) as err:
        validate_goal(Goal.parse("sliced(Mug) & inside(Pillow, Fridge)"), load_scene("FloorPlan1"))
    assert "Mug" in str(err.value) and "Pillow" in str(err.value)


def test_condition_hash_and_equality_follow_fields_after_a_copy() -> None:
    # a condition keeps its hash once worked out: a copy with another field must not share it
    a = Condition.parse("inside(Apple, Fridge)")
    seen = {a}
    moved = a.model_copy(update={"receptacle": ObjectRef(types=("Sink",))})
    again = Condition.parse("inside(Apple, Fridge)")
    assert again in seen and again == a and hash(again) == hash(a)
    assert moved not in seen and moved != a
    assert moved == Condition.parse("inside(Apple, Sink)") and hash(moved) == hash(Condition.parse("inside(Apple, Sink)"))
    assert a != "inside(Apple, Fridge)"
