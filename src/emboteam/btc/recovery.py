"""The recovery table: from a false precondition or a typed action failure to the
recovery subtree that can clear it.

Pre's condition nodes diagnose *why* the core action may not start; the core action
reports *why* it failed (a :class:`~emboteam.world.actions.FailureReason`). Both become a
:class:`Diagnosis` naming a :class:`Strategy`, the guard of one recovery subtree, and the
object it works on (the closed fridge to open, the apple to grasp again). A diagnosis
without a strategy is unrecoverable here: the branch fails and the executor replans.

Diagnosis looks one step ahead so recoveries compose: a dropped apple inside a closed
fridge is "open the fridge" first, "grasp the apple" on the next diagnosis.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum

from emboteam.pddl.literal import Literal
from emboteam.world.actions import Action, FailureReason, Skill
from emboteam.world.catalogue import load_catalogue
from emboteam.world.state import WorldState

R = FailureReason

#: the pseudo failure Post reports when the core action succeeded but its effect is not
#: observed (the world changed under it)
POST_NOT_OBSERVED = "post_not_observed"


class Strategy(str, Enum):
    """Recovery subtrees, by the situation they clear."""

    WAIT_SYNC = "wait_sync"        # another robot's step must end first: wait for its flag
    ACQUIRE_SPOT = "acquire_spot"  # the step's spot is not held yet: wait until free, take it
    WAIT_IDLE = "wait_idle"        # the robot is still finishing an interrupted action
    REAPPROACH = "reapproach"      # not visible / out of reach / occluded: GoToObject again
    OPEN = "open"                  # the target is in a closed receptacle / the receptacle is closed
    FREE_HAND = "free_hand"        # the hand is full: put down what it holds
    REGRASP = "regrasp"            # the robot lost the object it must hold: go, pick it up
    WAIT_SPOT = "wait_spot"        # spot busy outside the lock protocol: back off, retry
    WAIT_HOLDER = "wait_holder"    # another robot holds the object: back off, retry
    RETRY = "retry"                # actuation fault or unobserved effect: run the action again

    def __str__(self) -> str:
        return self.value


#: recoveries that act on the environment (count against ``BTConfig.max_recoveries``)
ACTING = frozenset({Strategy.REAPPROACH, Strategy.OPEN, Strategy.FREE_HAND, Strategy.REGRASP})
#: bounded back-offs (count against ``BTConfig.max_waits``)
BACKOFFS = frozenset({Strategy.WAIT_SPOT, Strategy.WAIT_HOLDER})
#: the protocol's own waits: not failures, not budgeted (a dead producer ends them)
PROTOCOL = frozenset({Strategy.WAIT_SYNC, Strategy.ACQUIRE_SPOT, Strategy.WAIT_IDLE})


@dataclass(frozen=True)
class Diagnosis:
    strategy: Strategy | None
    obj: str | None = None
    why: str = ""

    @property
    def recoverable(self) -> bool:
        return self.strategy is not None

    def __str__(self) -> str:
        what = str(self.strategy) if self.strategy else "unrecoverable"
        return f"{what}({self.obj})" if self.obj else what


def fatal(why: str) -> Diagnosis:
    return Diagnosis(None, None, why)


def strategies_for(skill: Skill, *, waits: bool, holds: bool) -> tuple[Strategy, ...]:
    """The recovery subtrees a step of this skill gets, in the Selector's order.

    A drive can only be retried (nothing can be "not visible" for navigation); every
    interaction gets the whole table, since any of them may find its object moved,
    enclosed, held by someone else or its hand full.
    """
    protocol = [s for s, on in ((Strategy.WAIT_SYNC, waits), (Strategy.ACQUIRE_SPOT, holds),
                                (Strategy.WAIT_IDLE, True)) if on]
    if skill is Skill.GoToObject:
        return (*protocol, Strategy.RETRY)
    return (*protocol, Strategy.REAPPROACH, Strategy.OPEN, Strategy.FREE_HAND, Strategy.REGRASP,
            Strategy.WAIT_SPOT, Strategy.WAIT_HOLDER, Strategy.RETRY)


def _regain(state: WorldState, robot: str, obj: str) -> Diagnosis:
    """The robot must hold ``obj`` but does not."""
    o = state.objects.get(obj)
    if o is None or o.gone:
        return fatal(f"{obj} no longer exists")
    r = state.robots[robot]
    if o.held_by is not None and o.held_by != robot:
        return Diagnosis(Strategy.WAIT_HOLDER, obj, f"{obj} is held by {o.held_by}")
    if r.holding is not None and r.holding != obj:
        return Diagnosis(Strategy.FREE_HAND, r.holding, f"{robot} must put {r.holding} down first")
    closed = state.enclosing_closed(obj)
    if closed is not None:
        return Diagnosis(Strategy.OPEN, closed, f"{obj} is inside closed {closed}")
    return Diagnosis(Strategy.REGRASP, obj, f"{robot} lost {obj}")


def _approach(state: WorldState, obj: str) -> Diagnosis:
    o = state.objects.get(obj)
    if o is None or o.gone:
        return fatal(f"{obj} no longer exists")
    closed = state.enclosing_closed(obj)
    if closed is not None:
        return Diagnosis(Strategy.OPEN, closed, f"{obj} is inside closed {closed}")
    return Diagnosis(Strategy.REAPPROACH, obj, f"{obj} is not within reach or not visible")


def diagnose_literal(lit: Literal, state: WorldState, robot: str) -> Diagnosis:
    """Why a false precondition is false, and what could make it true."""
    p, args = lit.predicate, lit.args
    if p == "at" and lit.positive:
        return _approach(state, args[1])
    if p == "hidden" and not lit.positive:
        closed = state.enclosing_closed(args[0]) if args[0] in state.objects else None
        return Diagnosis(Strategy.OPEN, closed, f"{args[0]} is inside closed {closed}") if closed \
            else fatal(f"{lit} does not hold")
    if p == "is-open" and lit.positive:
        o = state.objects.get(args[0])
        if o is not None and o.has("openable"):
            return Diagnosis(Strategy.OPEN, args[0], f"{args[0]} is closed")
    if p == "hand-empty" and lit.positive:
        held = state.robots[args[0]].holding if args[0] in state.robots else None
        return Diagnosis(Strategy.FREE_HAND, held, f"{args[0]} holds {held}")
    if p == "holding" and lit.positive and args[0] == robot:
        return _regain(state, robot, args[1])
    if p == "holding" and not lit.positive and args[0] == robot:
        return Diagnosis(Strategy.FREE_HAND, args[1], f"{robot} must not hold {args[1]}")
    return fatal(f"precondition {lit} does not hold")


def diagnose_failure(reason: str, action: Action, state: WorldState, robot: str) -> Diagnosis:
    """What to do about a typed failure of the core action."""
    obj = action.receptacle or action.target
    if reason in (R.NOT_VISIBLE, R.NOT_REACHABLE):
        return _approach(state, obj)
    if reason == R.RECEPTACLE_CLOSED and action.receptacle is not None:
        return Diagnosis(Strategy.OPEN, action.receptacle, f"{action.receptacle} is closed")
    if reason == R.HAND_FULL:
        held = state.robots[robot].holding
        return Diagnosis(Strategy.FREE_HAND, held, f"{robot} holds {held}")
    if reason in (R.HAND_EMPTY, R.NOT_HOLDING_TARGET):
        return _regain(state, robot, action.target)
    if reason == R.HELD_BY_OTHER:
        return Diagnosis(Strategy.WAIT_HOLDER, action.target, f"{action.target} is held by another robot")
    if reason == R.SPOT_BUSY:
        return Diagnosis(Strategy.WAIT_SPOT, obj, f"the spot of {obj} is busy")
    if reason == R.ROBOT_BUSY:
        return Diagnosis(Strategy.WAIT_IDLE, None, f"{robot} is busy")
    if reason in (R.ACTUATION_FAULT, POST_NOT_OBSERVED):
        return Diagnosis(Strategy.RETRY, action.target, f"{action} failed ({reason}): try again")
    return fatal(f"{action} failed: {reason}")


def put_down_action(state: WorldState, robot: str,
                    spot_taken: Callable[[str], bool]) -> Action | None:
    """How to empty the robot's hand without driving anywhere: put the held object on
    the nearest receptacle within reach that accepts it (open, not held, its spot not
    reserved by another robot), else drop it; ``None`` if the robot can do neither."""
    r = state.robots[robot]
    held = r.holding
    if held is None:
        return None
    cat = load_catalogue()
    h = state.objects[held]
    inside = {d.id for d in state.descendants(held)}
    if r.profile.can(Skill.PutObject):
        options = sorted(
            (state.distance(robot, o.id), o.id) for o in state.objects.values()
            if o.has("receptacle") and o.id != held and o.id not in inside and not o.gone
            and o.held_by is None and state.in_reach(robot, o.id)
            and cat.can_place(h.type, o.type)
            and not (o.type in cat.must_be_open and not o.is_open)
            and state.enclosing_closed(o.id) is None
            and not spot_taken(state.spot_of(o.id))
        )
        if options:
            return Action(skill=Skill.PutObject, target=held, receptacle=options[0][1])
    if r.profile.can(Skill.DropHandObject):
        return Action(skill=Skill.DropHandObject, target=held)
    return None
