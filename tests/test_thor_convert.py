"""AI2-THOR metadata -> WorldState, and our ids <-> objectIds, on the real AI2-THOR 5.x
metadata dumps of all 120 iTHOR floor plans (no AI2-THOR build needed)."""

from __future__ import annotations

import pytest

pytest.importorskip("ai2thor.server")

from ai2thor.server import Event, MultiAgentEvent

from emboteam.thor.convert import Member, world_state
from emboteam.thor.ids import ThorIds
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
from thor_unity_double import AGENT_Y, agent_metadata, floor_plans, metadata_objects

FIELDS = ("type", "properties", "mass", "position", "parent", "held_by", "is_open", "is_on", "is_sliced",
          "is_broken", "is_dirty", "is_cooked", "liquid", "temperature", "source", "controls")


def _convert(fp: str, team_spec: str = "1") -> tuple[WorldState, WorldState]:
    scene = load_scene(fp)
    team = parse_team(team_spec)
    objects = metadata_objects(fp)
    events = [Event(agent_metadata(objects, {"x": 0.0, "y": AGENT_Y, "z": 0.0}, i)) for i in range(len(team))]
    agents = [e.metadata for e in events]
    members = [Member(p, i) for i, p in enumerate(team)]
    return world_state(agents, scene, ThorIds(scene), members), WorldState.from_scene(scene, team)


@pytest.mark.parametrize("fp", floor_plans())
def test_fresh_scene_metadata_converts_to_the_scene_state(fp: str) -> None:
    """Every object of every floor plan: same id, type, flags, parent and state as the
    symbolic simulator starts from (the scene data was built from the same metadata)."""
    live, symbolic = _convert(fp)
    assert set(live.objects) == set(symbolic.objects)
    for oid, expected in symbolic.objects.items():
        got = live.objects[oid]
        for name in FIELDS:
            assert getattr(got, name) == getattr(expected, name), (oid, name)
    assert live.invariant_violations() == []


def test_ids_map_both_ways_on_every_scene() -> None:
    for fp in floor_plans():
        scene = load_scene(fp)
        ids = ThorIds(scene)
        for o in scene.objects:
            assert ids.ours(ids.thor(o.id)) == o.id
        assert ids.ours("Apple|+09.99|+09.99|+09.99") is None


def test_held_object_poses_and_agents_come_from_each_agents_metadata() -> None:
    fp = "FloorPlan1"
    scene = load_scene(fp)
    ids = ThorIds(scene)
    objects = metadata_objects(fp)
    apple = next(o for o in objects if o["objectId"] == ids.thor("Apple_1"))
    apple.update(isPickedUp=True, parentReceptacles=None)
    a0 = agent_metadata(objects, {"x": -1.0, "y": AGENT_Y, "z": 1.25}, 0)
    a1 = agent_metadata(objects, {"x": 0.5, "y": AGENT_Y, "z": -0.75}, 1)
    a1["inventoryObjects"] = [{"objectId": apple["objectId"], "objectType": "Apple"}]
    event = MultiAgentEvent(1, [Event(a0), Event(a1)])
    team = parse_team("5,24")
    state = world_state([e.metadata for e in event.events], scene, ids, [Member(p, i) for i, p in enumerate(team)],
                        at={"robot5": "Fridge_1"})
    assert state.robots["robot5"].position == (-1.0, 1.25) and state.robots["robot5"].at == "Fridge_1"
    assert state.robots["robot24"].position == (0.5, -0.75)
    assert state.robots["robot24"].holding == "Apple_1" and state.robots["robot5"].holding is None
    assert state.objects["Apple_1"].held_by == "robot24" and state.objects["Apple_1"].parent is None
    assert state.invariant_violations() == []


def test_slices_get_our_piece_ids_and_the_whole_stays_as_sliced() -> None:
    fp = "FloorPlan1"
    scene = load_scene(fp)
    ids = ThorIds(scene)
    objects = metadata_objects(fp)
    whole = next(o for o in objects if o["objectId"] == ids.thor("Tomato_1"))
    objects.remove(whole)  # AI2-THOR deactivates the whole when it spawns the pieces
    for k in range(7):
        objects.append({**whole, "objectId": f"{whole['objectId']}|TomatoSliced_{k}",
                        "objectType": "TomatoSliced", "sliceable": False, "isSliced": True})
    team = parse_team("1")
    state = world_state([agent_metadata(objects, {"x": 0.0, "y": AGENT_Y, "z": 0.0}, 0)], scene, ids,
                        [Member(team[0], 0)])
    assert state.objects["Tomato_1"].gone
    assert {f"Tomato_1_Slice_{k}" for k in range(1, 8)} <= set(state.objects)
    piece = state.objects["Tomato_1_Slice_1"]
    assert piece.source == "Tomato_1" and piece.parent == state.objects["Tomato_1"].parent
    assert ids.thor("Tomato_1_Slice_3") == f"{whole['objectId']}|TomatoSliced_2"


def test_state_flags_are_read_from_metadata() -> None:
    fp = "FloorPlan1"
    scene = load_scene(fp)
    ids = ThorIds(scene)
    objects = metadata_objects(fp)
    mug = next(o for o in objects if o["objectId"] == ids.thor("Mug_1"))
    mug.update(isDirty=True, isFilledWithLiquid=True, fillLiquid="coffee", temperature="Hot", isBroken=True)
    fridge = next(o for o in objects if o["objectId"] == ids.thor("Fridge_1"))
    fridge.update(isOpen=True)
    team = parse_team("1")
    state = world_state([agent_metadata(objects, {"x": 0.0, "y": AGENT_Y, "z": 0.0}, 0)], scene, ids,
                        [Member(team[0], 0)])
    m = state.objects["Mug_1"]
    assert (m.is_dirty, m.liquid, m.temperature, m.is_broken) == (True, "coffee", "Hot", True)
    assert state.objects["Fridge_1"].is_open
