"""Conditions the scene's start state settles (issue 25, cond25): "if the lamp's on, off
with it; if it's off, on". The branch whose condition holds at the start gives its goals,
the other gives none, and the condition's own state is no goal of its own. The sentences
are new, written for these tests (FloorPlan201 starts with the laptop open and the desk
lamp and the floor lamp on; a test may switch a device before reading)."""

from __future__ import annotations

import pytest

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline import OfflineFrontend
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

FRONTEND = OfflineFrontend()


def goal(text: str, off: tuple[str, ...] = (), shut: tuple[str, ...] = ()) -> set[str]:
    """The goal read in FloorPlan201, the types in ``off`` switched off and those in
    ``shut`` closed first."""
    scene = load_scene(201)
    team = parse_team("1,2")
    state = initial_state({}, scene, team)
    for o in state.objects.values():
        if o.type in off:
            o.is_on = False
        if o.type in shut:
            o.is_open = False
    spec = FRONTEND.decompose(text, scene, state, team)
    return {str(c) for c in spec.goal().conditions}


@pytest.mark.parametrize(("off", "expected"), [
    ((), "switched_off(DeskLamp)"),
    (("DeskLamp",), "switched_on(DeskLamp)"),
])
def test_the_branch_whose_condition_holds_is_read(off: tuple[str, ...], expected: str) -> None:
    # clauses._condition_then_state cuts "off with it" from its condition; idioms.json
    # reads "off with it" as "switch it off"; start_conditions checks the condition
    text = "Put the keys in the box. If the desk lamp's on, off with it; if it's off, on."
    assert goal(text, off) == {"inside(KeyChain, Box)", expected}


@pytest.mark.parametrize("shut", [(), ("Laptop",)])
def test_the_other_branch_after_if_not(shut: tuple[str, ...]) -> None:
    text = "The watch goes in a drawer. If the laptop is not open, open it; if not, leave it."
    read = goal(text, shut=shut)
    assert "inside(Watch, Drawer)" in read
    # open at the start: kept open (the failed branch asks what holds, "leave it"); shut: opened
    assert "open(Laptop)" in read
    assert "closed(Laptop)" not in read


def test_a_condition_that_fails_is_a_keep_and_no_goal() -> None:
    # the floor lamp is on: "if it's off, switch it on" changes nothing, the lamp is kept
    # as it is, and "off" (the condition) is not wished
    read = goal("Put the keys in the box. If the floor lamp is off, switch it on.")
    assert read == {"inside(KeyChain, Box)", "switched_on(FloorLamp)"}
    # a failed branch that would change the thing is dropped
    read = goal("Put the keys in the box. If the floor lamp is on, switch it off.", off=("FloorLamp",))
    assert read == {"inside(KeyChain, Box)", "switched_off(FloorLamp)"}


@pytest.mark.parametrize(("off", "expected"), [
    ((), "switched_off(FloorLamp)"),
    (("FloorLamp",), "switched_off(FloorLamp)"),
])
def test_a_condition_after_its_act(off: tuple[str, ...], expected: str) -> None:
    # "the floor lamp off if it's on": on, it is switched off; off, it stays off (a keep);
    # "on" (the condition) is never wished
    read = goal("Put the keys in the box. The floor lamp off if it's on; the desk lamp stays whatever it is now.", off)
    assert expected in read
    assert "switched_on(FloorLamp)" not in read
    assert "switched_on(DeskLamp)" in read     # "whatever it is now": as it is (on)


def test_a_condition_that_holds_and_is_only_kept_stays() -> None:
    # "if the desk lamp is on, that's how it should stay": the keep is the condition
    read = goal("Put the keys in the box. And if the desk lamp is on, that's how it should stay.")
    assert "switched_off(DeskLamp)" not in read
    assert "inside(KeyChain, Box)" in read


def test_off_with_it_inside_a_phrase_is_no_switch() -> None:
    # "get on with it" is no "switch it on": the idiom needs a clause of its own
    assert "switched_on(FloorLamp)" not in goal("Get on with it and put the keys in the box.")


def test_a_state_that_means_an_act_is_a_condition() -> None:
    # idioms.json: "open means you shut it" is "if it is open, shut it"; the state is no goal
    read = goal("Put the keys in the box. The laptop: open means you shut it, shut means you leave it.")
    assert read == {"inside(KeyChain, Box)", "closed(Laptop)"}
    read = goal("Put the keys in the box. Same for the desk lamp: on means you turn it off, off means you leave it.")
    assert read == {"inside(KeyChain, Box)", "switched_off(DeskLamp)"}


def test_a_rule_said_after_what_it_rules_and_a_place_told_first() -> None:
    # force.json's rule header "in this house" rules its own sentence too; idioms.json:
    # "the box is where the keys live" is the keys' place
    read = goal("The box is where the keys live. The laptop is open in this house.", shut=("Laptop",))
    assert read == {"inside(KeyChain, Box)", "open(Laptop)"}
