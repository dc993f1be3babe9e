"""AI2-THOR's navigation grid of a floor plan: the cells an agent can stand on.

The reachable positions come from ALFRED (``GetReachablePositions`` in AI2-THOR 2.1, MIT
licence: ``world/data/nav/LICENSE.txt``), converted by ``scripts/build_nav_data.py`` into
one small file per floor plan. A cell is a pair of integer grid indices
(x / 0.25, z / 0.25). Headings follow AI2-THOR's ``rotation.y``: 0 faces +z, 90 +x, 180 -z,
270 -x; the grid code numbers them 0..3.
"""

from __future__ import annotations

import gzip
import json
import math
from dataclasses import dataclass, field
from functools import cache
from importlib import resources

from emboteam.errors import UnknownSceneError

#: AI2-THOR's grid size (m): one MoveAhead
GRID = 0.25

Cell = tuple[int, int]
#: heading index -> grid step (di, dj); index k is AI2-THOR rotation 90 * k degrees
STEPS: tuple[Cell, ...] = ((0, 1), (1, 0), (0, -1), (-1, 0))


def heading_of_rotation(degrees: float) -> int:
    """AI2-THOR ``rotation.y`` (degrees) -> heading index 0..3 (nearest 90°)."""
    return round((degrees % 360) / 90) % 4


def turns_between(a: int, b: int) -> int:
    """90° rotations (RotateLeft/RotateRight) needed to turn from heading ``a`` to ``b``."""
    d = (b - a) % 4
    return min(d, 4 - d)


@dataclass(frozen=True)
class NavGrid:
    """The reachable cells of one floor plan and ALFRED's openable poses
    (``thor_id -> (x, z, rotation_y)``)."""

    floor_plan: str
    cells: frozenset[Cell]
    openable: dict[str, tuple[float, float, int]] = field(hash=False, compare=False)
    #: reachable cells left out because they are cut off from the main floor (islands of
    #: AI2-THOR 2.1's grid behind furniture): a robot there could never leave
    dropped: int = 0
    #: cells added for AI2-THOR 5.x objects the 2.1 grid does not reach, with why
    #: (``data/nav/added_cells.json``, derived by ``scripts/build_added_cells.py``)
    added: dict[Cell, str] = field(default_factory=dict, hash=False, compare=False)
    _sorted: tuple[Cell, ...] = field(init=False, hash=False, compare=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_sorted", tuple(sorted(self.cells)))

    @property
    def ordered(self) -> tuple[Cell, ...]:
        """The cells in a fixed order (for deterministic tie-breaking)."""
        return self._sorted

    @staticmethod
    def point(cell: Cell) -> tuple[float, float]:
        """Floor point (x, z) of a cell's centre, metres."""
        return (round(cell[0] * GRID, 3), round(cell[1] * GRID, 3))

    def cell_at(self, point: tuple[float, float]) -> Cell | None:
        """The cell whose centre is exactly ``point`` (within a millimetre), if reachable."""
        i, j = round(point[0] / GRID), round(point[1] / GRID)
        if abs(point[0] - i * GRID) < 1e-3 and abs(point[1] - j * GRID) < 1e-3 and (i, j) in self.cells:
            return (i, j)
        return None

    def nearest(self, point: tuple[float, float]) -> Cell:
        """The reachable cell nearest ``point`` (ties: the smaller cell)."""
        exact = self.cell_at(point)
        if exact is not None:
            return exact
        x, z = point
        return min(self._sorted, key=lambda c: (math.hypot(c[0] * GRID - x, c[1] * GRID - z), c))

    def neighbours(self, cell: Cell) -> list[Cell]:
        """Reachable 4-neighbours (one MoveAhead away in some heading)."""
        return [n for di, dj in STEPS if (n := (cell[0] + di, cell[1] + dj)) in self.cells]


@cache
def load_base_grid(floor_plan: str) -> NavGrid:
    """ALFRED's grid of ``floor_plan`` as it is (AI2-THOR 2.1), its largest piece; cached."""
    try:
        blob = resources.files("emboteam.world.data").joinpath(f"nav/{floor_plan}.json.gz").read_bytes()
    except FileNotFoundError:
        raise UnknownSceneError(f"no navigation grid for {floor_plan!r}") from None
    raw = json.loads(gzip.decompress(blob))
    cells = {(int(i), int(j)) for i, j in raw["cells"]}
    main = largest_component(cells)
    openable = {k: (float(v[0]), float(v[1]), int(v[2])) for k, v in raw["openable"].items()}
    return NavGrid(floor_plan, frozenset(main), openable, dropped=len(cells) - len(main))


@cache
def added_cells() -> dict[str, dict[Cell, str]]:
    """Floor plan -> cells added for AI2-THOR 5.x objects -> why (see :class:`NavGrid`)."""
    raw = json.loads(resources.files("emboteam.world.data").joinpath("nav/added_cells.json").read_text())
    return {fp: {(int(c["cell"][0]), int(c["cell"][1])): str(c["reason"]) for c in cells}
            for fp, cells in raw["scenes"].items()}


@cache
def load_grid(floor_plan: str) -> NavGrid:
    """The navigation grid of ``floor_plan`` (``FloorPlan6``): ALFRED's, plus the cells added
    for AI2-THOR 5.x (each joins the grid beside a kept cell or another added one); cached."""
    base = load_base_grid(floor_plan)
    added = {c: why for c, why in added_cells().get(floor_plan, {}).items() if c not in base.cells}
    if not added:
        return base
    cells = largest_component(set(base.cells) | set(added))
    return NavGrid(floor_plan, frozenset(cells), base.openable, dropped=base.dropped,
                   added={c: why for c, why in added.items() if c in cells})


def largest_component(cells: set[Cell]) -> set[Cell]:
    """The largest 4-connected set of cells (ties: the one with the smallest cell)."""
    seen: set[Cell] = set()
    best: set[Cell] = set()
    for c in sorted(cells):
        if c in seen:
            continue
        comp = {c}
        stack = [c]
        while stack:
            i, j = stack.pop()
            for di, dj in STEPS:
                n = (i + di, j + dj)
                if n in cells and n not in comp:
                    comp.add(n)
                    stack.append(n)
        seen |= comp
        if len(comp) > len(best):
            best = comp
    return best
