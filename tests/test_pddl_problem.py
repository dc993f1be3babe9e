"""Problems rendered from the state and goal conditions: pruning, goal compilation,
name mapping, typed errors (no planner calls)."""

from __future__ import annotations

import pytest

from emboteam.pddl.errors import ImpossibleGoalError, PlannerInputError, UnknownGoalObjectError
from emboteam.pddl.goal_compiler import compile_condition
from emboteam.pddl.problem import build_problem
from emboteam.sim.rules import apply_action
from emboteam.world.actions import Action, Skill
from emboteam.world.goals import Condition, Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

C = Condition.parse


def fresh(team: str = "1", fp: str = "FloorPlan1") -> WorldState:
    return WorldState.from_scene(load_scene(fp), parse_team(team))


def test_objects_are_pruned_to_the_goal_and_what_encloses_it() -> None:
    s = fresh()
    s.move_object("Apple_1", "Cabinet_4")  # a closed cabinet: it must be declared to be opened
    p = build_problem(s, [C("inside(Apple, Fridge)")], ["robot1"])
    assert {"Apple_1", "Fridge_1", "Cabinet_4"} <= set(p.objects)
    assert "LightSwitch_1" not in p.objects and "Knife_1" not in p.objects
    assert not any("_Slice_" in o for o in p.objects)  # nothing is cut: no pieces
    assert len(p.objects) < 12 < len(s.objects)


def test_slicing_declares_knives_and_the_pieces_ahead() -> None:
    s = fresh()
    p = build_problem(s, [C("sliced(Bread)"), C("cooked(Bread)")], ["robot1"])
    init = p.text[:p.text.index("(:goal")]
    assert {"Knife_1", "ButterKnife_1"} <= set(p.objects)
    assert {f"Bread_1_Slice_{k}" for k in (1, 2, 3)} <= set(p.objects)
    assert "Toaster_1" in p.objects  # only bread slices cook: in the toaster
    assert "(piece-of Bread_1_Slice_2 Bread_1)" in init
    assert "(available Bread_1_Slice_2)" not in init  # not cut yet
    assert "(cookable Bread_1_Slice_2)" in init  # statics of pieces come from the catalogue


def test_sink_means_sink_or_basin() -> None:
    """AI2-THOR puts things in the SinkBasin; "Sink" in a goal means either (the Sink
    itself counts where it is a receptacle)."""
    s = fresh()
    part = compile_condition(C("inside(Potato, Sink)"), s, ["robot1"])
    expected = {o.id for o in s.of_type("Sink", "SinkBasin") if o.has("receptacle")}
    assert "SinkBasin_1" in expected and set(part.places) == expected
    assert "(within Potato_1 SinkBasin_1)" in part.formula


def test_any_instance_and_n_of_types() -> None:
    s = fresh("1", "FloorPlan201")
    one = compile_condition(C("inside(Book|Pen, Sofa)"), s, ["robot1"])
    assert one.formula.startswith("(or ") and {"Book_1", "Pen_1"} <= set(one.subjects)
    two = compile_condition(C("inside(2 of Book|Pen|Pencil, Sofa)"), s, ["robot1"])
    assert two.formula.count("(and (and") == 3  # the three pairs of three candidates
    held = compile_condition(C("held(Pillow)"), fresh("1,2", "FloorPlan201"), ["robot1", "robot2"])
    assert "(holding robot1 Pillow_1)" in held.formula and "(holding robot2 Pillow_1)" in held.formula


def test_a_slice_of_the_named_whole_satisfies_its_goal() -> None:
    s = fresh()
    part = compile_condition(C("inside(Apple_1, Fridge)"), s, ["robot1"], slices={"Apple_1"})
    assert "Apple_1_Slice_1" in part.subjects and "(available Apple_1_Slice_1)" in part.formula


def test_satisfied_conditions_commit_to_their_witnesses() -> None:
    s = fresh()
    part = compile_condition(C("closed(Cabinet)"), s, ["robot1"])
    assert part.satisfied and len(part.subjects) == 1
    wide = compile_condition(C("closed(Cabinet)"), s, ["robot1"], narrow=False)
    assert len(wide.subjects) > 1


def test_mass_capacity_becomes_can_lift_facts() -> None:
    s = fresh("7,1")  # robot7 lifts 0.08 kg
    p = build_problem(s, [C("inside(Apple, Fridge)")], ["robot7", "robot1"])
    assert "(can-lift robot1 Apple_1)" in p.text
    assert "(can-lift robot7 Apple_1)" not in p.text


def test_plans_map_back_to_exact_names() -> None:
    s = fresh()
    p = build_problem(s, [C("inside(Apple, Fridge)")], ["robot1"])
    steps = p.decode(["(GOTO ROBOT1 APPLE_1)", "(put robot1 apple_1 fridge_1)"])
    assert [(r, str(a)) for r, a in steps] == [("robot1", "GoToObject(Apple_1)"),
                                               ("robot1", "PutObject(Apple_1, Fridge_1)")]
    with pytest.raises(PlannerInputError):
        p.decode(["(fly robot1 apple_1)"])
    with pytest.raises(PlannerInputError):
        p.decode(["(goto robot1 banana_7)"])


def test_rendering_is_deterministic() -> None:
    goal = Goal.parse("inside(Apple, Fridge) & sliced(Bread) & hot(Potato)")
    a = build_problem(fresh("1,2"), goal.conditions, ["robot1", "robot2"]).text
    b = build_problem(fresh("1,2"), goal.conditions, ["robot1", "robot2"]).text
    assert a == b


def test_a_robot_holding_something_gets_a_place_to_put_it() -> None:
    s = fresh()
    apply_action(s, "robot1", Action(skill=Skill.GoToObject, target="Mug_1"))
    apply_action(s, "robot1", Action(skill=Skill.PickupObject, target="Mug_1"))
    p = build_problem(s, [C("switched_off(LightSwitch)")], ["robot1"])
    assert "Mug_1" in p.objects and "(holding robot1 Mug_1)" in p.text
    assert any(f"(can-place Mug_1 {o})" in p.text for o in p.objects)
    assert "(hand-empty robot1)" in p.text  # the release goal


@pytest.mark.parametrize(("goal", "error", "match"), [
    ("inside(Apple_9, Fridge)", UnknownGoalObjectError, "Apple_9"),
    ("inside(Apple, Fridge_7)", UnknownGoalObjectError, "Fridge_7"),
    ("sliced(Television)", ImpossibleGoalError, "Television"),
    ("switched_on(Apple)", ImpossibleGoalError, "toggleable"),
    ("dirty(Mug)", ImpossibleGoalError, "dirty"),
    ("inside(5 of Apple, Fridge)", ImpossibleGoalError, "only"),
    ("inside(Apple, Apple)", ImpossibleGoalError, "receptacle"),
    ("filled(Mug, wine)", ImpossibleGoalError, "wine"),
])
def test_impossible_or_unknown_goals_are_typed_errors(goal: str, error: type[Exception], match: str) -> None:
    with pytest.raises(error, match=match):
        build_problem(fresh(), [C(goal)], ["robot1"])


def test_hot_in_the_fridge_is_refused_before_the_search() -> None:
    """A fridge cools what it holds: the same tomato cannot end hot in it (Fast Downward
    would spend its whole time limit failing to prove that)."""
    s = fresh("1", "FloorPlan2")
    assert len(list(s.of_type("Tomato"))) == 1
    with pytest.raises(ImpossibleGoalError, match="cools what it holds"):
        build_problem(s, [C("hot(Tomato)"), C("inside(Tomato, Fridge)")], ["robot1"])


def test_hot_and_in_the_fridge_are_fine_for_different_objects() -> None:
    s = fresh("1", "FloorPlan2")
    p = build_problem(s, [C("hot(Potato)"), C("inside(Tomato, Fridge)")], ["robot1"])
    assert {"Potato_1", "Tomato_1", "Fridge_1"} <= set(p.objects)
