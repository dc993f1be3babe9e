"""Scenes: the 120 iTHOR floor plans with readable stable object ids.

Each object keeps its AI2-THOR ``objectId`` (``thor_id``) so an adapter for a real
AI2-THOR controller can translate actions back; everything inside EmboTeam uses the
stable ``Type_N`` ids.
"""

from __future__ import annotations

import gzip
import json
import math
import re
from collections import Counter
from collections.abc import Mapping, Sequence
from functools import cache
from importlib import resources
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, PrivateAttr

from emboteam.errors import UnknownObjectError, UnknownSceneError
from emboteam.world.navgrid import NavGrid, load_grid

Room = Literal["kitchen", "living_room", "bedroom", "bathroom"]
Temperature = Literal["RoomTemp", "Hot", "Cold"]
Liquid = Literal["water", "coffee", "wine"]

_ID = re.compile(r"^[A-Za-z]+_\d+(_Slice_\d+)?$")


def is_object_id(text: str) -> bool:
    """``Apple_1`` and ``Apple_1_Slice_2`` are ids; ``Apple`` is a type."""
    return bool(_ID.match(text))


class InitialState(BaseModel):
    """Non-default state an object starts in (AI2-THOR defaults otherwise)."""

    model_config = ConfigDict(frozen=True)

    is_open: bool = False
    is_on: bool = False
    is_dirty: bool = False
    liquid: Liquid | None = None
    temperature: Temperature = "RoomTemp"


class SceneObject(BaseModel):
    """One object of a floor plan as it is at the start of an episode."""

    model_config = ConfigDict(frozen=True)

    id: str = Field(description="stable readable id, e.g. Apple_1")
    thor_id: str = Field(description="AI2-THOR objectId")
    type: str
    properties: frozenset[str]
    mass: float = Field(ge=0, description="kg")
    position: tuple[float, float, float] = Field(description="AI2-THOR world x, y, z (m)")
    parent: str | None = Field(None, description="id of the receptacle it is in/on")
    state: InitialState = InitialState()
    controls: tuple[str, ...] = Field((), description="objects it switches (knob->burner, faucet->basin)")

    def has(self, prop: str) -> bool:
        return prop in self.properties


class Scene(BaseModel):
    """A floor plan: id, room type and its objects (in id order)."""

    model_config = ConfigDict(frozen=True)

    floor_plan: str
    room: Room
    objects: tuple[SceneObject, ...]
    _index: dict[str, SceneObject] = PrivateAttr(default_factory=dict)
    _starts: list[tuple[float, float]] = PrivateAttr(default_factory=list)
    _type_counts: dict[str, int] = PrivateAttr(default_factory=dict)

    def model_post_init(self, __context: object) -> None:
        self._index = {o.id: o for o in self.objects}

    def get(self, object_id: str) -> SceneObject:
        try:
            return self._index[object_id]
        except KeyError:
            raise UnknownObjectError(f"{self.floor_plan} has no object {object_id!r}") from None

    def has_object(self, object_id: str) -> bool:
        return object_id in self._index

    def of_type(self, *types: str) -> list[SceneObject]:
        return [o for o in self.objects if o.type in types]

    def types(self) -> set[str]:
        # from the counted types (fewer than the objects), inserted one by one in the same
        # order as from the objects (set(dict) would presize the set: another order)
        return {t for t in self.type_counts()}

    def type_counts(self) -> Mapping[str, int]:
        """How many objects of each type (counted once: the scene is frozen; read-only)."""
        # pydantic's store of private attributes read directly: ``self._type_counts`` goes
        # through its slow ``__getattr__``, and this is asked per condition the reader checks
        private = self.__pydantic_private__
        assert private is not None    # (a model with private attributes always has the store)
        counts: dict[str, int] = private["_type_counts"]
        if not counts:
            counts = private["_type_counts"] = dict(Counter(o.type for o in self.objects))
        return counts

    def robot_start(self, index: int) -> tuple[float, float]:
        """Start pose (x, z) of the ``index``-th robot of a team: a cell of the floor
        plan's navigation grid (:mod:`emboteam.world.navgrid`).

        AI2-THOR's agent start positions are not in the metadata dump. Robots start on
        reachable cells that are also clear of objects and inside the room
        (:func:`free_floor_cells`: not next to a counter, not in the empty notch of an
        L-shaped room's bounding box), nearest first to the median object position and
        0.5 m or more apart while such cells remain; then on the other reachable cells,
        so every robot of a team gets its own cell.
        """
        if index < 0:
            raise ValueError(f"robot index must be >= 0, got {index}")
        if not self._starts:
            grid = _grid_cells(self.floor_plan)
            free = free_floor_cells(self)
            roomy = [c for c in grid if c in set(free)] if grid else free
            centre = _median_point(self)
            spaced = _spread(roomy, centre, TEAM_SPACING, strict=True)
            self._starts = _spread(grid or free, centre, TEAM_SPACING, first=spaced)
        starts = self._starts
        if not starts:  # no free cell (never happens in iTHOR): fall back to the centre
            cx, cz = _median_point(self)
            return (round(cx + TEAM_SPACING * index, 3), round(cz, 3))
        return starts[index % len(starts)]


def _grid_cells(floor_plan: str) -> list[tuple[float, float]]:
    try:
        grid = load_grid(floor_plan)
    except UnknownSceneError:
        return []
    return [NavGrid.point(c) for c in grid.ordered]


#: AI2-THOR's navigation grid (m)
GRID = 0.25
#: a start cell keeps this far (m, horizontally) from every object's pivot, so a robot does
#: not start inside a counter, an island or a table
START_CLEARANCE = 0.6
#: a cell is inside the room when objects lie on all four sides of it within this band (m)
ROOM_BAND = 1.0
#: distance between team members' start cells (m)
TEAM_SPACING = 0.5


def _placed(scene: Scene) -> list[tuple[float, float]]:
    """Floor positions (x, z) of the objects that mark out the room: the Floor and objects
    parked at the world origin (a placeholder pivot, e.g. some ShowerGlass) do not."""
    return [(o.position[0], o.position[2]) for o in scene.objects
            if o.type != "Floor" and o.position != (0.0, 0.0, 0.0)]


def _median_point(scene: Scene) -> tuple[float, float]:
    pts = _placed(scene) or [(0.0, 0.0)]
    xs = sorted(p[0] for p in pts)
    zs = sorted(p[1] for p in pts)
    return (xs[len(xs) // 2], zs[len(zs) // 2])


def free_floor_cells(scene: Scene) -> list[tuple[float, float]]:
    """Grid cells (x, z) that are plausibly open floor inside the room.

    Without AI2-THOR's navigation mesh the room is inferred from its objects: a cell is
    free when no object pivot is within :data:`START_CLEARANCE`, and inside the room when
    objects lie on all four sides of it within a :data:`ROOM_BAND` corridor (which rules
    out the empty notch of an L-shaped room's bounding box).
    """
    pts = _placed(scene)
    if not pts:
        return []
    xs = [p[0] for p in pts]
    zs = [p[1] for p in pts]
    x0 = math.floor(min(xs) / GRID) * GRID
    z0 = math.floor(min(zs) / GRID) * GRID
    nx = int((max(xs) - x0) / GRID) + 1
    nz = int((max(zs) - z0) / GRID) + 1
    cells = []
    for i in range(nx + 1):
        x = round(x0 + i * GRID, 3)
        column = [p for p in pts if abs(p[0] - x) <= ROOM_BAND]
        for j in range(nz + 1):
            z = round(z0 + j * GRID, 3)
            if min(math.hypot(px - x, pz - z) for px, pz in pts) < START_CLEARANCE:
                continue
            row = [p for p in pts if abs(p[1] - z) <= ROOM_BAND]
            if (any(p[0] > x for p in row) and any(p[0] < x for p in row)
                    and any(p[1] > z for p in column) and any(p[1] < z for p in column)):
                cells.append((x, z))
    return cells


def _spread(cells: list[tuple[float, float]], centre: tuple[float, float], spacing: float, *,
            strict: bool = False, first: Sequence[tuple[float, float]] = ()) -> list[tuple[float, float]]:
    """Cells nearest ``centre`` first, those ``spacing`` apart from earlier ones (``first``
    included) before the rest (a large team in a small room still gets distinct cells);
    ``strict``: only the spaced ones."""
    ordered = sorted(cells, key=lambda c: (math.hypot(c[0] - centre[0], c[1] - centre[1]), c))
    chosen: list[tuple[float, float]] = list(first)
    for c in ordered:
        if c not in chosen and all(math.hypot(c[0] - d[0], c[1] - d[1]) >= spacing - 1e-9 for d in chosen):
            chosen.append(c)
    if strict:
        return chosen
    taken = set(chosen)
    return chosen + [c for c in ordered if c not in taken]


@cache
def _raw_scenes() -> dict[str, dict[str, object]]:
    data = resources.files("emboteam.world.data").joinpath("scenes.json.gz").read_bytes()
    raw: dict[str, dict[str, object]] = json.loads(gzip.decompress(data))["scenes"]
    return raw


def scene_ids() -> list[str]:
    """All floor plan ids, in numeric order (FloorPlan1 .. FloorPlan430)."""
    return list(_raw_scenes())


def normalize_floor_plan(name: str | int) -> str:
    """Accept ``FloorPlan6``, ``floorplan6``, ``6`` and ``FP6``."""
    text = str(name).strip()
    digits = re.sub(r"^(floorplan|fp)", "", text, flags=re.IGNORECASE)
    if not digits.isdigit():
        raise UnknownSceneError(f"not a floor plan: {name!r} (expected e.g. FloorPlan6)")
    fp = f"FloorPlan{int(digits)}"
    if fp not in _raw_scenes():
        raise UnknownSceneError(f"unknown floor plan {fp!r}: iTHOR has 1-30, 201-230, 301-330, 401-430")
    return fp


@cache
def load_scene(floor_plan: str | int) -> Scene:
    """The scene of one floor plan (cached; scenes are immutable)."""
    fp = normalize_floor_plan(floor_plan)
    return Scene.model_validate(_raw_scenes()[fp])
