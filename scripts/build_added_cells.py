"""Derive the grid cells added for AI2-THOR 5.x objects the 2.1 grid does not reach
(src/emboteam/world/data/nav/added_cells.json).

ALFRED's grids are AI2-THOR 2.1's; our objects are 5.x's, and in some floor plans an object
lies beyond the 1.5 m interaction distance of every reachable cell. For every floor plan and
every such object this script looks for the shortest chain of new cells, on the same 0.25 m
lattice, from the grid to a cell within reach of the object. A cell may join the grid only if

- it lies on the floor inside the room: objects lie on all four sides of it within
  ``ROOM_BAND`` (the test ``scene.free_floor_cells`` uses for start cells), so a chain cannot
  leave the room through a wall;
- it is not inside an object: the metadata dump has object pivots, not bounding boxes, so an
  object's footprint is estimated from the data itself: for each object type, how close any
  reachable cell of any of the 120 floor plans comes to a pivot of that type (the
  ``FOOTPRINT_QUANTILE`` of the per-object nearest-cell distances). A candidate closer than
  that to an object of the type would stand where AI2-THOR 2.1's agent never stood next to
  such an object;
- it is connected to the grid (each chain starts beside a kept cell). Chains are not capped
  in length: the room test bounds them (the longest, in FloorPlan402 and FloorPlan29, has
  five and six cells).

Objects no chain reaches stay unposed (``emboteam scene N`` names them; a task that needs
one is rejected with UnreachableObjectError). Each added cell records why it was added.

    PYTHONPATH=src python3 scripts/build_added_cells.py [--check]

``--check`` compares with the file in the package and exits 1 when they differ.
"""

from __future__ import annotations

import json
import math
import sys
from collections import deque
from pathlib import Path

from emboteam.world.navgrid import GRID, STEPS, Cell, NavGrid, load_base_grid
from emboteam.world.poses import REACH
from emboteam.world.scene import ROOM_BAND, Scene, load_scene, scene_ids

ROOT = Path(__file__).resolve().parents[1]
TARGET = ROOT / "src" / "emboteam" / "world" / "data" / "nav" / "added_cells.json"
#: the quantile of (per object) nearest-reachable-cell distances that estimates a type's footprint
FOOTPRINT_QUANTILE = 0.05
#: types seen fewer times than this use the footprint over all types
MIN_TYPE_SAMPLES = 5


def _placed(scene: Scene) -> list[tuple[str, float, float]]:
    return [(o.type, o.position[0], o.position[2]) for o in scene.objects
            if o.type != "Floor" and o.position != (0.0, 0.0, 0.0)]


def _nearest_cell(grid: NavGrid, x: float, z: float) -> float:
    return min(math.hypot(c[0] * GRID - x, c[1] * GRID - z) for c in grid.ordered)


def _quantile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


def footprints() -> tuple[dict[str, float], float]:
    """Per type, how close (m) reachable cells come to a pivot of that type; and over all types."""
    per_type: dict[str, list[float]] = {}
    for fp in scene_ids():
        grid = load_base_grid(fp)
        for kind, x, z in _placed(load_scene(fp)):
            per_type.setdefault(kind, []).append(_nearest_cell(grid, x, z))
    every = [d for ds in per_type.values() for d in ds]
    overall = _quantile(every, FOOTPRINT_QUANTILE)
    return ({k: round(_quantile(v, FOOTPRINT_QUANTILE), 3) for k, v in per_type.items()
             if len(v) >= MIN_TYPE_SAMPLES}, round(overall, 3))


def _in_room(pts: list[tuple[str, float, float]], x: float, z: float) -> bool:
    row = [(px, pz) for _, px, pz in pts if abs(pz - z) <= ROOM_BAND]
    col = [(px, pz) for _, px, pz in pts if abs(px - x) <= ROOM_BAND]
    return (any(px > x for px, _ in row) and any(px < x for px, _ in row)
            and any(pz > z for _, pz in col) and any(pz < z for _, pz in col))


class _Floor:
    """Which lattice cells of one floor plan may be added."""

    def __init__(self, scene: Scene, grid: NavGrid, feet: dict[str, float], overall: float) -> None:
        self.grid = grid
        self.pts = _placed(scene)
        self.feet = feet
        self.overall = overall
        self._ok: dict[Cell, bool] = {}

    def addable(self, cell: Cell) -> bool:
        if cell not in self._ok:
            x, z = NavGrid.point(cell)
            clear = all(math.hypot(px - x, pz - z) >= self.feet.get(kind, self.overall)
                        for kind, px, pz in self.pts)
            self._ok[cell] = cell not in self.grid.cells and clear and _in_room(self.pts, x, z)
        return self._ok[cell]

    def bridge(self, point: tuple[float, float]) -> list[Cell] | None:
        """The shortest chain of addable cells from the grid to a cell within reach of
        ``point`` (breadth-first from every grid cell; ties: cell order)."""
        parent: dict[Cell, Cell | None] = {}
        queue: deque[Cell] = deque()
        for c in self.grid.ordered:
            for di, dj in STEPS:
                n = (c[0] + di, c[1] + dj)
                if n not in parent and self.addable(n):
                    parent[n] = None
                    queue.append(n)
        while queue:
            cell = queue.popleft()
            x, z = NavGrid.point(cell)
            if math.hypot(x - point[0], z - point[1]) <= REACH:
                chain = [cell]
                while (prev := parent[chain[-1]]) is not None:
                    chain.append(prev)
                return chain[::-1]
            for di, dj in STEPS:
                n = (cell[0] + di, cell[1] + dj)
                if n not in parent and self.addable(n):
                    parent[n] = cell
                    queue.append(n)
        return None


def added_for(floor_plan: str, feet: dict[str, float], overall: float) -> list[dict[str, object]]:
    """The cells to add in one floor plan, each with the objects it was added for."""
    scene = load_scene(floor_plan)
    grid = load_base_grid(floor_plan)
    floor = _Floor(scene, grid, feet, overall)
    reasons: dict[Cell, list[str]] = {}
    for o in scene.objects:
        if o.type == "Floor":
            continue
        point = (o.position[0], o.position[2])
        if any(math.hypot(c[0] * GRID - point[0], c[1] * GRID - point[1]) <= REACH for c in grid.ordered):
            continue
        chain = floor.bridge(point)
        for k, cell in enumerate(chain or ()):
            role = "within reach of" if k == len(chain or ()) - 1 else "on the way to"
            reasons.setdefault(cell, []).append(f"{role} {o.id}")
    return [{"cell": list(c), "reason": "; ".join(r)} for c, r in sorted(reasons.items())]


def build() -> dict[str, object]:
    feet, overall = footprints()
    scenes = {}
    for fp in scene_ids():
        cells = added_for(fp, feet, overall)
        if cells:
            scenes[fp] = cells
    return {"about": "grid cells added to ALFRED's AI2-THOR 2.1 grids so that AI2-THOR 5.x objects are "
                     "within 1.5 m of a reachable cell; derived by scripts/build_added_cells.py",
            "footprint_quantile": FOOTPRINT_QUANTILE,
            "footprint_default": overall, "scenes": scenes}


def main(argv: list[str]) -> int:
    data = build()
    text = json.dumps(data, indent=1, sort_keys=True) + "\n"
    if "--check" in argv:
        same = TARGET.exists() and TARGET.read_text() == text
        print("up to date" if same else f"{TARGET} differs from what the script derives")
        return 0 if same else 1
    TARGET.write_text(text)
    scenes: dict[str, list[object]] = data["scenes"]  # type: ignore[assignment]
    print(f"{sum(len(v) for v in scenes.values())} cells in {len(scenes)} floor plans -> {TARGET}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
