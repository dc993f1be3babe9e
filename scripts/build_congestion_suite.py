"""Write src/emboteam/bench/data/congestion.json: the congestion suite.

Candidates: in small bathrooms and kitchens, 4 to 8 robots each get an errand (a goal
condition) from a pool of that room's errands, rotated so robots cross the room; in rooms
whose navigation grid has a one-cell doorway, one robot starts parked in the doorway and
the others on the far side of it (``starts``). Every candidate is run once with the oracle
front end and avoidance on; only tasks it solves are written (as MACE-THOR keeps only
solvable tasks), and the script says which were dropped and why.

    PYTHONPATH=src .venv/bin/python scripts/build_congestion_suite.py
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from emboteam.bench.mace_thor import parse_tasks
from emboteam.config import RunConfig
from emboteam.pipeline import run_episode
from emboteam.world.navgrid import NavGrid, largest_component, load_grid
from emboteam.world.navigation import navigator
from emboteam.world.scene import load_scene

OUT = Path(__file__).resolve().parents[1] / "src" / "emboteam" / "bench" / "data" / "congestion.json"

BATH_POOL: list[tuple[str, list[dict[str, Any]]]] = [
    ("switched_off(LightSwitch)", []),
    ("inside(Towel, TowelHolder)", [{"object": "Towel_1", "parent": "Toilet_1"}]),
    ("inside(HandTowel, HandTowelHolder)", [{"object": "HandTowel_1", "parent": "Toilet_1"}]),
    ("inside(SprayBottle, Toilet)", []),
    ("inside(Cloth, Sink)", []),
    ("switched_on(Faucet)", []),
    ("inside(Candle, Toilet)", []),
    ("inside(SoapBar, Bathtub|Sink)", []),
    ("inside(ToiletPaper, ToiletPaperHanger)", []),
    ("inside(SoapBottle, Toilet)", []),
]
KITCHEN_POOL: list[tuple[str, list[dict[str, Any]]]] = [
    ("switched_off(LightSwitch)", []),
    ("inside(Apple, Fridge)", []),
    ("switched_on(Toaster)", []),
    ("inside(Mug, Sink)", []),
    ("switched_on(CoffeeMachine)", []),
    ("inside(Tomato, Fridge)", []),
    ("inside(Cup, Sink)", []),
    ("inside(Potato, Microwave)", []),
    ("sliced(Bread)", []),
    ("inside(Egg, Pan|Pot)", []),
]
TEAMS = ["1,2,3,4", "1,2,3,4,9", "1,2,3,4,9,28", "1,2,3,4,1,2,3", "1,2,3,4,1,2,3,4"]
BATHROOMS = ["FloorPlan401", "FloorPlan403", "FloorPlan405", "FloorPlan409", "FloorPlan412", "FloorPlan413",
             "FloorPlan418", "FloorPlan420", "FloorPlan425"]
KITCHENS = ["FloorPlan25", "FloorPlan30", "FloorPlan20", "FloorPlan5"]
# (the towels start on the toilet, not the floor: the Floor's pivot, where the setup would
# put them, lies out of reach in some bathrooms; a plunger may go on no receptacle here)
#: (floor plan, doorway cell): a cell whose removal cuts the grid in two parts
DOORWAYS = [("FloorPlan5", (3, 1)), ("FloorPlan13", (-5, 11)), ("FloorPlan30", (0, 0)), ("FloorPlan412", (-6, -4))]


def _usable(fp: str, pool: list[tuple[str, list[dict[str, Any]]]]) -> list[tuple[str, list[dict[str, Any]]]]:
    scene = load_scene(fp)
    types = scene.types()
    out = []
    for cond, setup in pool:
        args = [part.strip() for part in cond[cond.index("(") + 1:-1].split(",")]
        if all(any(n in types for n in arg.split("|")) for arg in args) \
                and all(scene.has_object(c["object"]) for c in setup):
            out.append((cond, setup))
    return out


def _task(tid: str, fp: str, team: str, conds: list[tuple[str, list[dict[str, Any]]]], note: str,
          starts: list[tuple[float, float]] | None = None) -> dict[str, Any]:
    setup = [c for _, s in conds for c in s]
    goal = [c for c, _ in conds]
    room = "bathroom" if int(fp.removeprefix("FloorPlan")) >= 400 else "kitchen"
    instruction = f"In the {room}: " + "; ".join(g.replace("(", " ").replace(")", "").replace(",", " ->")
                                                 for g in goal) + "."
    task: dict[str, Any] = {"id": tid, "floor_plan": fp, "category": "parallel",
                            "robots": [int(r) for r in team.split(",")], "instruction": instruction,
                            "goal": goal, "notes": note}
    if setup:
        task["setup"] = setup
    if starts:
        task["starts"] = [list(p) for p in starts]
    return task


def candidates() -> list[dict[str, Any]]:
    out = []
    k = 0
    for fp in BATHROOMS + KITCHENS:
        pool = _usable(fp, BATH_POOL if fp in BATHROOMS else KITCHEN_POOL)
        for j, team in enumerate(TEAMS[:3] if fp in KITCHENS else TEAMS[::2]):
            n = len(team.split(","))
            rot = (k * 3) % len(pool)
            conds = (pool[rot:] + pool[:rot])[:n]
            k += 1
            out.append(_task(f"{fp.lower().replace('floorplan', 'fp')}-crowd{j + 1}", fp, team, conds,
                             f"{n} robots, {len(conds)} errands across a {len(load_grid(fp).cells)}-cell grid"))
    for fp, door in DOORWAYS:
        grid = load_grid(fp)
        nav = navigator(fp)
        parts = [largest_component(set(grid.cells) - {door})]
        parts.append(set(grid.cells) - {door} - parts[0])
        scene = load_scene(fp)
        posed = [nav.pose_for((o.position[0], o.position[2])) for o in scene.objects]
        work = max(parts, key=lambda part: sum(1 for p in posed if p is not None and p.cell in part))
        far = sorted(parts[1] if work is parts[0] else parts[0], key=lambda c: (abs(c[0] - door[0]) + abs(c[1] - door[1]), c))
        pool = _usable(fp, BATH_POOL if int(fp.removeprefix("FloorPlan")) >= 400 else KITCHEN_POOL)
        for j, team in enumerate(("24,1,2,3", "1,2,3,4,9")):
            n = len(team.split(","))
            starts = [NavGrid.point(door), *[NavGrid.point(c) for c in far[1:2 * n:2]][:n - 1]]
            if len(starts) < n:
                continue
            conds = pool[j: j + n - 1]
            out.append(_task(f"{fp.lower().replace('floorplan', 'fp')}-doorway{j + 1}", fp, team, conds,
                             f"robot {team.split(',')[0]} starts parked in the one-cell doorway {NavGrid.point(door)}; "
                             "the others start beyond it", starts))
    return out


def main() -> int:
    doc = {"suite": "congestion", "version": 1,
           "description": "robots meeting on the navigation grid: crowded small rooms, crossing errands, "
                          "a robot parked in a doorway (scripts/build_congestion_suite.py)",
           "tasks": candidates()}
    tasks = parse_tasks(doc, suite="congestion", where="candidates")
    kept = []
    cfg = RunConfig(frontend="oracle")
    for raw, task in zip(doc["tasks"], tasks, strict=True):
        ep = run_episode(task, cfg)
        status = "kept" if ep.success else f"dropped ({ep.error or 'goal unmet'})"
        print(f"{task.id}: {status}; makespan {ep.makespan:.2f}, collisions {ep.collisions}, "
              f"waits {ep.nav_waits}, replans {ep.nav_replans}", file=sys.stderr)
        if ep.success:
            kept.append(raw)
    doc["tasks"] = kept
    OUT.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"{len(kept)} tasks written to {OUT}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
