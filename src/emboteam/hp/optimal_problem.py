"""The scheduling problem a plan poses, as :mod:`emboteam.hp.optimal` models it: the
jobs (blocks of one robot's steps between two moments its hands are empty), their
operations, who may take each group, and the orders between operations. Its own module
so that the model (:mod:`.optimal`) and its route relaxation (:mod:`.optimal_bound`) share
it without importing each other."""

from __future__ import annotations

from dataclasses import dataclass, field

from emboteam.world.actions import Skill
from emboteam.world.robots import RobotProfile

Point = tuple[float, float]


@dataclass
class Op:
    """One manipulation step of a job: where it happens, the spot it holds, its seconds."""

    step: str
    place: Point
    spot: str
    seconds: float
    #: a drive precedes it within the job (else the robot is already there)
    drive: bool
    #: where a drive to it goes: the point of the thing it acts on, as the plan's drive
    #: went there (its holder's position if held); where the robot stands, with no drive
    goal: Point = (0.0, 0.0)


@dataclass
class Job:
    """A block of one robot's steps between two moments its hands are empty (ids in
    order), its operations; ``group``: the jobs that move together (those serving the
    same subtask with the same robot), and the robots that may take them."""

    id: str
    robot: str
    group: str
    steps: list[str] = field(default_factory=list)
    ops: list[Op] = field(default_factory=list)
    subtasks: set[str] = field(default_factory=set)
    skills: set[Skill] = field(default_factory=set)
    lift: float = 0.0


@dataclass
class Problem:
    """The scheduling problem a plan poses (its jobs, who may take each group, the robots'
    starts and profiles, the precedences between operations)."""

    jobs: list[Job]
    candidates: dict[str, tuple[str, ...]]
    starts: dict[str, Point]
    profiles: dict[str, RobotProfile]
    #: (producer op step id, consumer op step id)
    precedences: list[tuple[str, str]] = field(default_factory=list)
    #: (producer op, consumer op) where the consumer's *drive* waits for the producer (the
    #: object it drives to arrives there then): the drive starts after the producer ends
    drive_waits: list[tuple[str, str]] = field(default_factory=list)
    #: object -> (first op, last op) spans during which one robot has it: from its pickup
    #: to its release (one op when it is only acted on); one robot at a time per object
    objects: dict[str, list[tuple[str, str]]] = field(default_factory=dict)
    #: the scene, for :func:`travel`
    floor_plan: str = ""
    #: operations on a carried receptacle kept between the carries the plan put them
    #: between (:mod:`emboteam.hp.optimal_carry`): (before, after) as :attr:`precedences`,
    #: and as :attr:`drive_waits` where the later one drives to the box. Apart from the
    #: plan's own waits because they hold only at the model's fixed places: the route
    #: stage, which plans the drives again, does not take them
    carry_orders: list[tuple[str, str]] = field(default_factory=list)
    carry_waits: list[tuple[str, str]] = field(default_factory=list)

    def orders(self) -> list[tuple[str, str]]:
        """Every (producer, consumer) the model orders: the plan's waits and drive waits,
        and the carries' orders."""
        return [*self.precedences, *self.drive_waits, *self.carry_orders, *self.carry_waits]


__all__ = ["Job", "Op", "Point", "Problem"]
