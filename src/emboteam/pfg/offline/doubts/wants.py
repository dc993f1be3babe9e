"""The end state a word asks of an object: a state word or a verb as a goal predicate.

Used by the rules that propose goals for a thing the reading left without one ("the
mug, washed" -> clean(Mug)); the reader's own semantics is richer, these are the plain
one-object readings.
"""

from __future__ import annotations

from emboteam.pfg.offline.lexicon import Act, Stat
from emboteam.pfg.offline.tagger import Item
from emboteam.world.goals import Condition, ObjectRef, Predicate

P = Predicate

#: state word (with its polarity) -> predicate
STATE_PREDICATES: dict[tuple[Stat, bool], Predicate] = {
    (Stat.SWITCH, True): P.switched_on, (Stat.SWITCH, False): P.switched_off,
    (Stat.OPEN, True): P.open, (Stat.OPEN, False): P.closed,
    (Stat.HOT, True): P.hot, (Stat.COLD, True): P.cold, (Stat.COOKED, True): P.cooked,
    (Stat.CLEAN, True): P.clean, (Stat.CLEAN, False): P.dirty, (Stat.SLICED, True): P.sliced,
    (Stat.BROKEN, True): P.broken, (Stat.FILLED, True): P.filled, (Stat.HELD, True): P.held,
    (Stat.TOASTED, True): P.cooked,
}

#: act of a verb -> the one-object predicate it asks for
ACT_PREDICATES: dict[Act, Predicate] = {
    Act.SLICE: P.sliced, Act.BREAK: P.broken, Act.OPEN: P.open, Act.CLOSE: P.closed,
    Act.SWITCH_ON: P.switched_on, Act.SWITCH_OFF: P.switched_off, Act.COOL: P.cold,
    Act.DIRTY: P.dirty, Act.HOLD: P.held, Act.HEAT: P.hot, Act.MICROWAVE: P.hot, Act.COOK: P.cooked,
    Act.TOAST: P.cooked, Act.CLEAN: P.clean, Act.FILL: P.filled, Act.WATER: P.filled,
    Act.DIM: P.switched_off, Act.BRIGHTEN: P.switched_on,
}


def asked_predicate(item: Item) -> Predicate | None:
    """The predicate a state word or a verb asks for, if it asks for one state."""
    if item.state is not None:
        return STATE_PREDICATES.get(item.state)
    if item.verb is not None:
        return ACT_PREDICATES.get(item.verb.sense.act)
    return None


def one_object(pred: Predicate, type_: str) -> Condition:
    """``pred(type_)`` (water by default for filled)."""
    return Condition(predicate=pred, subject=ObjectRef(types=(type_,)),
                     liquid="water" if pred is P.filled else None)


def placed(type_: str, place: str) -> Condition:
    return Condition(predicate=P.inside, subject=ObjectRef(types=(type_,)), receptacle=ObjectRef(types=(place,)))


def with_subject(c: Condition, type_: str) -> Condition:
    """The same end state for another object: "... and the egg" after "put the apple in
    the fridge" -> inside(Egg, Fridge)."""
    return c.model_copy(update={"subject": ObjectRef(types=(type_,)), "count": 1})
