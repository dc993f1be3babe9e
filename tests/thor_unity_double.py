"""Test support for the AI2-THOR adapter, without an AI2-THOR build.

- :func:`metadata_objects` turns the real AI2-THOR 5.x metadata dumps in
  ../shared/data/ai2thor/scene_inventories.json (``event.metadata["objects"]`` condensed:
  true property flags listed in ``props``, non-default state in ``state``) back into the
  full per-object dicts AI2-THOR sends: every flag as a boolean, every state field.
- :class:`UnityDouble` stands in for the Unity process behind ``Controller.step``: it
  records every action dict and answers with real ``ai2thor.server.Event`` /
  ``MultiAgentEvent`` objects built from those metadata dicts, applying the plain
  bookkeeping effect of each action (a pickup fills the inventory, a teleport moves the
  agent, the fridge chills what is put in it). Its only physics is the agent's:
  ``MoveAhead`` goes ``moveMagnitude`` along the agent's yaw and is refused, as AI2-THOR
  refuses it, when it would leave the reachable positions (by default the floor plan's
  navigation grid, which models AI2-THOR's) or come within one grid cell of another agent;
  ``RotateLeft/Right`` and ``LookUp/Down`` turn by ``degrees``. Teleports go wherever they
  are told, placement never fails unless a failure is scripted with
  :meth:`UnityDouble.fail_next`.
"""

from __future__ import annotations

import copy
import json
import math
from functools import cache
from typing import Any

import pytest

from emboteam.world.scene import scene_ids
from shared_data import AI2THOR

INVENTORIES = AI2THOR / "scene_inventories.json"

FLAGS = ("pickupable", "receptacle", "openable", "toggleable", "sliceable", "cookable", "breakable",
         "dirtyable", "canFillWithLiquid", "canBeUsedUp", "isHeatSource", "isColdSource", "moveable")
#: the agent's position height in iTHOR scenes (m)
AGENT_Y = 0.9009992


@cache
def _dumps() -> dict[str, list[dict[str, Any]]]:
    if not INVENTORIES.exists():
        pytest.skip(f"the AI2-THOR metadata dumps are not at {INVENTORIES}")
    data: dict[str, list[dict[str, Any]]] = json.loads(INVENTORIES.read_text())
    return data


def floor_plans() -> list[str]:
    """The 120 iTHOR floor plans, from the package's own scene data: this runs at collection
    time, where a missing dump must not skip the whole module (each test skips on use)."""
    return sorted(scene_ids(), key=lambda fp: int(fp.removeprefix("FloorPlan")))


def metadata_objects(floor_plan: str) -> list[dict[str, Any]]:
    """``event.metadata["objects"]`` of a freshly loaded floor plan, from the real dump."""
    out = []
    for d in _dumps()[floor_plan]:
        st = d["state"]
        o: dict[str, Any] = {
            "objectId": d["objectId"], "objectType": d["objectType"], "assetId": d["assetId"],
            "name": d["objectId"].split("|")[0], "position": dict(d["position"]),
            "rotation": {"x": 0.0, "y": 0.0, "z": 0.0}, "visible": False, "isInteractable": False,
            **{flag: flag in d["props"] for flag in FLAGS},
            "isOpen": bool(st.get("isOpen", False)), "openness": float(st.get("openness", 0.0)),
            "isToggled": bool(st.get("isToggled", False)), "isBroken": False,
            "isFilledWithLiquid": bool(st.get("isFilledWithLiquid", False)),
            # the dump keeps the flag, not the liquid: AI2-THOR fills WineBottles with wine
            "fillLiquid": ("wine" if d["objectType"] == "WineBottle" else "water")
            if st.get("isFilledWithLiquid") else None,
            "isDirty": bool(st.get("isDirty", False)), "isUsedUp": False, "isCooked": False,
            "temperature": st.get("temperature", "RoomTemp"), "isSliced": False, "isPickedUp": False,
            "isMoving": False, "mass": d["mass"], "salientMaterials": d["salientMaterials"],
            "receptacleObjectIds": d["receptacleObjectIds"], "distance": 0.0,
            "parentReceptacles": list(d["parentReceptacles"]) if d["parentReceptacles"] else None,
            "controlledObjects": None,
        }
        out.append(o)
    return out


def agent_metadata(objects: list[dict[str, Any]], position: dict[str, float], agent_id: int) -> dict[str, Any]:
    """One agent's ``event.metadata`` (the keys ``ai2thor.server.Event`` and our adapter read)."""
    return {
        "objects": objects, "agent": {"name": f"agent{agent_id}", "position": dict(position),
                                      "rotation": {"x": 0.0, "y": 0.0, "z": 0.0}, "cameraHorizon": 0.0,
                                      "isStanding": True},
        "inventoryObjects": [], "sceneName": "", "lastAction": "", "lastActionSuccess": True,
        "errorMessage": "", "errorCode": "", "actionReturn": None, "screenWidth": 300, "screenHeight": 300,
        "agentId": agent_id, "thirdPartyCameras": [], "colors": [], "sequenceId": 0,
    }


class UnityDouble:
    """Records ``Controller.step`` calls and answers with real ai2thor events (see module doc)."""

    def __init__(self, floor_plan: str, agent_count: int = 1, *, reachable: list[dict[str, float]] | None = None,
                 starts: list[tuple[float, float]] | None = None) -> None:
        from emboteam.world.navgrid import NavGrid, load_grid
        from emboteam.world.scene import load_scene

        scene = load_scene(floor_plan)
        self.floor_plan = floor_plan
        self.objects = metadata_objects(floor_plan)
        cells = [NavGrid.point(c) for c in load_grid(floor_plan).ordered]
        self.reachable = reachable if reachable is not None else [{"x": x, "y": AGENT_Y, "z": z} for x, z in cells]
        starts = starts or [scene.robot_start(i) for i in range(agent_count)]
        self.agents = [agent_metadata(self.objects, {"x": x, "y": AGENT_Y, "z": z}, i)
                       for i, (x, z) in enumerate(starts)]
        self.calls: list[dict[str, Any]] = []
        #: each agent's pose after every MoveAhead / Rotate it carried out
        self.poses: list[dict[str, Any]] = []
        self._failures: dict[str, str] = {}
        self.stopped = False
        self.last_event = self._event(0)

    # ---- scripting -------------------------------------------------------------------
    def fail_next(self, action: str, message: str) -> None:
        """The next ``action`` fails with AI2-THOR's ``message``."""
        self._failures[action] = message

    def by_action(self, name: str) -> list[dict[str, Any]]:
        return [c for c in self.calls if c["action"] == name]

    def obj(self, object_id: str) -> dict[str, Any]:
        return next(o for o in self.objects if o["objectId"] == object_id)

    # ---- Controller ------------------------------------------------------------------
    def stop(self) -> None:
        self.stopped = True

    def reset(self, scene: str, **init: Any) -> Any:
        self.__init__(scene, int(init.get("agentCount", len(self.agents))))  # type: ignore[misc]
        return self.last_event

    def step(self, action: Any = None, **args: Any) -> Any:
        call = dict(action) if isinstance(action, dict) else dict(action=action)
        call.update(args)
        self.calls.append(copy.deepcopy(call))
        agent_id = int(call.get("agentId", 0))
        meta = self.agents[agent_id]
        meta.update(lastAction=call["action"], lastActionSuccess=True, errorMessage="", actionReturn=None)
        message = self._failures.pop(call["action"], None)
        if message is None:
            message = self._apply(call, meta)
        if message:
            meta.update(lastActionSuccess=False, errorMessage=message)
        self.last_event = self._event(agent_id)
        return self.last_event

    def _event(self, active: int) -> Any:
        from ai2thor.server import Event, MultiAgentEvent

        events = [Event(m) for m in self.agents]
        return events[0] if len(events) == 1 else MultiAgentEvent(active, events)

    # ---- effects ---------------------------------------------------------------------
    def _move(self, name: str, call: dict[str, Any], meta: dict[str, Any]) -> str:
        agent = meta["agent"]
        if name in ("LookUp", "LookDown"):
            sign = 1.0 if name == "LookDown" else -1.0
            agent["cameraHorizon"] = round(agent["cameraHorizon"] + sign * float(call.get("degrees", 30)), 3)
            return ""
        if name != "MoveAhead":
            sign = 1.0 if name == "RotateRight" else -1.0
            yaw = (agent["rotation"]["y"] + sign * float(call.get("degrees", 90))) % 360.0
            agent["rotation"] = {"x": 0.0, "y": round(yaw, 3), "z": 0.0}
            self._moved(call, agent)
            return ""
        yaw = math.radians(agent["rotation"]["y"])
        step = float(call.get("moveMagnitude", 0.25))
        pos = agent["position"]
        x, z = round(pos["x"] + step * math.sin(yaw), 3), round(pos["z"] + step * math.cos(yaw), 3)
        me = int(call.get("agentId", 0))
        if not any(math.hypot(p["x"] - x, p["z"] - z) < 0.01 for p in self.reachable):
            return f"Wall is blocking Agent {me} from moving 0"
        for other in self.agents:
            o = other["agent"]["position"]
            if other is not meta and math.hypot(o["x"] - x, o["z"] - z) < 0.2:
                return f"{other['agent']['name']} is blocking Agent {me} from moving 0"
        agent["position"] = {"x": x, "y": pos["y"], "z": z}
        self._moved(call, agent)
        return ""

    def _moved(self, call: dict[str, Any], agent: dict[str, Any]) -> None:
        self.poses.append({"agentId": int(call.get("agentId", 0)), "x": agent["position"]["x"],
                           "z": agent["position"]["z"], "yaw": agent["rotation"]["y"]})

    def _apply(self, call: dict[str, Any], meta: dict[str, Any]) -> str:
        name = call["action"]
        inv = meta["inventoryObjects"]
        target = self.obj(call["objectId"]) if "objectId" in call else None
        if name == "GetReachablePositions":
            meta["actionReturn"] = copy.deepcopy(self.reachable)
        elif name == "GetShortestPathToPoint":
            meta["actionReturn"] = {"corners": [dict(call["position"]), dict(call["target"])]}
        elif name == "Teleport":
            meta["agent"]["position"] = dict(call["position"])
            meta["agent"]["rotation"] = dict(call["rotation"])
            meta["agent"]["cameraHorizon"] = call["horizon"]
        elif name in ("MoveAhead", "RotateLeft", "RotateRight", "LookUp", "LookDown"):
            return self._move(name, call, meta)
        elif name == "PickupObject":
            assert target is not None
            if inv:
                return "Agent hand has something in it already! Can't pick up anything else"
            if not target["pickupable"]:
                return f"{target['objectId']} must have the property CanPickup to be picked up."
            inv.append({"objectId": target["objectId"], "objectType": target["objectType"]})
            target.update(isPickedUp=True, parentReceptacles=None)
        elif name in ("PutObject", "DropHandObject"):
            if not inv:
                return "Can't place an object if Agent isn't holding anything"
            held = self.obj(inv.pop()["objectId"])
            where = target or next(o for o in self.objects if o["objectType"] == "Floor")
            held.update(isPickedUp=False, parentReceptacles=[where["objectId"]], position=dict(where["position"]))
            if where["isColdSource"]:  # AI2-THOR's fridge cold zone chills what is put in
                held["temperature"] = "Cold"
        elif name in ("OpenObject", "CloseObject"):
            assert target is not None
            target.update(isOpen=name == "OpenObject", openness=1.0 if name == "OpenObject" else 0.0)
        elif name in ("ToggleObjectOn", "ToggleObjectOff"):
            assert target is not None
            target["isToggled"] = name == "ToggleObjectOn"
        elif name == "SliceObject":
            assert target is not None
            self.objects.remove(target)
            piece = "EggCracked" if target["objectType"] == "Egg" else f"{target['objectType']}Sliced"
            for k in range(1 if piece == "EggCracked" else 7):
                self.objects.append({**copy.deepcopy(target), "objectId": f"{target['objectId']}|{piece}_{k}",
                                     "objectType": piece, "sliceable": False, "isSliced": True,
                                     "pickupable": True})
        elif name == "BreakObject":
            assert target is not None
            target["isBroken"] = True
        elif name in ("CleanObject", "DirtyObject"):
            assert target is not None
            target["isDirty"] = name == "DirtyObject"
        elif name == "FillObjectWithLiquid":
            assert target is not None
            target.update(isFilledWithLiquid=True, fillLiquid=call["fillLiquid"])
        return ""
