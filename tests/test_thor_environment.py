"""The AI2-THOR adapter's controller calls, timing and failures, against a recording
double of the Unity process (tests/thor_unity_double.py) that answers with real
``ai2thor.server`` events built from the real FloorPlan metadata."""

from __future__ import annotations

import itertools

import pytest

pytest.importorskip("ai2thor.server")

from emboteam.exec.nav_check import check_motion
from emboteam.sim.drives import drive_steps
from emboteam.sim.durations import FAILED_ACTION_SECONDS, action_seconds
from emboteam.sim.setup import StateChange
from emboteam.sim.simulator import Simulator
from emboteam.thor.changes import changes_between
from emboteam.thor.environment import ThorEnvironment
from emboteam.thor.errors import ThorSetupError, ThorTeamError
from emboteam.thor.skills import facing
from emboteam.world.actions import Action, ActionOutcome, FailureReason, Skill
from emboteam.world.environment import Environment
from emboteam.world.navgrid import NavGrid, load_grid
from emboteam.world.navigation import navigator
from emboteam.world.robots import RobotProfile, parse_team, robot_profile
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
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


def _replay(unity: UnityDouble, agent_id: int) -> list[tuple[float, float, float]]:
    """(x, z, yaw) after each MoveAhead/Rotate the double carried out for an agent."""
    return [(c["x"], c["z"], c["yaw"]) for c in unity.poses if c["agentId"] == agent_id]


def test_goto_drives_the_simulators_grid_path_step_by_step() -> None:
    env, unity = make()
    sim = Simulator(load_scene(FP), parse_team("1"), avoidance=True)
    expected = sim.execute("robot1", Action(skill=Skill.GoToObject, target="Fridge_1"))
    steps = drive_steps(sim.traffic.paths["robot1"], start=0.0, heading_before=0)  # the agent faces +z
    env.start("robot1", Action(skill=Skill.GoToObject, target="Fridge_1"))
    assert env.busy("robot1") and unity.by_action("MoveAhead") == []  # steps are sent as they end
    env.advance(steps[len(steps) // 2].end)  # halfway: the agent is on the path's cell of then
    x, z = env.pose("robot1")
    assert (x, z) == NavGrid.point(steps[len(steps) // 2].cell)
    outcome = env.advance(env.next_event_time() or 0.0)[0]
    assert outcome.success and outcome.end - outcome.start == pytest.approx(expected.end - expected.start)
    sent = [c["action"] for c in unity.calls if c["action"] in ("MoveAhead", "RotateLeft", "RotateRight")]
    moves = [s.action for s in steps if s.action != "Wait"]
    assert sent[:len(moves)] == moves  # then at most a turn by the last few degrees to face it
    grid = load_grid(FP)
    agent = unity.agents[0]["agent"]
    cell = grid.cell_at((agent["position"]["x"], agent["position"]["z"]))
    fridge = load_scene(FP).get("Fridge_1").position
    assert cell == sim.traffic.cell("robot1", sim.now).cell  # the very cell the simulator ends on
    assert cell in {p.cell for p in navigator(FP).poses_for((fridge[0], fridge[2]))}
    assert agent["rotation"]["y"] == pytest.approx(facing(agent["position"], dict(x=fridge[0], y=fridge[1],
                                                                                  z=fridge[2]))[0], abs=0.2)
    assert unity.by_action("Teleport") == [] and unity.by_action("GetShortestPathToPoint") == []
    robot = env.observe().robots["robot1"]
    assert robot.at == "Fridge_1" and robot.position == NavGrid.point(cell)


def test_every_move_lands_on_a_grid_cell_and_the_next_drive_starts_from_there() -> None:
    env, unity = make()
    grid = load_grid(FP)
    for target in ("Fridge_1", "Apple_1", "Toaster_1", "GarbageCan_1"):
        assert run(env, "robot1", Action(skill=Skill.GoToObject, target=target)).success, target
    cells = [grid.cell_at((x, z)) for x, z, _ in _replay(unity, 0)]
    assert cells and None not in cells
    assert all(abs(a[0] - b[0]) + abs(a[1] - b[1]) <= 1 for a, b in itertools.pairwise(cells))  # type: ignore[index]
    assert check_motion(env.nav_record()).collisions == 0


def test_teleport_mode_teleports_cell_by_cell_then_faces_the_object() -> None:
    profiles = parse_team("1")
    unity = UnityDouble(FP, 1)
    env = ThorEnvironment(unity, load_scene(FP), profiles, steps="teleport")
    assert run(env, "robot1", Action(skill=Skill.GoToObject, target="Fridge_1")).success
    tele = unity.by_action("Teleport")
    grid = load_grid(FP)
    cells = [grid.cell_at((t["position"]["x"], t["position"]["z"])) for t in tele]
    assert len(tele) >= 3 and None not in cells
    assert all(abs(a[0] - b[0]) + abs(a[1] - b[1]) <= 1 for a, b in itertools.pairwise(cells))  # type: ignore[index]
    assert unity.by_action("MoveAhead") == []
    fridge = load_scene(FP).get("Fridge_1").position
    yaw, horizon = facing(tele[-1]["position"], dict(x=fridge[0], y=fridge[1], z=fridge[2]))
    assert tele[-1]["rotation"]["y"] == yaw and tele[-1]["horizon"] == horizon
    with pytest.raises(ThorTeamError, match="step mode"):
        ThorEnvironment(UnityDouble(FP, 1), load_scene(FP), profiles, steps="fly")


def test_robots_crossing_paths_never_share_a_cell_in_thor() -> None:
    env, unity = make("1,2,3,4")
    targets = {"robot1": "Fridge_1", "robot2": "Sink_1", "robot3": "StoveBurner_1", "robot4": "Toaster_1"}
    for robot, target in targets.items():
        env.start(robot, Action(skill=Skill.GoToObject, target=target))
    done: list[ActionOutcome] = []
    while (t := env.next_event_time()) is not None:
        done += env.advance(t)
    assert len(done) == 4 and all(o.success for o in done), done  # the double refuses a move onto an agent
    assert check_motion(env.nav_record()).collisions == 0
    assert len(unity.by_action("MoveAhead")) > 8


def test_an_idle_robot_parked_in_the_doorway_steps_aside_in_thor() -> None:
    """FloorPlan5's one-cell doorway at (3, 1), robot 2 idle in it and robot 1 behind it
    (tests/test_sim_traffic.py's case): as in the simulator, robot 1's drive looks again,
    robot 2 is asked to step aside, its moves go to AI2-THOR, and robot 1 gets through."""
    from emboteam.world.navgrid import largest_component

    fp, door = "FloorPlan5", (3, 1)
    grid = load_grid(fp)
    other_side = largest_component(set(grid.cells) - {door})
    starts = {"robot1": NavGrid.point(min(other_side)), "robot2": NavGrid.point(door)}
    unity = UnityDouble(fp, 2)
    env = ThorEnvironment(unity, load_scene(fp), parse_team("1,2"), starts=starts)
    env.start("robot1", Action(skill=Skill.GoToObject, target="Apple_1"))
    done: list[ActionOutcome] = []
    while (t := env.next_event_time()) is not None:
        done += env.advance(t)
    assert [(o.robot, o.success) for o in done] == [("robot1", True)], done
    assert env.traffic.yields == 1
    robot2 = _replay(unity, 1)
    assert robot2 and grid.cell_at(robot2[-1][:2]) != door  # the double moved agent 1 off the doorway
    here = grid.cell_at(env.observe().robots["robot1"].position)
    assert here is not None and here not in other_side  # robot 1 went through
    assert check_motion(env.nav_record()).collisions == 0


def test_a_step_thor_refuses_ends_the_drive_where_the_agent_stands() -> None:
    env, unity = make()
    unity.fail_next("MoveAhead", "StandardIslandHeight is blocking Agent 0 from moving 0")
    failed = run(env, "robot1", Action(skill=Skill.GoToObject, target="Fridge_1"))
    assert not failed.success and failed.reason is FailureReason.NOT_REACHABLE
    assert "StandardIslandHeight" in failed.message
    agent = unity.agents[0]["agent"]["position"]
    here = load_grid(FP).cell_at((agent["x"], agent["z"]))
    assert here is not None and env.traffic.cell("robot1", env.now).cell == here
    assert env.observe().robots["robot1"].at is None
    assert run(env, "robot1", Action(skill=Skill.GoToObject, target="Fridge_1")).success  # from there


def test_agents_are_put_on_their_start_cells() -> None:
    profiles = parse_team("1,2")
    unity = UnityDouble(FP, 2, starts=[(0.1, 0.1), (-0.4, 0.3)])  # where AI2-THOR happened to put them
    starts = {"robot1": (-1.0, -1.5), "robot2": (-0.75, -1.5)}
    env = ThorEnvironment(unity, load_scene(FP), profiles, starts=starts)
    assert [(c["agentId"], c["position"]["x"], c["position"]["z"]) for c in unity.by_action("Teleport")] == [
        (0, -1.0, -1.5), (1, -0.75, -1.5)]
    assert {r: s.position for r, s in env.observe().robots.items()} == starts


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
    # two robots never end on the same grid cell
    env.start("robot5", Action(skill=Skill.GoToObject, target="Fridge_1"))
    env.start("robot24", Action(skill=Skill.GoToObject, target="Fridge_1"))
    while (t := env.next_event_time()) is not None:
        env.advance(t)
    a5, a24 = (unity.agents[i]["agent"]["position"] for i in (0, 1))
    assert (a5["x"], a5["z"]) != (a24["x"], a24["z"])


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
