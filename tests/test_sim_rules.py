"""Action semantics through the simulator: every action's success, every failure reason an
action can produce (each leaving the state exactly as it was), placement rules and the
side effects AI2-THOR applies by itself (docs/THOR_SEMANTICS.md, docs/world.md)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from emboteam.sim import Breakdown, FaultConfig, Simulator
from emboteam.sim.rules import piece_ids
from emboteam.world import (
    Action,
    ActionOutcome,
    FailureReason,
    Goal,
    RobotProfile,
    Skill,
    WorldState,
    check_goal,
    load_scene,
    parse_team,
)
from emboteam.world.navgrid import NavGrid
from emboteam.world.navigation import navigator

R = FailureReason
S = Skill
Snapshot = Callable[[WorldState], dict[str, Any]]

#: a robot with every skill, CleanObject included (no SMART-LLM profile can clean)
CLEANER = RobotProfile(name="cleaner", skills=frozenset(Skill), mass_capacity=100.0)


def act(sim: Simulator, robot: str, skill: Skill, target: str, receptacle: str | None = None) -> ActionOutcome:
    return sim.execute(robot, Action(skill=skill, target=target, receptacle=receptacle))


def ok(sim: Simulator, robot: str, skill: Skill, target: str, receptacle: str | None = None) -> None:
    out = act(sim, robot, skill, target, receptacle)
    assert out.success, str(out)


def go_do(sim: Simulator, robot: str, skill: Skill, target: str, receptacle: str | None = None) -> None:
    """Walk to where the action happens, then do it (it must succeed)."""
    ok(sim, robot, S.GoToObject, receptacle or target)
    ok(sim, robot, skill, target, receptacle)


def fails(sim: Simulator, snap: Snapshot, reason: FailureReason, robot: str, skill: Skill, target: str,
          receptacle: str | None = None) -> ActionOutcome:
    before = snap(sim.state)
    out = act(sim, robot, skill, target, receptacle)
    assert not out.success and out.reason is reason, str(out)
    assert out.message
    assert snap(sim.state) == before, f"{out} changed the state"
    return out


# ---- successes ---------------------------------------------------------------------------


def test_goto_moves_the_robot_to_the_object(sim1: Simulator) -> None:
    fridge = sim1.state.objects["Fridge_1"]
    ok(sim1, "robot1", S.GoToObject, "Fridge_1")
    r = sim1.state.robots["robot1"]
    # it stands on the fridge's interaction pose (a reachable cell within 1.5 m), not in it
    poses = navigator("FloorPlan1").poses_for((fridge.position[0], fridge.position[2]))
    assert r.position in [NavGrid.point(p.cell) for p in poses] and r.at == "Fridge_1"
    assert sim1.state.in_reach("robot1", "Egg_1")  # what is in the fridge is reachable there


def test_pickup_put_carry_contents_along(sim1: Simulator) -> None:
    st = sim1.state
    go_do(sim1, "robot1", S.PickupObject, "Apple_1")
    go_do(sim1, "robot1", S.PutObject, "Apple_1", "Pan_1")
    go_do(sim1, "robot1", S.PickupObject, "Pan_1")
    assert st.robots["robot1"].holding == "Pan_1" and st.objects["Pan_1"].held_by == "robot1"
    assert st.objects["Pan_1"].parent is None and st.objects["Apple_1"].parent == "Pan_1"
    # the pan and the apple in it travel with the robot
    ok(sim1, "robot1", S.GoToObject, "StoveBurner_3")
    x, z = st.robots["robot1"].position
    for oid in ("Pan_1", "Apple_1"):
        assert (st.objects[oid].position[0], st.objects[oid].position[2]) == (x, z), oid
    ok(sim1, "robot1", S.PutObject, "Pan_1", "StoveBurner_3")
    burner = st.objects["StoveBurner_3"].position
    assert st.objects["Pan_1"].parent == "StoveBurner_3" and st.objects["Apple_1"].position == burner
    assert st.robots["robot1"].holding is None and st.objects["Pan_1"].held_by is None


def test_open_close(sim1: Simulator) -> None:
    go_do(sim1, "robot1", S.OpenObject, "Fridge_1")
    assert sim1.state.objects["Fridge_1"].is_open
    ok(sim1, "robot1", S.CloseObject, "Fridge_1")
    assert not sim1.state.objects["Fridge_1"].is_open


def test_stove_knob_switches_its_burner_only(sim1: Simulator) -> None:
    st = sim1.state
    go_do(sim1, "robot1", S.SwitchOn, "StoveKnob_4")
    assert st.objects["StoveKnob_4"].is_on and st.objects["StoveBurner_3"].is_on
    assert [b for b in ("StoveBurner_1", "StoveBurner_2", "StoveBurner_4") if st.objects[b].is_on] == []
    ok(sim1, "robot1", S.SwitchOff, "StoveKnob_4")
    assert not st.objects["StoveBurner_3"].is_on


def test_slice_spawns_pieces_in_place_of_the_whole(sim1: Simulator) -> None:
    st = sim1.state
    go_do(sim1, "robot1", S.PickupObject, "ButterKnife_1")
    go_do(sim1, "robot1", S.SliceObject, "Apple_1")
    whole = st.objects["Apple_1"]
    assert whole.is_sliced and whole.gone
    assert piece_ids("Apple_1", 3) == ["Apple_1_Slice_1", "Apple_1_Slice_2", "Apple_1_Slice_3"]
    for pid in piece_ids("Apple_1", 3):
        p = st.objects[pid]
        assert p.type == "AppleSliced" and p.source == "Apple_1" and p.has("pickupable")
        assert p.parent == whole.parent == "CounterTop_2" and p.position == whole.position
        assert p.mass == pytest.approx(whole.mass / 3, abs=1e-3)
    assert st.robots["robot1"].holding == "ButterKnife_1"  # the knife stays in hand
    ok(sim1, "robot1", S.PutObject, "ButterKnife_1", "CounterTop_2")
    ok(sim1, "robot1", S.PickupObject, "Apple_1_Slice_2")
    assert st.invariant_violations() == []


def test_a_cooked_potato_gives_cooked_slices(sim1: Simulator) -> None:
    st = sim1.state
    st.objects["Potato_1"].is_cooked = True
    st.objects["Potato_1"].temperature = "Hot"
    go_do(sim1, "robot1", S.OpenObject, "Drawer_9")
    ok(sim1, "robot1", S.PickupObject, "Knife_1")
    go_do(sim1, "robot1", S.SliceObject, "Potato_1")
    for pid in piece_ids("Potato_1", 3):
        assert st.objects[pid].is_cooked and st.objects[pid].temperature == "Hot"


def test_break_and_egg_cracks(sim1: Simulator) -> None:
    st = sim1.state
    go_do(sim1, "robot1", S.BreakObject, "Vase_1")
    assert st.objects["Vase_1"].is_broken
    go_do(sim1, "robot1", S.OpenObject, "Fridge_1")
    ok(sim1, "robot1", S.BreakObject, "Egg_1")
    cracked = st.objects["Egg_1_Slice_1"]
    assert cracked.type == "EggCracked" and cracked.parent == "Fridge_1" and st.objects["Egg_1"].gone
    assert cracked.temperature == "Cold"  # a cold egg cracks into a cold egg
    report = check_goal(Goal.parse("broken(Egg); broken(Egg_1); broken(Vase)"), st)
    assert report.success, [str(r) for r in report.results]  # "crack the egg" is checkable


def test_slicing_an_egg_cracks_it_too(sim1: Simulator) -> None:
    go_do(sim1, "robot1", S.PickupObject, "ButterKnife_1")
    go_do(sim1, "robot1", S.OpenObject, "Fridge_1")
    ok(sim1, "robot1", S.SliceObject, "Egg_1")
    assert sim1.state.objects["Egg_1_Slice_1"].type == "EggCracked"


def test_broken_television_goes_off_for_good(state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan201"), parse_team("1"))
    tv = next(o for o in sim.state.of_type("Television"))
    go_do(sim, "robot1", S.SwitchOn, tv.id)
    ok(sim, "robot1", S.BreakObject, tv.id)
    assert tv.is_broken and not tv.is_on
    fails(sim, state_snapshot, R.ALREADY_BROKEN, "robot1", S.SwitchOn, tv.id)


def test_clean_object() -> None:
    sim = Simulator(load_scene("FloorPlan1"), (CLEANER,))
    sim.state.objects["Mug_1"].is_dirty = True
    go_do(sim, "cleaner", S.CleanObject, "Mug_1")
    assert not sim.state.objects["Mug_1"].is_dirty


def test_throw_lands_in_the_nearest_garbage_can(sim1: Simulator) -> None:
    go_do(sim1, "robot1", S.PickupObject, "Apple_1")
    ok(sim1, "robot1", S.GoToObject, "GarbageCan_1")
    ok(sim1, "robot1", S.ThrowObject, "Apple_1")
    assert sim1.state.objects["Apple_1"].parent == "GarbageCan_1"
    assert sim1.state.robots["robot1"].holding is None


def test_drop_lands_on_the_floor_under_the_robot(sim1: Simulator) -> None:
    go_do(sim1, "robot1", S.PickupObject, "Apple_1")
    ok(sim1, "robot1", S.GoToObject, "Stool_1")
    ok(sim1, "robot1", S.DropHandObject, "Apple_1")
    apple, (x, z) = sim1.state.objects["Apple_1"], sim1.state.robots["robot1"].position
    assert apple.parent == "Floor_1" and apple.position == (x, 0.0, z)


@pytest.mark.parametrize("skill", [S.PushObject, S.PullObject])
def test_push_pull_are_symbolic_no_ops(sim1: Simulator, state_snapshot: Snapshot, skill: Skill) -> None:
    ok(sim1, "robot1", S.GoToObject, "Stool_1")
    before = state_snapshot(sim1.state)
    ok(sim1, "robot1", skill, "Stool_1")
    assert state_snapshot(sim1.state) == before


# ---- failures: each reason, and the state never changes ---------------------------------

def test_unknown_object(sim1: Simulator, state_snapshot: Snapshot) -> None:
    fails(sim1, state_snapshot, R.UNKNOWN_OBJECT, "robot1", S.GoToObject, "Unicorn_1")
    fails(sim1, state_snapshot, R.UNKNOWN_OBJECT, "robot1", S.PutObject, "Apple_1", "Unicorn_1")


def test_missing_skill(state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("23"))  # GoTo, Open, Close only
    ok(sim, "robot23", S.GoToObject, "Apple_1")
    fails(sim, state_snapshot, R.MISSING_SKILL, "robot23", S.PickupObject, "Apple_1")


def test_not_reachable_without_going_there(sim1: Simulator, state_snapshot: Snapshot) -> None:
    out = fails(sim1, state_snapshot, R.NOT_REACHABLE, "robot1", S.PickupObject, "Apple_1")
    assert "go to it first" in out.message


def test_not_visible_inside_a_closed_receptacle(sim1: Simulator, state_snapshot: Snapshot) -> None:
    ok(sim1, "robot1", S.GoToObject, "Egg_1")
    fails(sim1, state_snapshot, R.NOT_VISIBLE, "robot1", S.PickupObject, "Egg_1")
    ok(sim1, "robot1", S.OpenObject, "Fridge_1")
    ok(sim1, "robot1", S.PickupObject, "Egg_1")


def test_things_on_a_closed_toilet_stay_visible() -> None:
    """AI2-THOR's bathrooms keep paper rolls and sprays on the tank of a closed toilet."""
    sim = Simulator(load_scene("FloorPlan414"), parse_team("1"))
    assert not sim.state.objects["Toilet_1"].is_open
    assert sim.state.objects["PaperTowelRoll_1"].parent == "Toilet_1"
    go_do(sim, "robot1", S.PickupObject, "PaperTowelRoll_1")


def test_a_closed_safe_hides_and_refuses(state_snapshot: Snapshot) -> None:
    scene = next(load_scene(fp) for fp in ("FloorPlan209", "FloorPlan303", "FloorPlan309", "FloorPlan310")
                 if load_scene(fp).of_type("Safe"))
    sim = Simulator(scene, parse_team("1"))
    safe = next(sim.state.of_type("Safe"))
    safe.is_open = False
    item = next(o for o in sim.state.objects.values()
                if o.has("pickupable") and o.mass < 1 and o.parent and sim.state.enclosing_closed(o.id) is None)
    go_do(sim, "robot1", S.PickupObject, item.id)
    ok(sim, "robot1", S.GoToObject, safe.id)
    fails(sim, state_snapshot, R.RECEPTACLE_CLOSED, "robot1", S.PutObject, item.id, safe.id)


def test_hand_full_empty_and_wrong_object(sim1: Simulator, state_snapshot: Snapshot) -> None:
    ok(sim1, "robot1", S.GoToObject, "Apple_1")
    fails(sim1, state_snapshot, R.HAND_EMPTY, "robot1", S.PutObject, "Apple_1", "CounterTop_2")
    fails(sim1, state_snapshot, R.HAND_EMPTY, "robot1", S.DropHandObject, "Apple_1")
    fails(sim1, state_snapshot, R.HAND_EMPTY, "robot1", S.ThrowObject, "Apple_1")
    ok(sim1, "robot1", S.PickupObject, "Apple_1")
    fails(sim1, state_snapshot, R.HAND_FULL, "robot1", S.PickupObject, "CreditCard_1")
    fails(sim1, state_snapshot, R.NOT_HOLDING_TARGET, "robot1", S.PutObject, "CreditCard_1", "CounterTop_2")


def test_too_heavy_and_not_pickupable(state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("10,1"))  # robot10 lifts 0.02 kg
    ok(sim, "robot10", S.GoToObject, "Apple_1")
    out = fails(sim, state_snapshot, R.TOO_HEAVY, "robot10", S.PickupObject, "Apple_1")
    assert "0.2 kg" in out.message
    ok(sim, "robot10", S.PickupObject, "CreditCard_1")  # 6 g
    ok(sim, "robot1", S.GoToObject, "CounterTop_2")
    fails(sim, state_snapshot, R.NOT_PICKUPABLE, "robot1", S.PickupObject, "CounterTop_2")


def test_held_by_other(sim1: Simulator, state_snapshot: Snapshot) -> None:
    go_do(sim1, "robot1", S.PickupObject, "Apple_1")
    ok(sim1, "robot2", S.GoToObject, "Apple_1")  # drives to robot1, who holds it
    fails(sim1, state_snapshot, R.HELD_BY_OTHER, "robot2", S.PickupObject, "Apple_1")
    fails(sim1, state_snapshot, R.HELD_BY_OTHER, "robot2", S.SliceObject, "Apple_1")


def test_put_needs_an_open_allowed_receptacle(sim1: Simulator, state_snapshot: Snapshot) -> None:
    go_do(sim1, "robot1", S.PickupObject, "Apple_1")
    fails(sim1, state_snapshot, R.NOT_A_RECEPTACLE, "robot1", S.PutObject, "Apple_1", "Tomato_1")
    fails(sim1, state_snapshot, R.NOT_A_RECEPTACLE, "robot1", S.PutObject, "Apple_1")
    ok(sim1, "robot1", S.GoToObject, "Fridge_1")
    out = fails(sim1, state_snapshot, R.RECEPTACLE_CLOSED, "robot1", S.PutObject, "Apple_1", "Fridge_1")
    assert "must be open" in out.message
    ok(sim1, "robot1", S.GoToObject, "Toaster_1")
    fails(sim1, state_snapshot, R.NOT_ALLOWED_HERE, "robot1", S.PutObject, "Apple_1", "Toaster_1")


def test_put_into_itself_or_into_a_held_receptacle(sim1: Simulator, state_snapshot: Snapshot) -> None:
    go_do(sim1, "robot1", S.PickupObject, "Bowl_1")
    fails(sim1, state_snapshot, R.NOT_ALLOWED_HERE, "robot1", S.PutObject, "Bowl_1", "Bowl_1")
    go_do(sim1, "robot2", S.PickupObject, "Apple_1")
    ok(sim1, "robot2", S.GoToObject, "Bowl_1")
    out = fails(sim1, state_snapshot, R.HELD_BY_OTHER, "robot2", S.PutObject, "Apple_1", "Bowl_1")
    assert "held by robot1" in out.message


def test_open_close_failures(sim1: Simulator, state_snapshot: Snapshot) -> None:
    ok(sim1, "robot1", S.GoToObject, "Fridge_1")
    fails(sim1, state_snapshot, R.ALREADY_CLOSED, "robot1", S.CloseObject, "Fridge_1")
    ok(sim1, "robot1", S.OpenObject, "Fridge_1")
    fails(sim1, state_snapshot, R.ALREADY_OPEN, "robot1", S.OpenObject, "Fridge_1")
    ok(sim1, "robot1", S.GoToObject, "Apple_1")
    fails(sim1, state_snapshot, R.NOT_OPENABLE, "robot1", S.OpenObject, "Apple_1")


def test_switch_failures(sim1: Simulator, state_snapshot: Snapshot) -> None:
    ok(sim1, "robot1", S.GoToObject, "StoveBurner_3")
    out = fails(sim1, state_snapshot, R.NOT_TOGGLEABLE, "robot1", S.SwitchOn, "StoveBurner_3")
    assert "StoveKnob" in out.message  # AI2-THOR: burners are switched by their knob
    fails(sim1, state_snapshot, R.ALREADY_OFF, "robot1", S.SwitchOff, "StoveKnob_4")
    ok(sim1, "robot1", S.SwitchOn, "StoveKnob_4")
    fails(sim1, state_snapshot, R.ALREADY_ON, "robot1", S.SwitchOn, "StoveKnob_4")


def test_microwave_door_and_power_interlock(sim1: Simulator, state_snapshot: Snapshot) -> None:
    """AI2-THOR: a microwave cannot be switched on while open, nor opened while on."""
    ok(sim1, "robot1", S.GoToObject, "Microwave_1")
    ok(sim1, "robot1", S.OpenObject, "Microwave_1")
    out = fails(sim1, state_snapshot, R.ALREADY_OPEN, "robot1", S.SwitchOn, "Microwave_1")
    assert "close it" in out.message
    ok(sim1, "robot1", S.CloseObject, "Microwave_1")
    ok(sim1, "robot1", S.SwitchOn, "Microwave_1")
    out = fails(sim1, state_snapshot, R.ALREADY_ON, "robot1", S.OpenObject, "Microwave_1")
    assert "switch it off" in out.message


def test_slice_failures(sim1: Simulator, state_snapshot: Snapshot) -> None:
    ok(sim1, "robot1", S.GoToObject, "Apple_1")
    out = fails(sim1, state_snapshot, R.NO_KNIFE, "robot1", S.SliceObject, "Apple_1")
    assert "Knife or ButterKnife" in out.message
    ok(sim1, "robot1", S.GoToObject, "Spatula_1")
    ok(sim1, "robot1", S.PickupObject, "Spatula_1")
    ok(sim1, "robot1", S.GoToObject, "Apple_1")
    fails(sim1, state_snapshot, R.NO_KNIFE, "robot1", S.SliceObject, "Apple_1")  # a spatula is no knife
    ok(sim1, "robot1", S.PutObject, "Spatula_1", "CounterTop_2")
    ok(sim1, "robot1", S.PickupObject, "ButterKnife_1")
    fails(sim1, state_snapshot, R.NOT_SLICEABLE, "robot1", S.SliceObject, "CreditCard_1")
    ok(sim1, "robot1", S.SliceObject, "Apple_1")
    fails(sim1, state_snapshot, R.ALREADY_SLICED, "robot1", S.SliceObject, "Apple_1")
    fails(sim1, state_snapshot, R.ALREADY_SLICED, "robot1", S.GoToObject, "Apple_1")  # it is gone
    fails(sim1, state_snapshot, R.NOT_SLICEABLE, "robot1", S.SliceObject, "Apple_1_Slice_1")


def test_break_failures(sim1: Simulator, state_snapshot: Snapshot) -> None:
    ok(sim1, "robot1", S.GoToObject, "Apple_1")
    fails(sim1, state_snapshot, R.NOT_BREAKABLE, "robot1", S.BreakObject, "Apple_1")
    ok(sim1, "robot1", S.GoToObject, "Vase_1")
    ok(sim1, "robot1", S.BreakObject, "Vase_1")
    fails(sim1, state_snapshot, R.ALREADY_BROKEN, "robot1", S.BreakObject, "Vase_1")


def test_clean_failures(state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan1"), (CLEANER,))
    ok(sim, "cleaner", S.GoToObject, "Mug_1")
    fails(sim, state_snapshot, R.ALREADY_CLEAN, "cleaner", S.CleanObject, "Mug_1")
    ok(sim, "cleaner", S.GoToObject, "Apple_1")
    fails(sim, state_snapshot, R.NOT_DIRTYABLE, "cleaner", S.CleanObject, "Apple_1")


def test_no_garbage_can_in_reach(sim1: Simulator, state_snapshot: Snapshot) -> None:
    go_do(sim1, "robot1", S.PickupObject, "Apple_1")
    fails(sim1, state_snapshot, R.NO_GARBAGE_CAN, "robot1", S.ThrowObject, "Apple_1")


def test_not_moveable(sim1: Simulator, state_snapshot: Snapshot) -> None:
    ok(sim1, "robot1", S.GoToObject, "CounterTop_2")
    fails(sim1, state_snapshot, R.NOT_MOVEABLE, "robot1", S.PushObject, "CounterTop_2")


def test_robot_down(state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"),
                    faults=FaultConfig(breakdowns=(Breakdown(robot="robot1", at=0.0),)))
    sim.advance(0.0)
    fails(sim, state_snapshot, R.ROBOT_DOWN, "robot1", S.GoToObject, "Apple_1")


def test_actuation_fault(state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"), faults=FaultConfig(action_failure=1.0))
    fails(sim, state_snapshot, R.ACTUATION_FAULT, "robot1", S.GoToObject, "Apple_1")
    assert sim.state.robots["robot1"].position == load_scene("FloorPlan1").robot_start(0)


# ---- placement rules ----------------------------------------------------------------------


@pytest.mark.parametrize(("obj", "receptacle", "allowed"), [
    ("Mug_1", "CoffeeMachine_1", True),
    ("Cup_1", "CoffeeMachine_1", False),
    ("Bread_1", "Toaster_1", False),      # whole bread: slice it first
    ("Pan_1", "StoveBurner_1", True),
    ("Pot_1", "StoveBurner_2", True),
    ("Kettle_1", "StoveBurner_4", True),
    ("Apple_1", "StoveBurner_1", False),
    ("Apple_1", "Pan_1", True),
    ("Apple_1", "SinkBasin_1", True),
    ("Book_1", "SinkBasin_1", False),
])
def test_placement_rules(obj: str, receptacle: str, allowed: bool, state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"))
    sim.state.move_object(obj, "CounterTop_2")  # reachable from one spot, out of any cabinet
    go_do(sim, "robot1", S.PickupObject, obj)
    ok(sim, "robot1", S.GoToObject, receptacle)
    if allowed:
        ok(sim, "robot1", S.PutObject, obj, receptacle)
        assert sim.state.objects[obj].parent == receptacle
    else:
        fails(sim, state_snapshot, R.NOT_ALLOWED_HERE, "robot1", S.PutObject, obj, receptacle)


def test_toaster_takes_bread_slices() -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"))
    go_do(sim, "robot1", S.PickupObject, "ButterKnife_1")
    go_do(sim, "robot1", S.SliceObject, "Bread_1")
    ok(sim, "robot1", S.PutObject, "ButterKnife_1", "CounterTop_2")
    ok(sim, "robot1", S.PickupObject, "Bread_1_Slice_1")
    go_do(sim, "robot1", S.PutObject, "Bread_1_Slice_1", "Toaster_1")


@pytest.mark.parametrize("receptacle", ["Fridge_1", "Microwave_1", "Drawer_1", "Cabinet_1"])
def test_must_be_open_receptacles(receptacle: str, state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan1"), parse_team("1"))
    go_do(sim, "robot1", S.PickupObject, "Potato_1")
    ok(sim, "robot1", S.GoToObject, receptacle)
    fails(sim, state_snapshot, R.RECEPTACLE_CLOSED, "robot1", S.PutObject, "Potato_1", receptacle)
    ok(sim, "robot1", S.OpenObject, receptacle)
    out = act(sim, "robot1", S.PutObject, "Potato_1", receptacle)
    # a potato may go in a fridge or microwave; drawers and cabinets refuse it once open
    assert out.success == (receptacle in ("Fridge_1", "Microwave_1"))
    assert out.success or out.reason is R.NOT_ALLOWED_HERE


def test_box_must_be_open_too(state_snapshot: Snapshot) -> None:
    sim = Simulator(load_scene("FloorPlan201"), parse_team("1"))
    box = next(sim.state.of_type("Box"))
    box.is_open = False
    go_do(sim, "robot1", S.PickupObject, "CreditCard_1")
    ok(sim, "robot1", S.GoToObject, box.id)
    fails(sim, state_snapshot, R.RECEPTACLE_CLOSED, "robot1", S.PutObject, "CreditCard_1", box.id)
    ok(sim, "robot1", S.OpenObject, box.id)
    ok(sim, "robot1", S.PutObject, "CreditCard_1", box.id)


# ---- side effects ------------------------------------------------------------------------


def test_microwave_heats_and_cooks_persistently(sim1: Simulator) -> None:
    st = sim1.state
    go_do(sim1, "robot1", S.PickupObject, "Potato_1")
    go_do(sim1, "robot1", S.OpenObject, "Microwave_1")
    ok(sim1, "robot1", S.PutObject, "Potato_1", "Microwave_1")
    ok(sim1, "robot1", S.CloseObject, "Microwave_1")
    assert st.objects["Potato_1"].temperature == "RoomTemp"  # off: nothing happens yet
    ok(sim1, "robot1", S.SwitchOn, "Microwave_1")
    assert st.objects["Potato_1"].temperature == "Hot" and st.objects["Potato_1"].is_cooked
    ok(sim1, "robot1", S.SwitchOff, "Microwave_1")
    ok(sim1, "robot1", S.OpenObject, "Microwave_1")
    ok(sim1, "robot1", S.PickupObject, "Potato_1")
    assert st.objects["Potato_1"].temperature == "Hot" and st.objects["Potato_1"].is_cooked


def test_stove_cooks_what_is_in_the_pan_on_a_lit_burner(sim1: Simulator) -> None:
    st = sim1.state
    go_do(sim1, "robot1", S.PickupObject, "Potato_1")
    go_do(sim1, "robot1", S.PutObject, "Potato_1", "Pan_1")
    ok(sim1, "robot1", S.PickupObject, "Pan_1")
    go_do(sim1, "robot1", S.PutObject, "Pan_1", "StoveBurner_1")  # knob 1's burner
    go_do(sim1, "robot1", S.SwitchOn, "StoveKnob_4")             # another burner
    assert not st.objects["Potato_1"].is_cooked
    ok(sim1, "robot1", S.SwitchOn, "StoveKnob_1")
    assert st.objects["Potato_1"].is_cooked and st.objects["Pan_1"].temperature == "Hot"


def test_cracked_egg_cooks_in_a_pan(sim1: Simulator) -> None:
    st = sim1.state
    go_do(sim1, "robot1", S.PickupObject, "Pan_1")
    go_do(sim1, "robot1", S.PutObject, "Pan_1", "StoveBurner_3")
    go_do(sim1, "robot1", S.OpenObject, "Fridge_1")
    ok(sim1, "robot1", S.PickupObject, "Egg_1")
    go_do(sim1, "robot1", S.PutObject, "Egg_1", "Pan_1")
    ok(sim1, "robot1", S.BreakObject, "Egg_1")
    assert st.objects["Egg_1_Slice_1"].parent == "Pan_1"
    go_do(sim1, "robot1", S.SwitchOn, "StoveKnob_4")
    assert st.objects["Egg_1_Slice_1"].is_cooked


def test_fridge_cools(sim1: Simulator) -> None:
    go_do(sim1, "robot1", S.PickupObject, "Apple_1")
    go_do(sim1, "robot1", S.OpenObject, "Fridge_1")
    ok(sim1, "robot1", S.PutObject, "Apple_1", "Fridge_1")
    assert sim1.state.objects["Apple_1"].temperature == "Cold"


def test_faucet_cleans_and_fills_what_is_in_the_basin(sim1: Simulator) -> None:
    st = sim1.state
    mug = st.objects["Mug_1"]
    mug.is_dirty = True
    go_do(sim1, "robot1", S.PickupObject, "Mug_1")
    go_do(sim1, "robot1", S.PutObject, "Mug_1", "SinkBasin_1")
    assert mug.is_dirty and mug.liquid is None  # the tap is off
    go_do(sim1, "robot1", S.SwitchOn, "Faucet_1")
    assert not mug.is_dirty and mug.liquid == "water"
    # a cup put under the running tap fills at once
    go_do(sim1, "robot1", S.OpenObject, "Cabinet_2")
    ok(sim1, "robot1", S.PickupObject, "Cup_1")
    go_do(sim1, "robot1", S.PutObject, "Cup_1", "SinkBasin_1")
    assert st.objects["Cup_1"].liquid == "water"


def test_coffee_machine_fills_a_mug_with_hot_coffee(sim1: Simulator) -> None:
    mug = sim1.state.objects["Mug_1"]
    go_do(sim1, "robot1", S.PickupObject, "Mug_1")
    go_do(sim1, "robot1", S.PutObject, "Mug_1", "CoffeeMachine_1")
    assert mug.liquid is None
    ok(sim1, "robot1", S.SwitchOn, "CoffeeMachine_1")
    assert mug.liquid == "coffee" and mug.temperature == "Hot"


def test_toaster_toasts_bread_slices(sim1: Simulator) -> None:
    go_do(sim1, "robot1", S.PickupObject, "ButterKnife_1")
    go_do(sim1, "robot1", S.SliceObject, "Bread_1")
    ok(sim1, "robot1", S.PutObject, "ButterKnife_1", "CounterTop_2")
    ok(sim1, "robot1", S.PickupObject, "Bread_1_Slice_2")
    go_do(sim1, "robot1", S.PutObject, "Bread_1_Slice_2", "Toaster_1")
    ok(sim1, "robot1", S.SwitchOn, "Toaster_1")
    toast = sim1.state.objects["Bread_1_Slice_2"]
    assert toast.is_cooked and toast.temperature == "Hot"
    assert not sim1.state.objects["Bread_1_Slice_1"].is_cooked
