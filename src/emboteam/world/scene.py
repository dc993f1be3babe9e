"""Scenes: the 120 iTHOR floor plans with readable stable object ids.

Each object keeps its AI2-THOR ``objectId`` (``thor_id``) so an adapter for a real
AI2-THOR controller can translate actions back; everything inside EmboTeam uses the
stable ``Type_N`` ids.
"""

from __future__ import annotations

import gzip
import json
import re
from functools import cache
from importlib import resources
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, PrivateAttr

from emboteam.errors import UnknownObjectError, UnknownSceneError

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
        return {o.type for o in self.objects}

    def robot_start(self, index: int) -> tuple[float, float]:
        """Start pose (x, z) of the ``index``-th robot of a team.

        AI2-THOR's agent start positions are not in the metadata dump; robots start in a
        row 0.5 m apart, centred on the middle of the floor plan's object bounding box,
        which is open floor in every iTHOR room.
        """
        xs = [o.position[0] for o in self.objects]
        zs = [o.position[2] for o in self.objects]
        cx, cz = (min(xs) + max(xs)) / 2, (min(zs) + max(zs)) / 2
        return (round(cx + 0.5 * index, 3), round(cz, 3))


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
