"""The symbolic world state: where every object is, what state it is in, and what each
robot holds and stands next to.

Mutable on purpose: the simulator applies thousands of actions per benchmark and the
planner validates merged plans by simulation, so copying is explicit (:meth:`copy`)
and cheap (slotted dataclasses, no validation on the hot path). The typed, validated
view of a scene at rest is :class:`emboteam.world.scene.Scene`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field, fields
from operator import attrgetter

from emboteam.errors import UnknownObjectError
from emboteam.world.catalogue import SPOT_RECEPTACLES, load_catalogue
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene

#: AI2-THOR's default interaction (visibility) distance, metres.
REACH = 1.5


@dataclass(slots=True)
class ObjectState:
    """Dynamic state of one object. ``parent`` and ``held_by`` are never both set."""

    id: str
    type: str
    properties: frozenset[str]
    mass: float
    position: tuple[float, float, float]
    parent: str | None = None
    held_by: str | None = None
    is_open: bool = False
    is_on: bool = False
    is_sliced: bool = False
    is_broken: bool = False
    is_dirty: bool = False
    is_cooked: bool = False
    liquid: str | None = None
    temperature: str = "RoomTemp"
    #: for a slice: the whole object it was cut from
    source: str | None = None
    controls: tuple[str, ...] = ()

    def has(self, prop: str) -> bool:
        return prop in self.properties

    @property
    def gone(self) -> bool:
        """A sliced whole: AI2-THOR deactivates it and its pieces take its place."""
        return self.is_sliced and self.source is None and "sliceable" in self.properties


@dataclass(slots=True)
class RobotState:
    """Dynamic state of one robot of the team."""

    name: str
    profile: RobotProfile
    position: tuple[float, float]
    #: the object whose interaction spot the robot stands at (after GoToObject)
    at: str | None = None
    holding: str | None = None
    down: bool = False


#: every field of a state record, in constructor order (for WorldState.copy)
_OBJECT_FIELDS = attrgetter(*(f.name for f in fields(ObjectState)))
_ROBOT_FIELDS = attrgetter(*(f.name for f in fields(RobotState)))


@dataclass(slots=True)
class WorldState:
    """Objects and robots. Robots are keyed by their team name (``robot5``)."""

    floor_plan: str
    objects: dict[str, ObjectState]
    robots: dict[str, RobotState] = field(default_factory=dict)

    # ---- construction ---------------------------------------------------------------
    @classmethod
    def from_scene(cls, scene: Scene, team: Sequence[RobotProfile] = ()) -> WorldState:
        objects = {
            o.id: ObjectState(
                id=o.id, type=o.type, properties=o.properties, mass=o.mass,
                position=o.position, parent=o.parent, is_open=o.state.is_open,
                is_on=o.state.is_on, is_dirty=o.state.is_dirty, liquid=o.state.liquid,
                temperature=o.state.temperature, controls=o.controls,
            )
            for o in scene.objects
        }
        state = cls(floor_plan=scene.floor_plan, objects=objects)
        for i, profile in enumerate(team):
            state.robots[profile.name] = RobotState(profile.name, profile, scene.robot_start(i))
        return state

    def copy(self, *, share_robots: bool = False) -> WorldState:
        """An independent copy. ``share_robots``: the copy holds the very same
        :class:`RobotState` records, for a caller that calls :meth:`own_robot` before each
        action it applies (an action writes only its own robot's record): the action
        elimination keeps hundreds of states of a 32-robot team, most robots idle."""
        # field-by-field positional copies: dataclasses.replace introspects the fields on
        # every call and is ~5x slower, and planning copies states hundreds of times
        return WorldState(
            floor_plan=self.floor_plan,
            objects={k: ObjectState(*_OBJECT_FIELDS(v)) for k, v in self.objects.items()},
            robots=dict(self.robots) if share_robots else {
                k: RobotState(*_ROBOT_FIELDS(v)) for k, v in self.robots.items()},
        )

    def own_robot(self, name: str) -> None:
        """Give this state its own copy of robot ``name``'s record (see :meth:`copy`)."""
        self.robots[name] = RobotState(*_ROBOT_FIELDS(self.robots[name]))

    # ---- lookups --------------------------------------------------------------------
    def obj(self, object_id: str) -> ObjectState:
        try:
            return self.objects[object_id]
        except KeyError:
            raise UnknownObjectError(f"{self.floor_plan} has no object {object_id!r}") from None

    def robot(self, name: str) -> RobotState:
        return self.robots[name]

    def of_type(self, *types: str) -> Iterator[ObjectState]:
        return (o for o in self.objects.values() if o.type in types and not o.gone)

    def children(self, receptacle: str) -> list[ObjectState]:
        """Objects directly in/on ``receptacle``."""
        return [o for o in self.objects.values() if o.parent == receptacle]

    def ancestors(self, object_id: str) -> list[str]:
        """The chain of receptacles around an object, innermost first."""
        chain: list[str] = []
        parent = self.objects[object_id].parent
        while parent is not None and parent not in chain:
            chain.append(parent)
            parent = self.objects[parent].parent
        return chain

    def is_within(self, object_id: str, receptacle: str) -> bool:
        """In/on ``receptacle`` directly or through containers (an apple on a plate in the
        fridge is in the fridge)."""
        return receptacle in self.ancestors(object_id)

    def descendants(self, receptacle: str) -> list[ObjectState]:
        """Everything in/on ``receptacle``, through nested containers."""
        out: list[ObjectState] = []
        frontier = [receptacle]
        while frontier:
            r = frontier.pop()
            for child in self.children(r):
                out.append(child)
                frontier.append(child.id)
        return out

    def enclosing_closed(self, object_id: str) -> str | None:
        """The innermost closed receptacle hiding the object, if any.

        Only receptacles things go *in* hide them (the catalogue's ``must_be_open``:
        fridge, cabinet, drawer, microwave, box, hamper, safe); a closed Toilet lid does
        not hide what stands on its tank.
        """
        enclosing = load_catalogue().must_be_open
        for r in self.ancestors(object_id):
            rec = self.objects[r]
            if rec.type in enclosing and not rec.is_open:
                return r
        return None

    def holder(self, object_id: str) -> str | None:
        return self.objects[object_id].held_by

    def spot_of(self, object_id: str) -> str:
        """The interaction spot an object is reached from: the outermost openable or
        appliance receptacle around it (the fridge for an apple in the fridge), else the
        object itself. Used for contention: one robot per spot at a time."""
        spot = object_id
        for r in self.ancestors(object_id):
            rec = self.objects[r]
            if (rec.has("openable") and rec.has("receptacle")) or rec.type in SPOT_RECEPTACLES:
                spot = r
        return spot

    def distance(self, robot: str, object_id: str) -> float:
        """Horizontal distance from a robot to an object (held objects: zero)."""
        o = self.objects[object_id]
        if o.held_by == robot:
            return 0.0
        x, z = self.robots[robot].position
        return math.hypot(o.position[0] - x, o.position[2] - z)

    def in_reach(self, robot: str, object_id: str) -> bool:
        return self.distance(robot, object_id) <= REACH

    # ---- mutation helpers used by the simulator --------------------------------------
    def move_object(self, object_id: str, parent: str | None, *, position: tuple[float, float, float]
                    | None = None) -> None:
        """Put an object (and, through ``position``, its contents) somewhere."""
        o = self.objects[object_id]
        o.parent = parent
        o.held_by = None
        if position is None and parent is not None:
            position = self.objects[parent].position
        if position is not None:
            self._relocate(object_id, position)

    def _relocate(self, object_id: str, position: tuple[float, float, float]) -> None:
        self.objects[object_id].position = position
        for child in self.descendants(object_id):
            child.position = position

    def attach_to_robot(self, object_id: str, robot: str) -> None:
        o = self.objects[object_id]
        o.parent = None
        o.held_by = robot
        r = self.robots[robot]
        r.holding = object_id
        self._relocate(object_id, (r.position[0], o.position[1], r.position[1]))

    def invariant_violations(self) -> list[str]:
        """Structural invariants; an empty list means the state is consistent."""
        problems: list[str] = []
        for o in self.objects.values():
            if o.parent is not None and o.held_by is not None:
                problems.append(f"{o.id} is both in {o.parent} and held by {o.held_by}")
            if o.parent is not None and o.parent not in self.objects:
                problems.append(f"{o.id} is in unknown {o.parent}")
            if o.held_by is not None:
                r = self.robots.get(o.held_by)
                if r is None or r.holding != o.id:
                    problems.append(f"{o.id} held by {o.held_by} who does not hold it")
            if o.id in self.ancestors(o.id):
                problems.append(f"{o.id} contains itself")
        held = [r.holding for r in self.robots.values() if r.holding is not None]
        if len(held) != len(set(held)):
            problems.append(f"one object held by two robots: {held}")
        for r in self.robots.values():
            if r.holding is not None and self.objects[r.holding].held_by != r.name:
                problems.append(f"{r.name} holds {r.holding} which is not with it")
        return problems

    def summary(self, ids: Iterable[str] | None = None) -> list[str]:
        """One line per object with its non-default state, for logs and prompts."""
        lines = []
        for o in (self.objects[i] for i in ids) if ids is not None else self.objects.values():
            flags = [f for f, on in (("open", o.is_open), ("on", o.is_on), ("sliced", o.is_sliced),
                                    ("broken", o.is_broken), ("dirty", o.is_dirty),
                                    ("cooked", o.is_cooked)) if on]
            if o.liquid:
                flags.append(f"filled:{o.liquid}")
            if o.temperature != "RoomTemp":
                flags.append(o.temperature.lower())
            where = f"held by {o.held_by}" if o.held_by else (f"in {o.parent}" if o.parent else "")
            lines.append(f"{o.id} ({o.type}) {where} {' '.join(flags)}".rstrip())
        return lines
