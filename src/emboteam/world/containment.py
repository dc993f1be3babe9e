"""Which receptacle an object is in: one parent per object from AI2-THOR's
``parentReceptacles``.

AI2-THOR lists *every* receptacle whose trigger box overlaps an object, in no useful order,
with physics artefacts (a CounterTop "in" a Bowl, a DiningTable "in" its Chairs, a Floor
"in" a GarbageCan). :func:`resolve_parents` keeps one immediate receptacle per object. The
scene data (scripts/build_world_data.py) and the live AI2-THOR adapter
(:mod:`emboteam.thor.convert`) both use it, so a live episode reads containment exactly as
the scenes were built. Records are dicts with AI2-THOR's ``objectId``, ``objectType``,
``parentReceptacles`` and ``position`` plus ``props``: the names of the object's true
property flags (``pickupable``, ``moveable``, ``receptacle``...).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from emboteam.errors import EmboTeamError


class ContainmentCycleError(EmboTeamError):
    """Resolved parents that form a cycle (never seen in AI2-THOR's data: a guard)."""

#: Seats: their trigger boxes reach up around a table they are tucked under, so an object
#: on the table is also "in" the chair. A seat loses to any other surface.
SEATS = frozenset({"Chair", "Stool", "ArmChair", "Sofa", "Ottoman", "Footstool"})

#: Moveable furniture that stands on the floor: its trigger-box overlaps with neighbouring
#: furniture (a desk "in" the chair pushed under it) are artefacts.
FLOOR_STANDING = SEATS | frozenset({
    "Bed", "CoffeeTable", "Desk", "DiningTable", "DogBed", "Dresser", "FloorLamp", "GarbageBag",
    "GarbageCan", "LaundryHamper", "RoomDecor", "Safe", "ShelvingUnit", "SideTable", "TVStand",
    "VacuumCleaner",
})


#: Basin-like receptacles running water fills; a Sink/Bathtub without a basin object
#: (a few bathrooms) stands in for its own basin.
WATER_BASINS = ("SinkBasin", "BathtubBasin")


def horizontal_distance(a: Mapping[str, float], b: Mapping[str, float]) -> float:
    return math.hypot(a["x"] - b["x"], a["z"] - b["z"])


def _kind(o: Mapping[str, Any]) -> str:
    if "pickupable" in o["props"]:
        return "pickupable"
    return "moveable" if "moveable" in o["props"] else "fixture"


def resolve_parents(objs: Sequence[Mapping[str, Any]]) -> dict[str, str | None]:
    """One immediate receptacle per object (AI2-THOR objectId -> objectId or None).

    - fixtures (neither pickupable nor moveable: counters, cabinets, sinks, the floor)
      have no parent, except a SinkBasin/BathtubBasin, which is part of the Sink/Bathtub
      its id is prefixed with (AI2-THOR's ``UseParentObjectIDasPrefix``);
    - moveable furniture (:data:`FLOOR_STANDING`) stands on the Floor when it is a
      candidate; other moveable objects (appliances, lamps, a television) rest on the
      non-pickupable candidate chosen as below (a toaster on a counter top);
    - pickupable objects: drop candidates that contain another candidate (the counter
      under the plate the tomato is on), then prefer anything over a seat, and a seat over
      the Floor; remaining ties (a pan across two burners) go to the horizontally nearest.
    """
    by_id = {o["objectId"]: o for o in objs}
    parents: dict[str, str | None] = {}
    resolving: set[str] = set()

    def ancestors(oid: str) -> set[str]:
        out: set[str] = set()
        cur = resolve(oid)
        while cur is not None and cur not in out:
            out.add(cur)
            cur = resolve(cur)
        return out

    def resolve(oid: str) -> str | None:
        if oid in parents:
            return parents[oid]
        o = by_id[oid]
        if oid in resolving:  # a containment cycle in the dump: this link is an artefact
            return None
        resolving.add(oid)
        kind = _kind(o)
        cands = [p for p in dict.fromkeys(o["parentReceptacles"] or []) if p != oid]
        choice: str | None = None
        if kind == "fixture":
            outer = oid.rsplit("|", 1)[0]
            if o["objectType"] in WATER_BASINS and outer != oid and outer in by_id:
                choice = outer
        elif (kind == "moveable" and o["objectType"] in FLOOR_STANDING
              and any(by_id[p]["objectType"] == "Floor" for p in cands)):
            choice = next(p for p in cands if by_id[p]["objectType"] == "Floor")
        else:
            if kind == "moveable":
                cands = [p for p in cands if _kind(by_id[p]) != "pickupable"]
            anc = {p: ancestors(p) for p in cands}
            inner = [p for p in cands if not any(p in anc[q] for q in cands if q != p)]
            cands = inner or cands
            if cands:
                def rank(p: str) -> tuple[int, float, str]:
                    t = by_id[p]["objectType"]
                    cls = 2 if t == "Floor" else 1 if t in SEATS else 0
                    return (cls, horizontal_distance(by_id[p]["position"], o["position"]), p)
                choice = min(cands, key=rank)
        resolving.discard(oid)
        parents[oid] = choice
        return choice

    for o in objs:
        resolve(o["objectId"])
    for oid in parents:  # the result must be a forest
        seen = {oid}
        cur = parents[oid]
        while cur is not None:
            if cur in seen:
                raise ContainmentCycleError(f"containment cycle through {oid}")
            seen.add(cur)
            cur = parents[cur]
    return parents
