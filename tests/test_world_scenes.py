"""Scenes as package data, object by object against AI2-THOR's metadata dump."""

from __future__ import annotations

import math
import re
from typing import Any

import pytest

from emboteam.errors import UnknownObjectError, UnknownSceneError
from emboteam.world import WorldState, load_scene, scene_ids
from emboteam.world.navgrid import load_grid
from emboteam.world.scene import (
    START_CLEARANCE,
    Scene,
    SceneObject,
    is_object_id,
    normalize_floor_plan,
)

#: the floor plans of SMART-LLM's and MACE-THOR's tasks: these must be exact
CORE = ("FloorPlan1", "FloorPlan6", "FloorPlan15", "FloorPlan21", "FloorPlan201", "FloorPlan209",
        "FloorPlan303", "FloorPlan414")

PROPS = {"pickupable", "receptacle", "openable", "toggleable", "sliceable", "cookable", "breakable",
         "dirtyable", "canFillWithLiquid", "canBeUsedUp", "isHeatSource", "isColdSource", "moveable"}


def _expected_state(o: dict[str, Any]) -> dict[str, Any]:
    """The non-default state of a dump object in our terms."""
    st = o["state"]
    return {
        "is_open": bool(st.get("isOpen", False)),
        "is_on": bool(st.get("isToggled", False)),
        "is_dirty": bool(st.get("isDirty", False)),
        "liquid": ("wine" if o["objectType"] == "WineBottle" else "water")
        if st.get("isFilledWithLiquid") else None,
        "temperature": st.get("temperature", "RoomTemp"),
    }


def _kind(o: SceneObject) -> str:
    if o.has("pickupable"):
        return "pickupable"
    return "moveable" if o.has("moveable") else "fixture"


def test_all_120_floor_plans_in_order() -> None:
    ids = scene_ids()
    assert len(ids) == 120
    nums = [int(i.removeprefix("FloorPlan")) for i in ids]
    assert nums == [*range(1, 31), *range(201, 231), *range(301, 331), *range(401, 431)]
    rooms = {load_scene(i).room for i in ("FloorPlan1", "FloorPlan201", "FloorPlan301", "FloorPlan401")}
    assert rooms == {"kitchen", "living_room", "bedroom", "bathroom"}


@pytest.mark.parametrize("name", ["FloorPlan6", "floorplan6", "6", "FP6", 6, " FloorPlan6 "])
def test_floor_plan_spellings(name: str | int) -> None:
    assert normalize_floor_plan(name) == "FloorPlan6"


@pytest.mark.parametrize("name", ["FloorPlan31", "FloorPlan0", "kitchen", "", "FloorPlan-1", 500])
def test_unknown_floor_plans_are_typed_errors(name: str | int) -> None:
    with pytest.raises(UnknownSceneError):
        load_scene(name)


def test_unknown_object_is_a_typed_error() -> None:
    with pytest.raises(UnknownObjectError, match="Unicorn_1"):
        load_scene(1).get("Unicorn_1")


@pytest.mark.parametrize("fp", CORE)
def test_core_scene_matches_ai2thor_object_by_object(
        fp: str, thor_inventories: dict[str, list[dict[str, Any]]]) -> None:
    scene = load_scene(fp)
    dump = thor_inventories[fp]
    by_thor = {o.thor_id: o for o in scene.objects}
    assert len(scene.objects) == len(dump) == len(by_thor), "one scene object per AI2-THOR object"
    for d in dump:
        o = by_thor[d["objectId"]]
        assert o.type == d["objectType"]
        assert re.fullmatch(rf"{o.type}_\d+", o.id) and is_object_id(o.id)
        assert o.properties == {p for p in d["props"] if p in PROPS}, o.id
        assert o.mass == pytest.approx(float(d["mass"] or 0.0)), o.id
        assert o.position == pytest.approx((d["position"]["x"], d["position"]["y"], d["position"]["z"]),
                                           abs=5e-4), o.id
        assert o.state.model_dump() == _expected_state(d), o.id
        parents = d["parentReceptacles"] or []
        if o.parent is None:
            # only fixtures (counters, cabinets: their trigger-box overlaps are artefacts)
            # and fully free objects have no parent
            assert _kind(o) == "fixture" or not parents, o.id
        else:
            p = scene.get(o.parent)
            is_basin_of = o.type in ("SinkBasin", "BathtubBasin") and o.thor_id.startswith(p.thor_id + "|")
            assert p.thor_id in parents or is_basin_of, o.id
            # a basin is part of its Sink/Bathtub even where that is no receptacle itself
            assert p.has("receptacle") or is_basin_of, o.id


@pytest.mark.parametrize("fp", CORE)
def test_stable_ids_number_each_type_in_objectid_order(fp: str) -> None:
    scene = load_scene(fp)
    for t in scene.types():
        objs = scene.of_type(t)
        assert sorted(o.id for o in objs) == sorted(f"{t}_{k}" for k in range(1, len(objs) + 1))
        by_num = sorted(objs, key=lambda o: int(o.id.rsplit("_", 1)[1]))
        assert [o.thor_id for o in by_num] == sorted(o.thor_id for o in objs)


@pytest.mark.parametrize(("fp", "thor_prefix", "parent_type"), [
    # each object below is listed by AI2-THOR in two or more receptacles
    ("FloorPlan15", "Mug|-03.38|+00.95|+03.27", "CoffeeMachine"),      # not the counter under it
    ("FloorPlan15", "Pot|-03.14|+00.96|+02.37", "StoveBurner"),        # the nearer of two burners
    ("FloorPlan201", "Book|-01.87|+00.68|+01.17", "DiningTable"),      # not the chair tucked under
    ("FloorPlan201", "Plate|-02.40|+00.68|+01.68", "DiningTable"),
    ("FloorPlan201", "DiningTable|", "Floor"),                         # not "in" its chairs
    ("FloorPlan209", "Pillow|-04.28|+00.42|-01.74", "Sofa"),           # not the floor
    ("FloorPlan209", "Box|-02.36|+00.25|-01.65", "Shelf"),
    ("FloorPlan209", "KeyChain|-04.21|+00.32|-03.65", "ArmChair"),
])
def test_ambiguous_parents_resolve_to_the_immediate_receptacle(fp: str, thor_prefix: str,
                                                               parent_type: str) -> None:
    scene = load_scene(fp)
    o = next(o for o in scene.objects if o.thor_id.startswith(thor_prefix))
    assert o.parent is not None and scene.get(o.parent).type == parent_type
    if thor_prefix.startswith("Pot"):
        burners = [b for b in scene.of_type("StoveBurner")]
        nearest = min(burners, key=lambda b: math.dist(b.position[::2], o.position[::2]))
        assert o.parent == nearest.id


def test_basin_belongs_to_its_sink() -> None:
    scene = load_scene("FloorPlan1")
    basin = scene.of_type("SinkBasin")[0]
    assert basin.parent is not None and scene.get(basin.parent).type == "Sink"
    assert basin.thor_id.startswith(scene.get(basin.parent).thor_id)


@pytest.mark.parametrize("fp", scene_ids())
def test_every_scene_is_a_consistent_forest(fp: str) -> None:
    """No object contains itself (the raw dump has CounterTop-in-Bowl cycles), every
    parent is a receptacle of the scene, and the initial state passes the invariants."""
    scene = load_scene(fp)
    state = WorldState.from_scene(scene)
    assert state.invariant_violations() == []
    for o in scene.objects:
        if o.parent is not None and o.type not in ("SinkBasin", "BathtubBasin"):
            assert scene.get(o.parent).has("receptacle"), o.id
        if o.type == "Floor" or (_kind(o) == "fixture" and o.type not in ("SinkBasin", "BathtubBasin")):
            assert o.parent is None, o.id


def _knob_burner_pairs(scene: Scene) -> dict[str, str]:
    pairs = {}
    for knob in scene.of_type("StoveKnob"):
        burners = [c for c in knob.controls if scene.get(c).type == "StoveBurner"]
        assert len(burners) == 1, f"{knob.id} controls {knob.controls}"
        pairs[knob.id] = burners[0]
    return pairs


@pytest.mark.parametrize("fp", [f"FloorPlan{i}" for i in range(1, 31)])
def test_each_knob_switches_one_distinct_nearby_burner(fp: str) -> None:
    scene = load_scene(fp)
    pairs = _knob_burner_pairs(scene)
    assert len(pairs) == len(scene.of_type("StoveBurner")) > 0
    assert len(set(pairs.values())) == len(pairs), "two knobs for one burner"
    for knob, burner in pairs.items():
        assert math.dist(scene.get(knob).position, scene.get(burner).position) < 0.6


def test_floorplan1_knob_matches_rl_thor_recording() -> None:
    """rl_thor's FloorPlan1 recording cooks a potato in a pan on the front-left burner
    by toggling this knob (Kajiih/rl_thor, generate_tasks_test_data.py)."""
    scene = load_scene("FloorPlan1")
    knob = next(o for o in scene.objects if o.thor_id == "StoveKnob|-00.48|+00.88|-02.19")
    burner = scene.get(knob.controls[0])
    assert burner.thor_id == "StoveBurner|-00.47|+00.92|-02.37"


@pytest.mark.parametrize("fp", [*CORE, "FloorPlan24", "FloorPlan401", "FloorPlan420", "FloorPlan430"])
def test_water_runs_into_a_basin_in_reach(fp: str) -> None:
    scene = load_scene(fp)
    for src in scene.of_type("Faucet", "ShowerHead"):
        if not src.controls:
            assert src.type == "ShowerHead" or fp == "FloorPlan430", src.id  # its tub holds nothing
            continue
        basin = scene.get(src.controls[0])
        assert basin.type in ("SinkBasin", "BathtubBasin", "Sink", "Bathtub") and basin.has("receptacle")
        assert math.dist(basin.position[::2], src.position[::2]) <= 1.5
        if src.type == "ShowerHead":
            assert basin.thor_id.startswith("Bathtub"), "showers run into bathtubs, not sinks"
        for outer in src.controls[1:]:
            assert basin.thor_id.startswith(scene.get(outer).thor_id + "|")
    if scene.room == "kitchen":
        faucet = scene.of_type("Faucet")[0]
        assert scene.get(faucet.controls[0]).type == "SinkBasin"


def _placed(scene: Scene) -> list[tuple[float, float]]:
    return [(o.position[0], o.position[2]) for o in scene.objects
            if o.type != "Floor" and o.position != (0.0, 0.0, 0.0)]


@pytest.mark.parametrize("fp", scene_ids())
def test_robots_start_on_free_floor_inside_the_room(fp: str) -> None:
    """Start cells keep clear of every object and have objects on all four sides: the old
    bounding-box centre put robots in an island (FloorPlan8, 23) or outside an L-shaped
    room (FloorPlan28, 209, 219, 223)."""
    scene = load_scene(fp)
    pts = _placed(scene)
    starts = [scene.robot_start(i) for i in range(4)]
    grid = load_grid(fp)
    for i, (x, z) in enumerate(starts):
        assert grid.cell_at((x, z)) is not None, "robots start on a reachable cell of the grid"
        # FloorPlan425's grid (25 cells) has only three cells both clear of objects and
        # 0.5 m apart: its fourth robot starts on a reachable cell nearer a fixture
        if not (fp == "FloorPlan425" and i == 3):
            assert min(math.hypot(px - x, pz - z) for px, pz in pts) >= START_CLEARANCE - 1e-9
        assert any(px > x for px, pz in pts if abs(pz - z) <= 1.0)
        assert any(px < x for px, pz in pts if abs(pz - z) <= 1.0)
        assert any(pz > z for px, pz in pts if abs(px - x) <= 1.0)
        assert any(pz < z for px, pz in pts if abs(px - x) <= 1.0)
    for i, a in enumerate(starts):
        for b in starts[i + 1:]:
            assert math.dist(a, b) >= 0.5 - 1e-9
    assert starts == [scene.robot_start(i) for i in range(4)], "deterministic"
    assert len({scene.robot_start(i) for i in range(10)}) == 10, "a large team gets distinct cells"
    assert all(grid.cell_at(scene.robot_start(i)) is not None for i in range(10))
