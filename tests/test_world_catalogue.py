"""The object catalogue against AI2-THOR's own data: types, flags, masses, placement rules."""

from __future__ import annotations

import statistics
from collections import defaultdict
from typing import Any

import pytest

from emboteam.errors import UnknownObjectError
from emboteam.world.catalogue import KNIVES, Catalogue, place_types

PROPS = ("pickupable", "receptacle", "openable", "toggleable", "sliceable", "cookable", "breakable",
         "dirtyable", "canFillWithLiquid", "canBeUsedUp", "isHeatSource", "isColdSource", "moveable")


def test_every_scene_type_is_catalogued(catalogue: Catalogue,
                                        thor_inventories: dict[str, list[dict[str, Any]]]) -> None:
    seen = {o["objectType"] for objs in thor_inventories.values() for o in objs}
    assert seen <= set(catalogue.types)
    # slice products never appear in a scene at rest but must be known to the planner
    for piece in ("AppleSliced", "BreadSliced", "LettuceSliced", "PotatoSliced", "TomatoSliced",
                  "EggCracked"):
        assert catalogue.type(piece).has("pickupable")


def test_type_flags_are_the_union_over_instances(catalogue: Catalogue,
                                                 thor_inventories: dict[str, list[dict[str, Any]]]) -> None:
    union: dict[str, set[str]] = defaultdict(set)
    for objs in thor_inventories.values():
        for o in objs:
            union[o["objectType"]] |= {p for p in o["props"] if p in PROPS}
    for name, flags in union.items():
        assert set(catalogue.type(name).properties) == flags, name


def test_masses_are_medians_over_instances(catalogue: Catalogue,
                                           thor_inventories: dict[str, list[dict[str, Any]]]) -> None:
    masses: dict[str, list[float]] = defaultdict(list)
    for objs in thor_inventories.values():
        for o in objs:
            if o["mass"]:
                masses[o["objectType"]].append(float(o["mass"]))
    for name, ms in masses.items():
        assert catalogue.type(name).mass == pytest.approx(statistics.median(ms), abs=1e-3), name
    # a slice weighs its share of the whole; a cracked egg weighs the egg
    assert catalogue.type("AppleSliced").mass == pytest.approx(catalogue.type("Apple").mass / 3, abs=1e-3)
    assert catalogue.type("EggCracked").mass == catalogue.type("Egg").mass


def test_known_flags_of_key_types(catalogue: Catalogue) -> None:
    fridge, burner, knob = catalogue.type("Fridge"), catalogue.type("StoveBurner"), catalogue.type("StoveKnob")
    assert fridge.has("openable") and fridge.has("receptacle") and fridge.has("isColdSource")
    # AI2-THOR: burners are switched through their knob, never directly
    assert not burner.has("toggleable") and burner.has("isHeatSource") and knob.has("toggleable")
    assert catalogue.type("Microwave").has("openable") and catalogue.type("Microwave").has("toggleable")
    assert catalogue.type("Potato").has("cookable") and catalogue.type("Potato").has("sliceable")
    assert catalogue.type("Mug").has("canFillWithLiquid") and catalogue.type("Mug").has("dirtyable")
    assert catalogue.type("Egg").has("breakable")
    assert {"Knife", "ButterKnife"} == KNIVES


def test_placement_is_the_simobjtype_transcription(catalogue: Catalogue, thor_restrictions: dict[str, Any]) -> None:
    """The transcription of SimObjType.cs was checked entry by entry against the source
    (docs/world.md); the catalogue must carry it unchanged."""
    raw = thor_restrictions["PlacementRestrictions"]
    for obj_type, allowed in raw.items():
        assert catalogue.placement[obj_type] == frozenset(allowed), obj_type
    # AI2-THOR's MustBeOpenToPlaceObjectsIn plus the Safe (docs/world.md)
    assert set(thor_restrictions["MustBeOpenToPlaceObjectsIn"]) == {
        "Drawer", "Cabinet", "Fridge", "Microwave", "Box", "LaundryHamper"}
    assert catalogue.must_be_open == {"Drawer", "Cabinet", "Fridge", "Microwave", "Box", "LaundryHamper",
                                      "Safe"}
    assert catalogue.in_receptacles == frozenset(thor_restrictions["InReceptacles"])


def test_transcription_only_widens_the_public_web_table(thor_restrictions: dict[str, Any],
                                                        thor_web_table: dict[str, Any]) -> None:
    """Discrepancy documented in docs/world.md: the web table is older and omits newer
    receptacles (Chair, Stool, Floor, ...) and the Mug's CoffeeMachine; it never allows
    something the source forbids."""
    raw = thor_restrictions["PlacementRestrictions"]
    wider = []
    for obj_type, allowed in raw.items():
        if obj_type not in thor_web_table:
            continue
        web = {r for r in thor_web_table[obj_type]["compatible_receptacles"] if r}
        assert web <= set(allowed), obj_type
        if web != set(allowed):
            wider.append(obj_type)
    assert "Mug" in wider and "CoffeeMachine" not in thor_web_table["Mug"]["compatible_receptacles"]


@pytest.mark.parametrize(("obj", "receptacle", "ok"), [
    ("Mug", "CoffeeMachine", True),
    ("Cup", "CoffeeMachine", False),        # "only Mugs were created to fit coffee machines"
    ("BreadSliced", "Toaster", True),
    ("Bread", "Toaster", False),
    ("Apple", "Toaster", False),
    ("Pan", "StoveBurner", True),
    ("Pot", "StoveBurner", True),
    ("Kettle", "StoveBurner", True),
    ("Egg", "StoveBurner", False),          # eggs go in a pan on the burner
    ("Towel", "TowelHolder", True),
    ("HandTowel", "TowelHolder", False),
    ("HandTowel", "HandTowelHolder", True),
    ("ToiletPaper", "ToiletPaperHanger", True),
    ("Apple", "Fridge", True),
    ("Tomato", "Microwave", False),         # SimObjType.cs lists no Microwave for Tomato
    ("Lettuce", "Microwave", False),
    ("Potato", "Microwave", True),
    ("Pan", "Shelf", False),
    ("Book", "Fridge", False),
    ("ScrubBrush", "Bed", True),            # a type without a restriction goes anywhere
])
def test_can_place(catalogue: Catalogue, obj: str, receptacle: str, ok: bool) -> None:
    assert catalogue.can_place(obj, receptacle) is ok


def test_slice_products_and_sources(catalogue: Catalogue) -> None:
    assert catalogue.slice_product("Apple") == ("AppleSliced", 3)
    assert catalogue.slice_product("Egg") == ("EggCracked", 1)
    assert catalogue.slice_product("Mug") is None
    for whole, (piece, n) in catalogue.slice_products.items():
        assert n >= 1 and catalogue.source_type(piece) == whole
        assert catalogue.type(whole).has("sliceable")
    assert catalogue.source_type("Apple") is None


def test_sink_and_basin_are_one_place() -> None:
    assert place_types(("Sink",)) == {"Sink", "SinkBasin"}
    assert place_types(("BathtubBasin",)) == {"Bathtub", "BathtubBasin"}
    assert place_types(("Fridge", "Sink")) == {"Fridge", "Sink", "SinkBasin"}


def test_unknown_type_is_a_typed_error(catalogue: Catalogue) -> None:
    with pytest.raises(UnknownObjectError, match="Banana"):
        catalogue.type("Banana")
