"""Groundings reused across states (pddl/recorded.py): a kept grounding is taken only when
the state answers every question it asked as before, and then equals a fresh one."""

from __future__ import annotations

from emboteam.pddl.domain import Universe, ground_action
from emboteam.sim.rules import apply_action
from emboteam.world.actions import Action, Skill
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

GO_FRIDGE = Action(skill=Skill.GoToObject, target="Fridge_1")
GO_APPLE = Action(skill=Skill.GoToObject, target="Apple_1")
PICK_APPLE = Action(skill=Skill.PickupObject, target="Apple_1")
OPEN_FRIDGE = Action(skill=Skill.OpenObject, target="Fridge_1")


def fresh() -> WorldState:
    return WorldState.from_scene(load_scene("FloorPlan1"), parse_team("1,1"))


def test_a_state_that_answers_alike_reuses_the_grounding() -> None:
    start = fresh()
    universe = Universe(start.copy())
    first = ground_action("robot1", GO_FRIDGE, start, universe=universe.at(start))
    later = start.copy()
    apply_action(later, "robot1b", OPEN_FRIDGE)  # robot1b does what robot1's drive does not look at
    again = ground_action("robot1", GO_FRIDGE, later, universe=universe.at(later))
    assert again is first
    assert again == ground_action("robot1", GO_FRIDGE, later)  # as grounded from scratch


def test_a_changed_answer_grounds_again_and_both_are_kept() -> None:
    start = fresh()
    universe = Universe(start.copy())
    at_start = ground_action("robot1", GO_FRIDGE, start, universe=universe.at(start))
    moved = start.copy()
    apply_action(moved, "robot1", GO_APPLE)  # robot1 now reaches other things than at its start
    there = ground_action("robot1", GO_FRIDGE, moved, universe=universe.at(moved))
    assert there != at_start
    assert there == ground_action("robot1", GO_FRIDGE, moved)
    # both states keep their own grounding
    assert ground_action("robot1", GO_FRIDGE, start, universe=universe.at(start)) is at_start
    assert ground_action("robot1", GO_FRIDGE, moved, universe=universe.at(moved)) is there


def test_a_fluent_the_step_reads_is_asked_again() -> None:
    s = fresh()
    apply_action(s, "robot1", GO_APPLE)
    universe = Universe(s.copy())
    before = ground_action("robot1", PICK_APPLE, s, universe=universe.at(s))
    closer = s.copy()
    apply_action(closer, "robot1b", GO_APPLE)  # robot1b now stands at the apple too: its 'at' goes
    after = ground_action("robot1", PICK_APPLE, closer, universe=universe.at(closer))
    assert after == ground_action("robot1", PICK_APPLE, closer)
    assert after != before
