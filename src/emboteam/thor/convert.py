"""AI2-THOR ``event.metadata`` -> :class:`WorldState`: objects, parents, states, poses.

The objects list is the same for every agent of a multi-agent event (only visibility
differs), so it is read from the first agent; what each robot holds comes from its own
agent's ``inventoryObjects`` and its pose from its own ``agent`` entry. Containment is
resolved by the rule the scene data was built with (:mod:`emboteam.world.containment`),
so an untouched scene converts to exactly the state :meth:`WorldState.from_scene` gives.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

from emboteam.thor.ids import ThorIds
from emboteam.world.containment import resolve_parents
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import ObjectState, RobotState, WorldState

#: AI2-THOR's boolean property flags, under the names the scene data uses
PROPS: tuple[str, ...] = (
    "pickupable", "receptacle", "openable", "toggleable", "sliceable", "cookable",
    "breakable", "dirtyable", "canFillWithLiquid", "canBeUsedUp", "isHeatSource",
    "isColdSource", "moveable",
)

Metadata = Mapping[str, Any]


@dataclass(frozen=True, slots=True)
class Member:
    """One robot of the team and the AI2-THOR agent that plays it."""

    profile: RobotProfile
    agent_id: int

    @property
    def name(self) -> str:
        return self.profile.name


def props_of(obj: Metadata) -> list[str]:
    return [p for p in PROPS if obj.get(p)]


def containment_records(objects: Sequence[Metadata]) -> list[dict[str, Any]]:
    """The fields :func:`resolve_parents` reads, from metadata objects."""
    return [{"objectId": o["objectId"], "objectType": o["objectType"], "props": props_of(o),
             "parentReceptacles": o.get("parentReceptacles"), "position": o["position"]}
            for o in objects]


def _liquid(obj: Metadata) -> str | None:
    if not obj.get("isFilledWithLiquid"):
        return None
    liquid = obj.get("fillLiquid")
    return str(liquid) if liquid else "water"


def _temperature(obj: Metadata) -> str:
    # AI2-THOR 5.x reports ``temperature``; builds before 3.0 called it ``ObjectTemperature``
    t = obj.get("temperature", obj.get("ObjectTemperature", "RoomTemp"))
    return t if t in ("Hot", "Cold") else "RoomTemp"


def _xyz(p: Mapping[str, float]) -> tuple[float, float, float]:
    return (round(float(p["x"]), 3), round(float(p["y"]), 3), round(float(p["z"]), 3))


def world_state(agents: Sequence[Metadata], scene: Scene, ids: ThorIds, team: Sequence[Member], *,
                previous: WorldState | None = None, down: frozenset[str] = frozenset(),
                at: Mapping[str, str | None] | None = None) -> WorldState:
    """The symbolic state of one AI2-THOR event.

    ``agents``: each agent's metadata, indexed by AI2-THOR agent id. ``previous``: the
    state before, for objects AI2-THOR no longer reports (a sliced whole is deactivated
    when its pieces spawn). ``at``: the object each robot last navigated to.
    """
    objects_meta = list(agents[0]["objects"])
    parents = resolve_parents(containment_records(objects_meta))
    holders: dict[str, str] = {}
    for m in team:
        for inv in agents[m.agent_id].get("inventoryObjects") or ():
            holders[inv["objectId"]] = m.name
    controls = {o.id: o.controls for o in scene.objects}
    objects: dict[str, ObjectState] = {}
    for o in objects_meta:
        oid = ids.ours(o["objectId"])
        if oid is None:
            continue  # spawned by AI2-THOR and unknown to the plan (never a goal object)
        whole = oid.split("_Slice_")[0] if "_Slice_" in oid else None
        props = set(props_of(o))
        parent = parents.get(o["objectId"])
        held_by = holders.get(o["objectId"])
        objects[oid] = ObjectState(
            id=oid, type=o["objectType"],
            properties=frozenset(props | {"pickupable"} if whole else props),
            mass=float(o.get("mass") or 0.0), position=_xyz(o["position"]),
            parent=None if held_by or parent is None else ids.ours(parent), held_by=held_by,
            is_open=bool(o.get("isOpen")), is_on=bool(o.get("isToggled")),
            is_sliced=bool(o.get("isSliced")) or whole is not None, is_broken=bool(o.get("isBroken")),
            is_dirty=bool(o.get("isDirty")), is_cooked=bool(o.get("isCooked")), liquid=_liquid(o),
            temperature=_temperature(o), source=whole, controls=controls.get(oid, ()),
        )
    sliced = {o.source for o in objects.values() if o.source}
    for so in scene.objects:  # deactivated wholes stay, as the symbolic simulator keeps them
        if so.id in objects:
            continue
        if previous is not None and so.id in previous.objects:
            kept = replace(previous.objects[so.id])
        else:
            kept = WorldState.from_scene(scene).objects[so.id]
        kept.is_sliced = kept.is_sliced or so.id in sliced
        kept.held_by = None
        objects[so.id] = kept
    state = WorldState(floor_plan=scene.floor_plan, objects=objects)
    for m in team:
        agent = agents[m.agent_id]["agent"]
        pos = agent["position"]
        holding = next((inv for inv in (agents[m.agent_id].get("inventoryObjects") or ())), None)
        state.robots[m.name] = RobotState(
            name=m.name, profile=m.profile, position=(round(float(pos["x"]), 3), round(float(pos["z"]), 3)),
            at=(at or {}).get(m.name), holding=ids.ours(holding["objectId"]) if holding else None,
            down=m.name in down,
        )
    return state
