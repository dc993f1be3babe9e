"""Interaction poses: where a robot stands, and which way it faces, to act on something.

A pose is a reachable cell within AI2-THOR's interaction distance (1.5 m, horizontally)
of the object's point, facing it (the 90° heading nearest the bearing to the object).
For openable objects ALFRED recorded the pose it opened them from; it is used when the
object id still exists (AI2-THOR 5.x renamed some), its cell is on the grid and the object
is within reach from it. Otherwise the nearest reachable cell is chosen (the one ALFRED's
planner would stop at), ties broken by cell order so plans are reproducible.

Objects move (carried, put elsewhere), so poses are looked up by the object's current
point, and cached per point: the set of points in an episode is small.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

from emboteam.world.navgrid import GRID, Cell, NavGrid, heading_of_rotation, load_grid

#: AI2-THOR's default interaction (visibility) distance, metres (as ``world.state.REACH``)
REACH = 1.5


@dataclass(frozen=True, slots=True)
class Pose:
    """A cell and a heading index (0..3, see :mod:`emboteam.world.navgrid`)."""

    cell: Cell
    heading: int


def facing(cell: Cell, point: tuple[float, float]) -> int:
    """The heading from ``cell`` that points most nearly at ``point``."""
    dx, dz = point[0] - cell[0] * GRID, point[1] - cell[1] * GRID
    if abs(dx) < 1e-9 and abs(dz) < 1e-9:
        return 0
    return heading_of_rotation(math.degrees(math.atan2(dx, dz)))


def _dist(cell: Cell, point: tuple[float, float]) -> float:
    return math.hypot(cell[0] * GRID - point[0], cell[1] * GRID - point[1])


def candidate_poses(grid: NavGrid, point: tuple[float, float], thor_id: str | None = None,
                    limit: int = 12) -> tuple[Pose, ...]:
    """Poses to act on the thing at ``point``, best first: ALFRED's openable pose when it
    fits, then reachable cells within reach by distance. Empty when nothing is in reach."""
    return _candidates(grid.floor_plan, round(point[0], 3), round(point[1], 3), thor_id, limit)


@lru_cache(maxsize=65536)
def _candidates(floor_plan: str, x: float, z: float, thor_id: str | None, limit: int) -> tuple[Pose, ...]:
    grid = load_grid(floor_plan)
    point = (x, z)
    out: list[Pose] = []
    alfred = grid.openable.get(thor_id) if thor_id else None
    if alfred is not None:
        cell = grid.cell_at((alfred[0], alfred[1]))
        if cell is not None and _dist(cell, point) <= REACH:
            out.append(Pose(cell, heading_of_rotation(alfred[2])))
    near = sorted((c for c in grid.ordered if _dist(c, point) <= REACH), key=lambda c: (_dist(c, point), c))
    out.extend(Pose(c, facing(c, point)) for c in near if not out or c != out[0].cell)
    return tuple(out[:limit])


def interaction_pose(grid: NavGrid, point: tuple[float, float], thor_id: str | None = None) -> Pose | None:
    """The preferred pose for the thing at ``point``; ``None`` when no reachable cell is
    within reach (the object cannot be acted on in this floor plan's grid)."""
    poses = candidate_poses(grid, point, thor_id, limit=1)
    return poses[0] if poses else None
