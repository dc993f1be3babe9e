"""The PDDL domain and its grounding into plan-step literals (no planner calls)."""

from __future__ import annotations

import re

import pytest

from emboteam.errors import EmboTeamError
from emboteam.pddl import vocabulary
from emboteam.pddl.domain import DERIVED, SCHEMA_BY_SKILL, SCHEMAS, domain_pddl, step_literals
from emboteam.pddl.literal import Literal
from emboteam.sim.physics import switch
from emboteam.sim.rules import apply_action
from emboteam.world.actions import Action, Skill
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


def lit(text: str) -> Literal:
    neg = text.startswith("not ")
    pred, *args = text.removeprefix("not ").split()
    return Literal(predicate=pred, args=tuple(args), positive=not neg)


def fresh(team: str = "1", fp: str = "FloorPlan1") -> WorldState:
    return WorldState.from_scene(load_scene(fp), parse_team(team))


def do(state: WorldState, robot: str, skill: Skill, target: str, receptacle: str | None = None) -> None:
    apply_action(state, robot, Action(skill=skill, target=target, receptacle=receptacle))


def test_every_skill_has_exactly_one_action_schema() -> None:
    assert set(SCHEMA_BY_SKILL) == set(Skill)
    assert len(SCHEMAS) == len(Skill)


def test_domain_uses_only_vocabulary_predicates() -> None:
    """The BT compiler checks step literals against the vocabulary: the domain may use
    nothing else, and every derived predicate has a Python evaluator."""
    known = set(vocabulary.FLUENTS) | set(vocabulary.STATICS) | set(vocabulary.CAPABILITIES.values())
    text = domain_pddl()
    body = text[text.index("(:derived"):]
    used = set(re.findall(r"\((?:not \()?([a-z][a-z-]*) [?a-z]", body))
    keywords = {"and", "or", "not", "exists", "forall", "when", "imply", "derived", "action"}
    assert used - keywords <= known, used - keywords - known
    assert set(DERIVED) <= set(vocabulary.FLUENTS)


def test_put_into_a_closed_fridge_needs_it_open_and_cools() -> None:
    s = fresh()
    do(s, "robot1", Skill.GoToObject, "Apple_1")
    do(s, "robot1", Skill.PickupObject, "Apple_1")
    do(s, "robot1", Skill.GoToObject, "Fridge_1")
    pre, post = step_literals("robot1", Action(skill=Skill.PutObject, target="Apple_1", receptacle="Fridge_1"), s)
    for need in ("is-open Fridge_1", "at robot1 Fridge_1", "holding robot1 Apple_1", "can-place Apple_1 Fridge_1",
                 "not hidden Fridge_1", "can-put robot1"):
        assert lit(need) in pre, need
    for effect in ("in Apple_1 Fridge_1", "cold Apple_1", "hand-empty robot1", "not holding robot1 Apple_1",
                   "at robot1 Apple_1"):
        assert lit(effect) in post, effect
    assert not vocabulary.evaluate(lit("is-open Fridge_1"), s)  # so the BT's Pre check would catch it


def test_slicing_spawns_the_declared_pieces_where_the_whole_was() -> None:
    s = fresh()
    where = s.objects["Apple_1"].parent
    knife = "Knife_1"
    do(s, "robot1", Skill.GoToObject, knife)
    do(s, "robot1", Skill.PickupObject, knife)
    do(s, "robot1", Skill.GoToObject, "Apple_1")
    pre, post = step_literals("robot1", Action(skill=Skill.SliceObject, target="Apple_1"), s)
    assert lit(f"holding robot1 {knife}") in pre and lit(f"knife {knife}") in pre
    assert lit("not available Apple_1") in post and lit("sliced Apple_1") in post
    for k in (1, 2, 3):
        piece = f"Apple_1_Slice_{k}"
        assert lit(f"available {piece}") in post
        assert lit(f"in {piece} {where}") in post
        assert lit(f"at robot1 {piece}") in post
    do(s, "robot1", Skill.SliceObject, "Apple_1")
    assert all(vocabulary.evaluate(x, s) for x in post if vocabulary.observable(x))


def test_a_stove_knob_heats_and_cooks_what_is_in_the_pan_on_its_burner() -> None:
    s = fresh()
    knob = next(k for k in s.of_type("StoveKnob") if k.controls)
    burner = knob.controls[0]
    s.move_object("Pan_1", burner)
    s.move_object("Potato_1", "Pan_1")
    r = s.robots["robot1"]
    r.position = (knob.position[0], knob.position[2])
    _, post = step_literals("robot1", Action(skill=Skill.SwitchOn, target=knob.id), s)
    for effect in (f"is-on {knob.id}", f"is-on {burner}", "hot Potato_1", "cooked Potato_1", "hot Pan_1"):
        assert lit(effect) in post, effect


def test_microwave_interlock_and_broken_appliances_are_preconditions() -> None:
    s = fresh()
    do(s, "robot1", Skill.GoToObject, "Microwave_1")
    pre_on, _ = step_literals("robot1", Action(skill=Skill.SwitchOn, target="Microwave_1"), s)
    assert lit("not is-open Microwave_1") in pre_on and lit("not broken Microwave_1") in pre_on
    s.objects["Microwave_1"].is_on = True
    pre_open, _ = step_literals("robot1", Action(skill=Skill.OpenObject, target="Microwave_1"), s)
    assert lit("not is-on Microwave_1") in pre_open


def test_switching_a_knob_off_requires_it_to_be_the_last_one_on_its_burner() -> None:
    """A burner burns while any of its knobs is on: the domain only lets the last knob go
    off, so the burner's state after the step is certain (no iTHOR burner has two knobs;
    the test gives it one)."""
    s = fresh()
    k, k2 = [k for k in s.of_type("StoveKnob") if k.controls][:2]
    burner = k.controls[0]
    k2.controls = (burner,)
    switch(s, k, on=True)
    s.robots["robot1"].position = (k.position[0], k.position[2])
    pre, post = step_literals("robot1", Action(skill=Skill.SwitchOff, target=k.id), s)
    assert lit(f"not is-on {k2.id}") in pre
    assert vocabulary.evaluate(lit(f"not is-on {k2.id}"), s)
    assert lit(f"not is-on {burner}") in post
    switch(s, k2, on=True)
    assert not vocabulary.evaluate(lit(f"not is-on {k2.id}"), s)  # the step would be refused


def test_throw_lands_in_the_garbage_can_in_reach() -> None:
    s = fresh()
    do(s, "robot1", Skill.GoToObject, "Tomato_1")
    do(s, "robot1", Skill.PickupObject, "Tomato_1")
    do(s, "robot1", Skill.GoToObject, "GarbageCan_1")
    pre, post = step_literals("robot1", Action(skill=Skill.ThrowObject, target="Tomato_1"), s)
    assert lit("at robot1 GarbageCan_1") in pre and lit("in Tomato_1 GarbageCan_1") in post


def test_bad_actions_are_typed_errors() -> None:
    s = fresh()
    with pytest.raises(EmboTeamError, match="no object"):
        step_literals("robot1", Action(skill=Skill.GoToObject, target="Apple_9"), s)
    with pytest.raises(EmboTeamError, match="no robot"):
        step_literals("robot9", Action(skill=Skill.GoToObject, target="Apple_1"), s)
    with pytest.raises(EmboTeamError, match="knife"):
        step_literals("robot1", Action(skill=Skill.SliceObject, target="Apple_1"), s)
