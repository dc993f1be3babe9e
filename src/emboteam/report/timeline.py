"""A trace turned into what the viewer draws: action bars, pose tracks, object moves and
a log of blackboard / simulator / replanning events.

Everything here is computed once in Python, so the page only looks things up by time
(binary search over sorted arrays) and stays responsive on traces of many thousands of
events. The trace format is :mod:`emboteam.exec.trace`; fields the executor may or may
not fill (``step``, ``recovery``, a structured or a string ``action``) are optional.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Sequence
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from emboteam.exec.trace import TraceEvent
from emboteam.world.actions import Action

Outcome = Literal["success", "failed", "unfinished"]
Category = Literal["sync", "lock", "blackboard", "recovery", "sim", "replan"]

_CALL = re.compile(r"^\s*([A-Za-z_]\w*)\s*\((.*)\)\s*$")
#: blackboard key words that mark a resource lock / a synchronisation flag (docs/report.md)
_LOCK_WORDS = ("lock", "resource", "spot", "mutex", "claim")
_SYNC_WORDS = ("sync", "done", "wait", "flag", "signal", "ready", "finished", "barrier")


class ActionBar(BaseModel):
    """One executed action of one robot, from its start to its end event."""

    model_config = ConfigDict(frozen=True)

    robot: str
    start: float
    end: float
    action: str
    skill: str
    args: tuple[str, ...] = ()
    step: str | None = None
    recovery: bool = False
    outcome: Outcome = "success"
    reason: str | None = None
    message: str = ""


class PoseTrack(BaseModel):
    """A robot's sampled positions, columnar (compact JSON, binary-searchable by ``t``)."""

    t: list[float] = Field(default_factory=list)
    x: list[float] = Field(default_factory=list)
    z: list[float] = Field(default_factory=list)
    holding: list[str | None] = Field(default_factory=list)


class ObjectMove(BaseModel):
    """From ``t`` on, an object is held by ``robot``, or lies at (x, z), or is gone."""

    model_config = ConfigDict(frozen=True)

    t: float
    object: str
    robot: str | None = None
    at: str | None = Field(None, description="the receptacle it was put in/on")
    x: float | None = None
    z: float | None = None
    gone: bool = False


class LogEvent(BaseModel):
    model_config = ConfigDict(frozen=True)

    t: float
    category: Category
    robot: str | None
    key: str
    value: str


class NodeChange(BaseModel):
    model_config = ConfigDict(frozen=True)

    t: float
    robot: str | None
    path: tuple[str, ...]
    status: str
    type: str | None = None


class Timeline(BaseModel):
    end: float
    robots: list[str]
    actions: list[ActionBar]
    poses: dict[str, PoseTrack]
    moves: list[ObjectMove]
    events: list[LogEvent]
    nodes: list[NodeChange] = Field(default_factory=list, exclude=True)


def parse_action(raw: object) -> tuple[str, str, tuple[str, ...]]:
    """(text, skill, args) from an ``Action`` dump or its text ``PutObject(Apple_1, Fridge_1)``."""
    if isinstance(raw, dict):
        try:
            a = Action.model_validate(raw)
        except ValidationError:
            return json.dumps(raw, sort_keys=True), "?", ()
        args = (a.target,) if a.receptacle is None else (a.target, a.receptacle)
        return str(a), a.skill.value, args
    text = str(raw) if raw is not None else "?"
    m = _CALL.match(text)
    if m is None:
        return text, text.split()[0] if text.split() else "?", ()
    parts = tuple(a.strip() for a in m.group(2).split(",") if a.strip())
    return text.strip(), m.group(1), parts


def normalize_status(raw: object) -> str:
    """``Status.SUCCESS``, ``SUCCESS`` and ``success`` all become ``success``."""
    return str(raw).rsplit(".", 1)[-1].strip().lower() or "invalid"


def classify_key(key: str) -> Category:
    k = key.lower()
    if any(w in k for w in _LOCK_WORDS):
        return "lock"
    if any(w in k for w in _SYNC_WORDS):
        return "sync"
    return "blackboard"


def _short(value: Any) -> str:
    text = value if isinstance(value, str) else json.dumps(value, ensure_ascii=False, default=str)
    return text if len(text) <= 200 else text[:199] + "…"


def _path(data: dict[str, Any], robot: str | None) -> tuple[str, ...]:
    raw = data.get("path")
    if isinstance(raw, (list, tuple)):
        parts = [str(p) for p in raw if str(p)]
    elif isinstance(raw, str) and raw.strip():
        parts = [p for p in raw.split("/") if p]
    else:
        parts = [p for p in (robot, data.get("node")) if p]
    return tuple(parts) or ("?",)


def _bool(value: object) -> bool:
    return value is True or (isinstance(value, str) and value.lower() in ("true", "1", "yes"))


class _Builder:
    def __init__(self, robots: Sequence[str]) -> None:
        self.robots: list[str] = list(robots)
        self.actions: list[ActionBar] = []
        self.open: dict[str, TraceEvent] = {}
        self.poses: dict[str, PoseTrack] = {r: PoseTrack() for r in robots}
        self.moves: list[ObjectMove] = []
        self.events: list[LogEvent] = []
        self.nodes: list[NodeChange] = []

    def robot(self, name: str | None) -> None:
        if name is not None and name not in self.poses:
            self.robots.append(name)
            self.poses[name] = PoseTrack()

    def start(self, ev: TraceEvent, robot: str) -> None:
        previous = self.open.pop(robot, None)
        if previous is not None:
            self.close(previous, robot, ev.t, None)
        self.open[robot] = ev

    def close(self, start: TraceEvent, robot: str, t: float, end: TraceEvent | None) -> None:
        data = {**start.data, **(end.data if end is not None else {})}
        text, skill, args = parse_action(data.get("action"))
        if end is None:
            outcome: Outcome = "unfinished"
        else:
            outcome = "success" if _bool(data.get("success")) else "failed"
        reason = data.get("reason")
        self.actions.append(ActionBar(
            robot=robot, start=start.t, end=max(t, start.t), action=text, skill=skill, args=args,
            step=str(data["step"]) if data.get("step") is not None else None,
            recovery=_bool(data.get("recovery")), outcome=outcome,
            reason=str(reason) if reason and outcome == "failed" else None,
            message=str(data.get("message") or ""),
        ))

    def end(self, ev: TraceEvent, robot: str) -> None:
        start = self.open.pop(robot, None)
        if start is None:  # an end without a start: the action began before the trace did
            t0 = float(ev.data.get("start", ev.t))
            start = TraceEvent(t=min(t0, ev.t), kind="action_start", robot=robot, data=ev.data)
        self.close(start, robot, ev.t, ev)
        if _bool(ev.data.get("success")):
            self.object_effect(ev, robot)

    def object_effect(self, ev: TraceEvent, robot: str) -> None:
        _, skill, args = parse_action(ev.data.get("action"))
        if not args:
            return
        if skill == "PickupObject":
            self.moves.append(ObjectMove(t=ev.t, object=args[0], robot=robot))
        elif skill == "PutObject" and len(args) > 1:
            self.moves.append(ObjectMove(t=ev.t, object=args[0], at=args[1]))
        elif skill in ("DropHandObject", "ThrowObject"):
            x, z = self.position(robot)
            self.moves.append(ObjectMove(t=ev.t, object=args[0], x=x, z=z, gone=skill == "ThrowObject"))

    def position(self, robot: str) -> tuple[float | None, float | None]:
        track = self.poses.get(robot)
        if track is None or not track.t:
            return None, None
        return track.x[-1], track.z[-1]

    def pose(self, ev: TraceEvent, robot: str) -> None:
        try:
            x, z = float(ev.data["x"]), float(ev.data["z"])
        except (KeyError, TypeError, ValueError):
            return
        track = self.poses[robot]
        holding = ev.data.get("holding")
        track.t.append(ev.t)
        track.x.append(round(x, 3))
        track.z.append(round(z, 3))
        track.holding.append(str(holding) if holding else None)

    def sim(self, ev: TraceEvent) -> None:
        kind = str(ev.data.get("kind", "sim"))
        detail = str(ev.data.get("detail", ""))
        self.events.append(LogEvent(t=ev.t, category="sim", robot=ev.robot, key=kind, value=_short(detail)))
        m = re.match(r"^\s*(\S+)\s*->\s*(\S+)\s*$", detail)
        if kind == "moved" and m:
            self.moves.append(ObjectMove(t=ev.t, object=m.group(1), at=m.group(2)))
        m = re.match(r"^\s*(\S+) dropped (\S+)\s*$", detail)
        if kind == "drop" and m:
            x, z = self.position(m.group(1))
            self.moves.append(ObjectMove(t=ev.t, object=m.group(2), x=x, z=z))

    def add(self, ev: TraceEvent) -> None:
        self.robot(ev.robot)
        robot = ev.robot
        if ev.kind == "action_start" and robot is not None:
            self.start(ev, robot)
        elif ev.kind == "action_end" and robot is not None:
            self.end(ev, robot)
        elif ev.kind == "pose" and robot is not None:
            self.pose(ev, robot)
        elif ev.kind == "blackboard":
            key = str(ev.data.get("key", "?"))
            self.events.append(LogEvent(t=ev.t, category=classify_key(key), robot=robot, key=key,
                                        value=_short(ev.data.get("value"))))
        elif ev.kind == "sim":
            self.sim(ev)
        elif ev.kind == "network":  # a lost lock release, a lock taken over, a flag read late
            key = str(ev.data.get("key", "?"))
            what = str(ev.data.get("what", "network"))
            rest = {k: v for k, v in ev.data.items() if k not in ("what", "key", "plan")}
            self.events.append(LogEvent(t=ev.t, category=classify_key(key), robot=robot,
                                        key=f"{what.replace('_', ' ')}: {key}", value=_short(rest) if rest else ""))
        elif ev.kind == "replan":
            reason = str(ev.data.get("reason", "replan"))
            rest = {k: v for k, v in ev.data.items() if k != "reason"}
            self.events.append(LogEvent(t=ev.t, category="replan", robot=robot, key=reason,
                                        value=_short(rest) if rest else ""))
        elif ev.kind == "recovery":
            strategy = str(ev.data.get("strategy") or "recovery")
            why = str(ev.data.get("why") or ev.data.get("fault") or "")
            step = ev.data.get("step")
            text = (f"{step}: " if step else "") + why + (" (gave up)" if _bool(ev.data.get("gave_up")) else "")
            self.events.append(LogEvent(t=ev.t, category="recovery", robot=robot, key=strategy,
                                        value=_short(text)))
        elif ev.kind == "node":
            t = ev.data.get("type")
            self.nodes.append(NodeChange(t=ev.t, robot=robot, path=_path(ev.data, robot),
                                         status=normalize_status(ev.data.get("status")),
                                         type=str(t) if t else None))


def build_timeline(trace: Iterable[TraceEvent], robots: Sequence[str], makespan: float = 0.0,
                   starts: dict[str, tuple[float, float]] | None = None) -> Timeline:
    """The viewer's timeline of a trace. ``starts`` gives start poses for robots the trace
    never places (an episode that failed before acting still shows its team)."""
    events = sorted(trace, key=lambda e: e.t)  # stable: same-time events keep file order
    b = _Builder(robots)
    for ev in events:
        b.add(ev)
    last = max([e.t for e in events] + [makespan, 0.0])
    for robot, start in list(b.open.items()):
        b.close(start, robot, last, None)
    for robot, (x, z) in (starts or {}).items():
        track = b.poses.get(robot)
        if track is not None and not track.t:
            track.t.append(0.0)
            track.x.append(x)
            track.z.append(z)
            track.holding.append(None)
    b.actions.sort(key=lambda a: (a.start, a.robot))
    end = max([last] + [a.end for a in b.actions])
    return Timeline(end=round(end if end > 0 else 1.0, 4), robots=b.robots, actions=b.actions,
                    poses=b.poses, moves=b.moves, events=b.events, nodes=b.nodes)
