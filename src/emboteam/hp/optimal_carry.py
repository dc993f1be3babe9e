"""Operations on a receptacle that robots carry, for :mod:`emboteam.hp.optimal`'s model
(issue 28).

A box is picked up by one robot, carried and put down elsewhere; other robots put things
into it, take things out, open or close it. In the simulator nothing goes into (or out of)
an object another robot holds, and such an operation happens where the box stands at that
moment. The model fixes every operation's place as the plan's replay left it, so an
operation on the box (its target, its receptacle, or what contains either) belongs to the
stretch between two carries in which the plan did it: after the put-down that ended the
carry before it, before the pickup that starts the next one. Without these orders the
model proved FloorPlan201 4 x 8 (goal seed 1) at 16.0 s with the pencil and the book put
into the box while another robot carried it: no real schedule.

The orders are plain precedences (a drive wait when the operation's robot drives to the
box, or to something in it: the box's new place exists only after its put-down), kept in
:attr:`emboteam.hp.optimal_problem.Problem.carry_orders` and ``carry_waits``: the model and its
route relaxation (:mod:`emboteam.hp.optimal_bound`, which stays a relaxation: every
schedule of the model meets them) take them; the route stage, which plans the drives
again (so a put into the box may move to the other side of a carry, at the box's other
place), does not.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from emboteam.world.actions import Action, Skill
from emboteam.world.state import WorldState

#: the skills whose target is the held object, not a thing the robot acts on in place
_RELEASES = frozenset({Skill.PutObject, Skill.ThrowObject, Skill.DropHandObject})


def containers(state: WorldState, thing: str | None) -> set[str]:
    """``thing`` and everything it lies in or on (its parents, transitively): what must
    stand still for an operation on it. Empty for None, an unknown id, or a held object
    (it moves with its robot)."""
    out: set[str] = set()
    while thing is not None and thing in state.objects and thing not in out:
        obj = state.objects[thing]
        if obj.held_by is not None:
            break
        out.add(thing)
        thing = obj.parent
    return out


@dataclass
class CarryLog:
    """Filled while :func:`emboteam.hp.optimal.problem_of` replays a plan: each
    operation's position in the plan, the objects it needs to stand still (:func:`containers`
    of its target and receptacle), those its drive goes to, and each object's carries."""

    order: dict[str, int] = field(default_factory=dict)
    anchors: dict[str, set[str]] = field(default_factory=dict)
    drive_anchors: dict[str, set[str]] = field(default_factory=dict)
    #: robot -> what its pending drive goes to (the containers of its GoToObject target)
    pending: dict[str, set[str]] = field(default_factory=dict)

    def drive(self, state: WorldState, robot: str, target: str) -> None:
        self.pending[robot] = containers(state, target)

    def op(self, state: WorldState, robot: str, step: str, action: Action) -> None:
        """Before ``action`` is applied: what it needs to stand still."""
        self.order[step] = len(self.order)
        needs = containers(state, action.receptacle)
        if action.skill not in _RELEASES:
            needs |= containers(state, action.target)
        self.anchors[step] = needs
        self.drive_anchors[step] = self.pending.pop(robot, set())

    def orders(self, carries: Mapping[str, Sequence[tuple[str, str | None]]], first_ops: set[str]
               ) -> tuple[set[tuple[str, str]], set[tuple[str, str]]]:
        """(precedences, drive waits): each operation on a carried object after the
        put-down of the carry before it (a drive wait when its robot drives to the object,
        or arrives at it from another job) and before the pickup of the carry after it.
        ``carries``: object -> (pickup op, put-down op or None when never put down) in
        plan order; ``first_ops``: the first operation of every job."""
        precedences: set[tuple[str, str]] = set()
        waits: set[tuple[str, str]] = set()
        for step, needs in self.anchors.items():
            at = self.order[step]
            for obj in sorted(needs):
                before, after = _neighbours(self.order, carries.get(obj, ()), at)
                if after is not None:
                    precedences.add((step, after))
                if before is not None:
                    arrives = obj in self.drive_anchors[step] or step in first_ops
                    (waits if arrives else precedences).add((before, step))
        return precedences, waits


def _neighbours(order: Mapping[str, int], spans: Sequence[tuple[str, str | None]], at: int
                ) -> tuple[str | None, str | None]:
    """The put-down of the last carry that ended before plan position ``at`` and the pickup
    of the first one that starts after it; a carry ``at`` lies within (the carrier's own
    operations, its pickup and put-down among them) is neither."""
    before: str | None = None
    after: str | None = None
    for pickup, putdown in spans:
        first, last = order[pickup], (order[putdown] if putdown is not None else len(order))
        if first <= at <= last:
            continue
        if last < at and putdown is not None:
            before = putdown
        if first > at and after is None:
            after = pickup
    return before, after
