"""The object catalogue: AI2-THOR object types, their property flags, masses and the
placement rules that say which type may go in or on which receptacle.

Built once from package data (converted from AI2-THOR 5.x metadata by
``scripts/build_world_data.py``) and cached; it is immutable.
"""

from __future__ import annotations

import json
from functools import cache
from importlib import resources
from typing import Literal

from pydantic import BaseModel, ConfigDict

from emboteam.errors import UnknownObjectError

Property = Literal[
    "pickupable", "receptacle", "openable", "toggleable", "sliceable", "cookable",
    "breakable", "dirtyable", "canFillWithLiquid", "canBeUsedUp", "isHeatSource",
    "isColdSource", "moveable",
]

#: Knife types that satisfy the slicing rule (ALFRED / rl_thor): to slice, hold one.
KNIVES: frozenset[str] = frozenset({"Knife", "ButterKnife"})

# The appliances: the only lists of them (sim/physics.py applies their effects,
# sim/capability.py says what it takes to use them, docs/architecture.md).

#: Receptacles that heat (and cook) everything in or on them, transitively, while switched
#: on (a StoveBurner is "on" when its StoveKnob is).
HEATERS: frozenset[str] = frozenset({"Microwave", "StoveBurner", "Toaster"})

#: The heaters a StoveKnob switches (they burn while any of their knobs is on).
BURNERS: frozenset[str] = frozenset({"StoveBurner"})

#: Appliances that brew: an empty Mug in a running CoffeeMachine fills with coffee and
#: turns Hot (its direct contents only; only Mugs fit, see the receptacle whitelist).
BREWERS: frozenset[str] = frozenset({"CoffeeMachine"})

#: Receptacles that keep what is in them Cold, if the instance has ``isColdSource``.
COLD_SOURCES: frozenset[str] = frozenset({"Fridge"})

#: Objects whose running water reaches the basins they control (cleans, fills).
WATER_SOURCES: frozenset[str] = frozenset({"Faucet", "ShowerHead"})

#: Appliances whose door and power interlock (AI2-THOR's object table: "Microwaves cannot
#: be turned on if they are open, and cannot be opened if they are currently on").
INTERLOCKED: frozenset[str] = frozenset({"Microwave"})

#: Receptacles a robot works at as one spot (contention: one robot at a time), besides
#: openable receptacles: the appliances and the sink basin.
SPOT_RECEPTACLES: frozenset[str] = HEATERS | BREWERS | frozenset({"SinkBasin"})

#: "In the sink" means in its basin: AI2-THOR puts objects in the SinkBasin (the Sink
#: itself is often not a receptacle). Goal references to the left mean either.
SAME_PLACE: dict[str, frozenset[str]] = {
    "Sink": frozenset({"Sink", "SinkBasin"}),
    "SinkBasin": frozenset({"Sink", "SinkBasin"}),
    "Bathtub": frozenset({"Bathtub", "BathtubBasin"}),
    "BathtubBasin": frozenset({"Bathtub", "BathtubBasin"}),
}


def place_types(types: tuple[str, ...]) -> frozenset[str]:
    """Receptacle types a goal's receptacle reference stands for (Sink -> Sink, SinkBasin)."""
    out: set[str] = set()
    for t in types:
        out |= SAME_PLACE.get(t, frozenset({t}))
    return frozenset(out)


class ObjectType(BaseModel):
    """One AI2-THOR object type: the union of its instances' property flags, its median mass."""

    model_config = ConfigDict(frozen=True)

    name: str
    properties: frozenset[str]
    mass: float
    rooms: tuple[str, ...] = ()

    def has(self, prop: str) -> bool:
        return prop in self.properties


class Catalogue(BaseModel):
    """All object types plus the placement rules of AI2-THOR's SimObjType.cs."""

    model_config = ConfigDict(frozen=True)

    types: dict[str, ObjectType]
    #: object type -> receptacle types it may be placed in/on (types absent: anywhere)
    placement: dict[str, frozenset[str]]
    #: receptacles that must be open before something is put in them
    must_be_open: frozenset[str]
    #: receptacles things go *in* (the rest are surfaces things go *on*)
    in_receptacles: frozenset[str]
    #: receptacles that accept only the listed types (CoffeeMachine takes Mug, ...)
    receptacle_whitelist: dict[str, frozenset[str]]
    #: sliceable type -> (piece type, number of pieces)
    slice_products: dict[str, tuple[str, int]]
    #: piece type -> the first whole that is cut into it (:meth:`source_type`, asked for
    #: every type of every condition the reader checks: a look-up, not a scan); a slot, as
    #: a pydantic private attribute is read through its slow ``__getattr__``
    __slots__ = ("_sources",)

    def type(self, name: str) -> ObjectType:
        try:
            return self.types[name]
        except KeyError:
            raise UnknownObjectError(f"unknown object type {name!r}") from None

    def can_place(self, obj_type: str, receptacle_type: str) -> bool:
        """May an object of ``obj_type`` be put in/on a ``receptacle_type``?

        A receptacle with a whitelist (CoffeeMachine, Toaster, StoveBurner, the holders)
        decides alone: it takes exactly the listed types. Otherwise the object's placement
        restriction decides; a type without a restriction goes anywhere (AI2-THOR's rule).
        """
        white = self.receptacle_whitelist.get(receptacle_type)
        if white is not None:
            return obj_type in white
        allowed = self.placement.get(obj_type)
        return allowed is None or receptacle_type in allowed

    def slice_product(self, whole_type: str) -> tuple[str, int] | None:
        return self.slice_products.get(whole_type)

    def source_type(self, piece_type: str) -> str | None:
        """The whole a piece type comes from (``AppleSliced`` -> ``Apple``)."""
        try:
            sources: dict[str, str] = self._sources    # type: ignore[attr-defined]
        except AttributeError:      # the first time (or a copy)
            sources = {}
            for whole, (piece, _) in self.slice_products.items():
                sources.setdefault(piece, whole)
            object.__setattr__(self, "_sources", sources)
        return sources.get(piece_type)


@cache
def load_catalogue() -> Catalogue:
    """The catalogue shipped with the package (cached: it never changes at run time)."""
    raw = json.loads(resources.files("emboteam.world.data").joinpath("catalogue.json").read_text())
    return Catalogue(
        types={
            name: ObjectType(name=name, properties=frozenset(t["properties"]), mass=t["mass"],
                             rooms=tuple(t["rooms"]))
            for name, t in raw["types"].items()
        },
        placement={k: frozenset(v) for k, v in raw["placement"].items()},
        must_be_open=frozenset(raw["must_be_open"]),
        in_receptacles=frozenset(raw["in_receptacles"]),
        receptacle_whitelist={k: frozenset(v) for k, v in raw["receptacle_whitelist"].items()},
        slice_products={k: (v[0], int(v[1])) for k, v in raw["slice_products"].items()},
    )
