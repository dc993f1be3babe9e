"""Convert ../shared/data/ai2thor into the package data of ``emboteam.world``.

Run from the repository root:  ``python scripts/build_world_data.py [--shared ../shared]``

Writes ``src/emboteam/world/data/catalogue.json`` and ``scenes.json.gz``. The AI2-THOR
metadata is MIT/Apache licensed and may ship with the package; the SMART-LLM task files
are *not* read here and must never be shipped.

Conversion decisions (each one documented in docs/world.md):
- stable ids ``Type_N``: objects of one type numbered 1.. in the order of their AI2-THOR
  objectId (a string that encodes the position, so the order is stable across dumps);
- parent: ``parentReceptacles`` lists *every* receptacle whose trigger box overlaps the
  object, in no useful order, with physics artefacts (a CounterTop "in" a Bowl, a
  DiningTable "in" its Chairs, a Floor "in" a GarbageCan). :func:`resolve_parents` keeps
  one immediate receptacle per object by the rule documented there and in docs/world.md;
  every parent id in the dump resolves exactly, and the result has no cycle (both checked);
- ``controls``: AI2-THOR's ``controlledObjects`` is missing from the dump, so each
  StoveKnob is paired with a StoveBurner by minimum-distance matching, and each Faucet or
  ShowerHead with the nearest basin within :data:`WATER_REACH` (the basin its water runs
  into) and the Sink / Bathtub that basin belongs to;
- initial state: AI2-THOR defaults (closed, off, clean, empty, room temperature) unless the
  dump records a non-default value.
"""

from __future__ import annotations

import argparse
import gzip
import itertools
import json
import math
import statistics
from collections import defaultdict
from pathlib import Path
from typing import Any

from emboteam.world.containment import WATER_BASINS, horizontal_distance, resolve_parents

PROPS = [
    "pickupable", "receptacle", "openable", "toggleable", "sliceable", "cookable",
    "breakable", "dirtyable", "canFillWithLiquid", "canBeUsedUp", "isHeatSource",
    "isColdSource", "moveable",
]

#: What slicing (or cracking) produces, and how many pieces. AI2-THOR spawns 7-10 pieces
#: for most types; we spawn fewer to keep planning problems small. No goal in any suite
#: depends on more than two pieces of one object.
SLICE_PRODUCTS: dict[str, tuple[str, int]] = {
    "Apple": ("AppleSliced", 3),
    "Bread": ("BreadSliced", 3),
    "Lettuce": ("LettuceSliced", 3),
    "Potato": ("PotatoSliced", 3),
    "Tomato": ("TomatoSliced", 3),
    "Egg": ("EggCracked", 1),
}

#: Openable receptacles that enclose their contents although AI2-THOR's
#: MustBeOpenToPlaceObjectsIn omits them: a closed Safe's door blocks every placement in
#: AI2-THOR's physics. (A Toilet is *not* among them: things stand on its tank with the lid
#: closed, as 43 objects do in the bathroom scenes.)
ENCLOSED_TOO = frozenset({"Safe"})

#: Receptacles that accept only some types (AI2-THOR SimObjType.cs and the public object
#: table: "CoffeeMachines ... only allow objects of type Mug", "StoveBurners ... only allow
#: Pot, Pan and Kettle", Toaster takes BreadSliced, the holders take their one type).
RECEPTACLE_WHITELIST = {
    "CoffeeMachine": ["Mug"],
    "Toaster": ["BreadSliced"],
    "TowelHolder": ["Towel"],
    "HandTowelHolder": ["HandTowel"],
    "ToiletPaperHanger": ["ToiletPaper"],
    "StoveBurner": ["Pot", "Pan", "Kettle"],
}


def room_of(floor_plan: str) -> str:
    n = int(floor_plan.removeprefix("FloorPlan"))
    if n < 100:
        return "kitchen"
    return {2: "living_room", 3: "bedroom", 4: "bathroom"}[n // 100]


def truthy(value: Any) -> bool:
    """A type-level flag: True, or 'mixed k/n' (true for some instances) counts as True."""
    return value is True or (isinstance(value, str) and value.startswith("mixed"))


def build_catalogue(shared: Path, scenes_raw: dict[str, list[dict[str, Any]]]) -> dict[str, Any]:
    ai = shared / "data" / "ai2thor"
    type_props = json.loads((ai / "object_type_properties.json").read_text())
    web = json.loads((ai / "object_types_web_table.json").read_text())
    restr = json.loads((ai / "receptacle_restrictions.json").read_text())

    masses: dict[str, list[float]] = defaultdict(list)
    for objs in scenes_raw.values():
        for o in objs:
            if o["mass"]:
                masses[o["objectType"]].append(float(o["mass"]))

    types: dict[str, Any] = {}
    for name in sorted(set(type_props) | set(web)):
        if name == "TargetCircle":  # an AI2-THOR debugging marker, not a household object
            continue
        if name in type_props:
            flags = sorted(p for p in PROPS if truthy(type_props[name].get(p)))
        else:  # slice products only appear in the web table
            flags = sorted(p for p in web[name]["actionable_properties"] if p in PROPS)
        rooms = sorted(type_props.get(name, {}).get("scene_count", {}))
        mass = statistics.median(masses[name]) if masses.get(name) else 0.0
        types[name] = {"properties": flags, "mass": round(mass, 3), "rooms": rooms}

    # slice products: mass is the whole's mass split over the pieces
    for whole, (piece, n) in SLICE_PRODUCTS.items():
        types[piece]["mass"] = round(types[whole]["mass"] / n, 3)
        if piece == "EggCracked":
            types[piece]["mass"] = types[whole]["mass"]

    placement = {k: sorted(v) for k, v in restr["PlacementRestrictions"].items()}
    for piece in ("LettuceSliced", "TomatoSliced", "AppleSliced", "PotatoSliced", "EggCracked"):
        if piece not in placement and piece in web:
            placement[piece] = sorted(r for r in web[piece]["compatible_receptacles"] if r)

    return {
        "source": "converted by scripts/build_world_data.py from ../shared/data/ai2thor "
        "(AI2-THOR 5.x metadata, MIT/Apache)",
        "types": types,
        "placement": placement,
        "must_be_open": sorted(set(restr["MustBeOpenToPlaceObjectsIn"]) | ENCLOSED_TOO),
        "in_receptacles": sorted(restr["InReceptacles"]),
        "receptacle_whitelist": RECEPTACLE_WHITELIST,
        "slice_products": SLICE_PRODUCTS,
    }


def _num(key: str) -> int:
    return int(key.rsplit("_", 1)[1])


def _dist(a: dict[str, float], b: dict[str, float]) -> float:
    return math.dist((a["x"], a["y"], a["z"]), (b["x"], b["y"], b["z"]))


def _pair_knobs(knobs: list[dict[str, Any]], burners: list[dict[str, Any]]) -> dict[str, str]:
    """Minimum total distance one-to-one matching (scenes have at most 6 knobs: brute force)."""
    if not knobs or not burners:
        return {}
    best: tuple[float, tuple[int, ...]] | None = None
    small, large = (knobs, burners) if len(knobs) <= len(burners) else (burners, knobs)
    for perm in itertools.permutations(range(len(large)), len(small)):
        cost = sum(_dist(small[i]["position"], large[j]["position"]) for i, j in enumerate(perm))
        if best is None or cost < best[0]:
            best = (cost, perm)
    assert best is not None
    pairs = {}
    for i, j in enumerate(best[1]):
        knob, burner = (small[i], large[j]) if small is knobs else (large[j], small[i])
        pairs[knob["objectId"]] = burner["objectId"]
    return pairs


#: How far (horizontally, m) a Faucet's or ShowerHead's water reaches: it runs into the
#: nearest basin within this distance, or into nothing (a shower over a bare floor).
WATER_REACH = 1.5

WATER_OUTERS = ("Sink", "Bathtub")


def water_links(objs: list[dict[str, Any]]) -> dict[str, list[str]]:
    """Faucet/ShowerHead -> the basin its water runs into and that basin's Sink/Bathtub."""
    by_id = {o["objectId"]: o for o in objs}
    basins = [o for o in objs if o["objectType"] in WATER_BASINS]
    # a Sink/Bathtub with no basin object of its own is its own basin
    owned = {b["objectId"].rsplit("|", 1)[0] for b in basins}
    basins += [o for o in objs if o["objectType"] in WATER_OUTERS and o["objectId"] not in owned]
    basins = [b for b in basins if "receptacle" in b["props"]]  # water into nothing does nothing
    links: dict[str, list[str]] = {}
    for src in (o for o in objs if o["objectType"] in ("Faucet", "ShowerHead")):
        # a shower head runs into a bathtub, never into a sink (shower stalls have no basin)
        near = [b for b in basins if horizontal_distance(b["position"], src["position"]) <= WATER_REACH
                and (src["objectType"] == "Faucet" or b["objectId"].startswith("Bathtub"))]
        if not near:
            continue
        basin = min(near, key=lambda b: (horizontal_distance(b["position"], src["position"]), b["objectId"]))
        links[src["objectId"]] = [basin["objectId"]]
        outer = basin["objectId"].rsplit("|", 1)[0]
        if outer != basin["objectId"] and outer in by_id:
            links[src["objectId"]].append(outer)
    return links


def convert_scene(floor_plan: str, objs: list[dict[str, Any]]) -> dict[str, Any]:
    by_thor = {o["objectId"]: o for o in objs}
    counters: dict[str, int] = defaultdict(int)
    stable: dict[str, str] = {}
    for o in sorted(objs, key=lambda o: (o["objectType"], o["objectId"])):
        counters[o["objectType"]] += 1
        stable[o["objectId"]] = f"{o['objectType']}_{counters[o['objectType']]}"
    for o in objs:
        for p in o["parentReceptacles"] or []:
            if p not in by_thor:
                raise SystemExit(f"{floor_plan}: parent {p} of {o['objectId']} not in scene")

    controls: dict[str, list[str]] = defaultdict(list)
    knobs = [o for o in objs if o["objectType"] == "StoveKnob"]
    burners = [o for o in objs if o["objectType"] == "StoveBurner"]
    for knob, burner in _pair_knobs(knobs, burners).items():
        controls[knob].append(burner)
    for src, targets in water_links(objs).items():
        controls[src].extend(targets)
    parents = resolve_parents(objs)

    out = []
    for o in sorted(objs, key=lambda o: (o["objectType"], _num(stable[o["objectId"]]))):
        st = o["state"]
        state: dict[str, Any] = {}
        # ``isOpen`` decides (AI2-THOR's OpenObject/PutObject checks read it); three
        # cabinets/drawers report openness 1.0 with isOpen false and stay closed
        if st.get("isOpen"):
            state["is_open"] = True
        if st.get("isToggled"):
            state["is_on"] = True
        if st.get("isDirty"):
            state["is_dirty"] = True
        if st.get("isFilledWithLiquid"):
            state["liquid"] = "wine" if o["objectType"] == "WineBottle" else "water"
        if st.get("temperature") in ("Hot", "Cold"):
            state["temperature"] = st["temperature"]
        pos = o["position"]
        parent = parents[o["objectId"]]
        out.append({
            "id": stable[o["objectId"]],
            "thor_id": o["objectId"],
            "type": o["objectType"],
            "properties": sorted(p for p in o["props"] if p in PROPS),
            "mass": float(o["mass"] or 0.0),
            "position": [round(pos["x"], 3), round(pos["y"], 3), round(pos["z"], 3)],
            "parent": stable[parent] if parent is not None else None,
            "state": state,
            "controls": [stable[c] for c in controls.get(o["objectId"], [])],
        })
    return {"floor_plan": floor_plan, "room": room_of(floor_plan), "objects": out}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shared", type=Path, default=Path(__file__).resolve().parents[2] / "shared")
    ap.add_argument("--out", type=Path, default=Path(__file__).resolve().parents[1] / "src/emboteam/world/data")
    args = ap.parse_args()
    raw = json.loads((args.shared / "data/ai2thor/scene_inventories.json").read_text())
    args.out.mkdir(parents=True, exist_ok=True)
    catalogue = build_catalogue(args.shared, raw)
    (args.out / "catalogue.json").write_text(json.dumps(catalogue, indent=1, sort_keys=True) + "\n")
    scenes = {fp: convert_scene(fp, objs) for fp, objs in sorted(raw.items(), key=lambda kv: int(kv[0][9:]))}
    payload = json.dumps({"source": catalogue["source"], "scenes": scenes}, separators=(",", ":"))
    # mtime=0 keeps the archive byte-identical across rebuilds
    with gzip.GzipFile(args.out / "scenes.json.gz", "wb", mtime=0) as fh:
        fh.write(payload.encode())
    print(f"wrote {len(catalogue['types'])} types, {len(scenes)} scenes to {args.out}")


if __name__ == "__main__":
    main()
