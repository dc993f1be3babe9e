"""The top-down map of a floor plan: room outline, furniture footprints, object dots.

The AI2-THOR metadata dump the scenes come from has object centres but no bounding boxes,
so footprints are estimated: a nominal size per furniture type (typical iTHOR asset
dimensions, long side along the nearest wall), grown to cover the objects that start on
or in it (a counter top's footprint spans the things lying on it). The map is for
following robots around, not for measuring: the page says the shapes are approximate.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Literal

from pydantic import BaseModel, ConfigDict

from emboteam.errors import UnknownSceneError
from emboteam.world.navgrid import NavGrid, load_grid
from emboteam.world.scene import Scene, SceneObject

Kind = Literal["furniture", "appliance", "fixture", "item"]

#: nominal footprint (long side, short side) in metres of large non-pickupable types
FOOTPRINT: dict[str, tuple[float, float]] = {
    "ArmChair": (0.85, 0.85), "Bathtub": (1.6, 0.75), "BathtubBasin": (1.4, 0.6), "Bed": (2.0, 1.6),
    "Cabinet": (0.45, 0.4), "Chair": (0.5, 0.5), "CoffeeMachine": (0.3, 0.25), "CoffeeTable": (1.0, 0.55),
    "CounterTop": (0.6, 0.6), "Desk": (1.2, 0.6), "DiningTable": (1.2, 0.8), "DogBed": (0.7, 0.6),
    "Drawer": (0.4, 0.35), "Dresser": (1.0, 0.5), "FloorLamp": (0.35, 0.35), "Fridge": (0.75, 0.75),
    "GarbageCan": (0.3, 0.3), "HandTowelHolder": (0.2, 0.1), "HousePlant": (0.35, 0.35),
    "LaundryHamper": (0.45, 0.45), "Microwave": (0.5, 0.35), "Ottoman": (0.6, 0.6), "Safe": (0.45, 0.45),
    "Shelf": (0.8, 0.3), "ShelvingUnit": (0.9, 0.35), "ShowerDoor": (0.9, 0.1), "SideTable": (0.5, 0.5),
    "Sink": (0.6, 0.45), "SinkBasin": (0.45, 0.35), "Sofa": (2.0, 0.9), "Stool": (0.4, 0.4),
    "StoveBurner": (0.22, 0.22), "TVStand": (1.2, 0.45), "Television": (1.0, 0.15), "Toaster": (0.25, 0.18),
    "Toilet": (0.7, 0.45), "ToiletPaperHanger": (0.15, 0.1), "TowelHolder": (0.5, 0.1),
    "VacuumCleaner": (0.35, 0.35),
}

#: appliances get their own colour: they are where heating, cooling and washing happen
APPLIANCES = frozenset({"Fridge", "Microwave", "StoveBurner", "Toaster", "CoffeeMachine", "Sink",
                        "SinkBasin", "Bathtub", "BathtubBasin", "Television", "Toilet"})

#: margin around everything for the room outline, and around an object's contents, metres
ROOM_MARGIN = 0.35
CONTENT_MARGIN = 0.08


class MapObject(BaseModel):
    model_config = ConfigDict(frozen=True)

    id: str
    type: str
    kind: Kind
    x: float
    z: float
    w: float = 0.0
    d: float = 0.0
    y: float = 0.0
    parent: str | None = None
    highlight: bool = False


class FloorMap(BaseModel):
    """Everything in AI2-THOR world metres: x to the right, z up the page."""

    model_config = ConfigDict(frozen=True)

    floor_plan: str
    room: str
    min_x: float
    max_x: float
    min_z: float
    max_z: float
    objects: tuple[MapObject, ...]
    #: the reachable cells of the navigation grid (x, z), where robots can stand
    cells: tuple[tuple[float, float], ...] = ()


def _kind(o: SceneObject) -> Kind:
    if o.has("pickupable"):
        return "item"
    if o.type in FOOTPRINT:
        return "appliance" if o.type in APPLIANCES else "furniture"
    return "fixture"


def _footprint(o: SceneObject, children: list[SceneObject], bounds: tuple[float, float, float, float]
               ) -> tuple[float, float, float, float]:
    """(centre x, centre z, width along x, depth along z)."""
    long_side, short_side = FOOTPRINT[o.type]
    x, z = o.position[0], o.position[2]
    min_x, max_x, min_z, max_z = bounds
    # the long side runs along the nearest wall: near a left/right wall it runs along z
    near_x_wall = min(x - min_x, max_x - x) < min(z - min_z, max_z - z)
    w, d = (short_side, long_side) if near_x_wall else (long_side, short_side)
    x0, x1, z0, z1 = x - w / 2, x + w / 2, z - d / 2, z + d / 2
    for c in children:
        cx, cz = c.position[0], c.position[2]
        x0, x1 = min(x0, cx - CONTENT_MARGIN), max(x1, cx + CONTENT_MARGIN)
        z0, z1 = min(z0, cz - CONTENT_MARGIN), max(z1, cz + CONTENT_MARGIN)
    x0, x1 = max(x0, min_x), min(x1, max_x)
    z0, z1 = max(z0, min_z), min(z1, max_z)
    return ((x0 + x1) / 2, (z0 + z1) / 2, max(x1 - x0, 0.05), max(z1 - z0, 0.05))


def floor_map(scene: Scene, highlight: Iterable[str] = (),
              extra_points: Iterable[tuple[float, float]] = ()) -> FloorMap:
    """The map of ``scene``; ``highlight`` ids get permanent labels (the objects the plan
    touches); ``extra_points`` (robot poses) are kept inside the drawn room."""
    marked = set(highlight)
    placed = [o for o in scene.objects if o.type != "Floor"]
    xs = [o.position[0] for o in placed] + [p[0] for p in extra_points]
    zs = [o.position[2] for o in placed] + [p[1] for p in extra_points]
    if not xs:
        xs, zs = [0.0], [0.0]
    bounds = (min(xs) - ROOM_MARGIN, max(xs) + ROOM_MARGIN, min(zs) - ROOM_MARGIN, max(zs) + ROOM_MARGIN)
    children: dict[str, list[SceneObject]] = {}
    for o in placed:
        if o.parent is not None:
            children.setdefault(o.parent, []).append(o)
    objects: list[MapObject] = []
    for o in placed:
        kind = _kind(o)
        x, z, w, d = o.position[0], o.position[2], 0.0, 0.0
        if kind in ("furniture", "appliance"):
            x, z, w, d = _footprint(o, children.get(o.id, []), bounds)
        objects.append(MapObject(
            id=o.id, type=o.type, kind=kind, x=round(x, 3), z=round(z, 3), w=round(w, 3), d=round(d, 3),
            y=round(o.position[1], 3), parent=o.parent, highlight=o.id in marked))
    # big shapes first, so smaller ones are drawn over them and stay hoverable
    objects.sort(key=lambda m: (m.kind == "item", -(m.w * m.d), m.id))
    try:
        cells = tuple(NavGrid.point(c) for c in load_grid(scene.floor_plan).ordered)
    except UnknownSceneError:
        cells = ()
    return FloorMap(floor_plan=scene.floor_plan, room=scene.room, min_x=round(bounds[0], 3),
                    max_x=round(bounds[1], 3), min_z=round(bounds[2], 3), max_z=round(bounds[3], 3),
                    objects=tuple(objects), cells=cells)
