"""The AI2-THOR adapter's controller calls, timing and failures, against a recording
double of the Unity process (tests/thor_unity_double.py) that answers with real
``ai2thor.server`` events built from the real FloorPlan metadata."""

from __future__ import annotations

import pytest

pytest.importorskip("ai2thor.server")

from emboteam.sim.durations import FAILED_ACTION_SECONDS, MIN_NAVIGATION_SECONDS, action_seconds
from emboteam.sim.setup import StateChange
from emboteam.thor.changes import changes_between
from emboteam.thor.environment import ThorEnvironment
from emboteam.thor.errors import ThorSetupError, ThorTeamError
from emboteam.thor.skills import path_length
from emboteam.world.actions import Action, ActionOutcome, FailureReason, Skill
from emboteam.world.environment import Environment
from emboteam.world.robots import RobotProfile, parse_team, robot_profile
from emboteam.world.scene import load_scene
from emboteam.world.state import REACH, WorldState
from thor_unity_double import UnityDouble

FP = "FloorPlan1"


def make(team: str = "1", *, agents: int | None = None, setup: tuple[StateChange, ...] = ()
         ) -> tuple[ThorEnvironment, UnityDouble]:
    profiles = parse_team(team)
    unity = UnityDouble(FP, agents or len(profiles))
    return ThorEnvironment(unity, load_scene(FP), profiles, setup=setup), unity


def run(env: ThorEnvironment, robot: str, action: Action) -> ActionOutcome:
    env.start(robot, action)
    t = env.next_event_time()
    assert t is not None
    (outcome,) = [o for o in env.advance(t) if o.robot == robot]
    return outcome


def thor(env: ThorEnvironment, oid: str) -> str:
    return env.ids.thor(oid)


def test_it_is_an_environment() -> None:
    env, _ = make()
    assert isinstance(env, Environment)


def test_goto_plans_with_reachable_positions_and_shortest_path_then_teleports_at_the_end() -> None:
    env, unity = make()
    start = env.observe().robots["robot1"].position
    env.start("robot1", Action(skill=Skill.GoToObject, target="Fridge_1"))
    (reach,) = unity.by_action("GetReachablePositions")
    (path,) = unity.by_action("GetShortestPathToPoint")
    assert path["agentId"] == 0 and (path["position"]["x"], path["position"]["z"]) == start
    dest = path["target"]
    fridge = env.observe().objects["Fridge_1"].position
    assert ((dest["x"] - fridge[0]) ** 2 + (dest["z"] - fridge[2]) ** 2) ** 0.5 <= REACH
    assert dest in unity.reachable
    assert unity.by_action("Teleport") == []  # the robot is still driving
    length = path_length([path["position"], dest])
    env.advance(env.now + 0.25)  # halfway along the drive, for the trace's floor map
    x, z = env.pose("robot1")
    assert min(start[0], dest["x"]) <= x <= max(start[0], dest["x"]) and (x, z) != start
    assert env.next_event_time() == pytest.approx(max(MIN_NAVIGATION_SECONDS, length / 1.0))
    outcome = env.advance(env.next_event_time() or 0.0)[0]
    assert outcome.success
    (tele,) = unity.by_action("Teleport")
    assert tele["agentId"] == 0 and tele["position"] == dest and tele["standing"] is True
    robot = env.observe().robots["robot1"]
    assert robot.position == (round(dest["x"], 3), round(dest["z"], 3)) and robot.at == "Fridge_1"
    # the navmesh is queried once per scene
    run(env, "robot1", Action(skill=Skill.GoToObject, target="Apple_1"))
    assert len(unity.by_action("GetReachablePositions")) == 1 and reach["agentId"] == 0


@pytest.mark.parametrize(("skill", "target", "thor_action"), [
    (Skill.OpenObject, "Fridge_1", "OpenObject"),
    (Skill.CloseObject, "Drawer_1", "CloseObject"),
    (Skill.SwitchOff, "LightSwitch_1", "ToggleObjectOff"),
    (Skill.SwitchOn, "Faucet_1", "ToggleObjectOn"),
    (Skill.BreakObject, "Mug_1", "BreakObject"),
    (Skill.PickupObject, "Apple_1", "PickupObject"),
])
def test_interactions_map_to_thor_actions_with_the_objects_thor_id(skill: Skill, target: str,
                                                                   thor_action: str) -> None:
    env, unity = make()
    outcome = run(env, "robot1", Action(skill=skill, target=target))
    assert outcome.success and outcome.end - outcome.start == action_seconds(skill)
    (call,) = unity.by_action(thor_action)
    assert call == {"action": thor_action, "agentId": 0, "objectId": thor(env, target), "forceAction": True}


def test_clean_object_is_thors_clean_object() -> None:
    # no SMART-LLM profile has CleanObject (they wash under the faucet): a custom robot
    cleaner = RobotProfile(name="cleaner", skills=frozenset(Skill), mass_capacity=100)
    unity = UnityDouble(FP, 1)
    env = ThorEnvironment(unity, load_scene(FP), [cleaner], setup=(StateChange(object="Bowl_1", is_dirty=True),))
    assert unity.by_action("DirtyObject")[0]["objectId"] == thor(env, "Bowl_1")
    assert env.observe().objects["Bowl_1"].is_dirty
    assert run(env, "cleaner", Action(skill=Skill.CleanObject, target="Bowl_1")).success
    assert unity.by_action("CleanObject")[-1]["objectId"] == thor(env, "Bowl_1")
    assert not env.observe().objects["Bowl_1"].is_dirty


def test_pickup_put_slice_drop_throw_push_in_thor_terms() -> None:
    env, unity = make()
    assert run(env, "robot1", Action(skill=Skill.PickupObject, target="Knife_1")).success
    assert env.observe().robots["robot1"].holding == "Knife_1"
    assert run(env, "robot1", Action(skill=Skill.SliceObject, target="Apple_1")).success
    assert unity.by_action("SliceObject")[0]["objectId"] == thor(env, "Apple_1")
    state = env.observe()
    assert state.objects["Apple_1"].gone and "Apple_1_Slice_1" in state.objects
    assert run(env, "robot1", Action(skill=Skill.PutObject, target="Knife_1", receptacle="CounterTop_1")).success
    put = unity.by_action("PutObject")[0]
    assert put["objectId"] == thor(env, "CounterTop_1") and put["placeStationary"] is True
    assert env.observe().objects["Knife_1"].parent == "CounterTop_1"
    assert run(env, "robot1", Action(skill=Skill.PickupObject, target="Apple_1_Slice_1")).success
    assert unity.by_action("PickupObject")[-1]["objectId"] == f"{thor(env, 'Apple_1')}|AppleSliced_0"
    assert run(env, "robot1", Action(skill=Skill.DropHandObject, target="Apple_1_Slice_1")).success
    assert unity.by_action("DropHandObject")[0] == {"action": "DropHandObject", "agentId": 0, "forceAction": True}
    assert run(env, "robot1", Action(skill=Skill.PushObject, target="Stool_1")).success
    assert unity.by_action("PushObject")[0]["moveMagnitude"] > 0
    # a throw lands in the GarbageCan within reach, as our model defines it
    assert run(env, "robot1", Action(skill=Skill.PickupObject, target="Mug_1")).success
    far = run(env, "robot1", Action(skill=Skill.ThrowObject, target="Mug_1"))
    assert not far.success and far.reason is FailureReason.NO_GARBAGE_CAN
    assert run(env, "robot1", Action(skill=Skill.GoToObject, target="GarbageCan_1")).success
    assert run(env, "robot1", Action(skill=Skill.ThrowObject, target="Mug_1")).success
    assert unity.by_action("PutObject")[-1]["objectId"] == thor(env, "GarbageCan_1")
    assert env.observe().objects["Mug_1"].parent == "GarbageCan_1"


def test_running_water_cleans_and_fills_what_is_in_the_basin() -> None:
    env, unity = make(setup=(StateChange(object="Mug_1", parent="SinkBasin_1", is_dirty=True),))
    assert env.observe().objects["Mug_1"].parent == "SinkBasin_1"
    assert run(env, "robot1", Action(skill=Skill.SwitchOn, target="Faucet_1")).success
    mug = thor(env, "Mug_1")
    assert any(c["objectId"] == mug for c in unity.by_action("CleanObject"))
    (fill,) = [c for c in unity.by_action("FillObjectWithLiquid") if c["objectId"] == mug]
    assert fill["fillLiquid"] == "water"
    m = env.observe().objects["Mug_1"]
    assert not m.is_dirty and m.liquid == "water"


def test_thor_failures_come_back_typed_with_thors_message_after_the_actions_duration() -> None:
    env, unity = make()
    run(env, "robot1", Action(skill=Skill.PickupObject, target="Apple_1"))
    unity.fail_next("PutObject", "No valid positions to place object found")
    outcome = run(env, "robot1", Action(skill=Skill.PutObject, target="Apple_1", receptacle="Bowl_1"))
    assert not outcome.success and outcome.reason is FailureReason.NOT_ALLOWED_HERE
    assert outcome.message == "No valid positions to place object found"
    assert outcome.end - outcome.start == action_seconds(Skill.PutObject)
    assert env.observe().robots["robot1"].holding == "Apple_1"  # the state is AI2-THOR's: unchanged
    unity.fail_next("OpenObject", "Fridge|-02.10|+00.00|+01.07 is not interactable and (perhaps it is "
                                  "occluded by something).")
    assert run(env, "robot1", Action(skill=Skill.OpenObject, target="Fridge_1")).reason is FailureReason.NOT_VISIBLE
    unity.fail_next("Teleport", "StandardIslandHeight is blocking Agent 0 from moving 0")
    assert run(env, "robot1", Action(skill=Skill.GoToObject, target="Fridge_1")).reason is FailureReason.NOT_REACHABLE


def test_team_rules_are_checked_before_any_controller_call() -> None:
    env, unity = make("24,7")  # robot24: GoTo and switches only; robot7 lifts 0.08 kg
    before = len(unity.calls)
    missing = run(env, "robot24", Action(skill=Skill.PickupObject, target="Apple_1"))
    assert missing.reason is FailureReason.MISSING_SKILL
    assert missing.end - missing.start == FAILED_ACTION_SECONDS
    assert run(env, "robot7", Action(skill=Skill.PickupObject, target="Potato_1")).reason is FailureReason.TOO_HEAVY
    assert run(env, "robot7", Action(skill=Skill.SliceObject, target="Apple_1")).reason is FailureReason.NO_KNIFE
    assert len(unity.calls) == before


def test_robots_act_through_their_own_agents_in_multi_agent_mode() -> None:
    env, unity = make("5,24")
    env.start("robot5", Action(skill=Skill.PickupObject, target="Apple_1"))
    env.start("robot24", Action(skill=Skill.SwitchOff, target="LightSwitch_1"))
    assert env.busy("robot5") and env.busy("robot24")
    assert unity.by_action("PickupObject") == []  # effects happen when the actions end
    done = env.advance(10.0)
    assert {o.robot for o in done} == {"robot5", "robot24"} and all(o.success for o in done)
    assert unity.by_action("ToggleObjectOff")[0]["agentId"] == 1
    assert unity.by_action("PickupObject")[0]["agentId"] == 0
    assert env.observe().robots["robot5"].holding == "Apple_1"
    assert env.observe().objects["Apple_1"].held_by == "robot5"
    # two robots never head for the same grid position
    env.start("robot5", Action(skill=Skill.GoToObject, target="Fridge_1"))
    env.start("robot24", Action(skill=Skill.GoToObject, target="Fridge_1"))
    d5, d24 = (c["target"] for c in unity.by_action("GetShortestPathToPoint")[-2:])
    assert (d5["x"], d5["z"]) != (d24["x"], d24["z"])


def test_a_joining_robot_needs_a_spare_agent() -> None:
    env, _ = make("5")
    with pytest.raises(ThorTeamError):
        env.add_robot(robot_profile(24))
    env, _ = make("5", agents=2)
    env.add_robot(robot_profile(24))
    assert run(env, "robot24", Action(skill=Skill.SwitchOff, target="LightSwitch_1")).success


def test_initial_state_changes_are_read_off_the_planning_state_and_made_in_thor() -> None:
    scene = load_scene(FP)
    before = WorldState.from_scene(scene)
    after = before.copy()
    after.objects["Fridge_1"].is_open = True
    after.move_object("Potato_1", "Fridge_1")
    after.objects["Potato_1"].temperature = "Cold"  # what the fridge does by itself
    changes = changes_between(before, after)
    assert changes[0] == StateChange(object="Potato_1", parent="Fridge_1")
    env, unity = make(setup=tuple(changes))
    assert [c["action"] for c in unity.calls if c.get("forceAction")][:3] == ["PickupObject", "PutObject",
                                                                            "OpenObject"]
    assert env.observe().objects["Potato_1"].parent == "Fridge_1"
    with pytest.raises(ThorSetupError, match="temperature"):
        make(setup=(StateChange(object="Apple_1", temperature="Hot"),))
