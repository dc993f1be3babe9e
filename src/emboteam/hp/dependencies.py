"""What each plan step reads and writes, as state variables: the basis of the merge's
causal links and conflict orderings.

A step's *reads* are the state variables its preconditions and the conditions of its
effects looked at (the grounding records them in short-circuit order, so a condition
that decided nothing is not a dependency); its *writes* are the variables its effects set,
no-ops included (a second "make it hot" still races with a "make it cold"). Two steps of
different robots commute when neither writes what the other reads or writes: ordering
every pair that does not is Bäckström's read/write deordering, which keeps each step's
view of the world, hence its outcome, the same in every linearisation.

Variables (``kind:object``):

- ``pose:r`` where robot r stands, ``hand:r`` what it holds;
- ``loc:o`` where object o is (its receptacle or holder);
- ``contents:o`` the set of objects within o (an appliance heats all of them);
- ``open:o``, ``on:o``, ``temp:o``, ``cooked:o``, ``liquid:o``, ``dirty:o``,
  ``form:o`` (exists / sliced into pieces), ``broken:o``.

``at`` facts about *other* robots are the planner's bookkeeping, not the world: a robot's
reach depends on its own pose and the object's place, nothing else.
"""

from __future__ import annotations

from dataclasses import dataclass

from emboteam.pddl.domain import Grounding
from emboteam.pddl.schema import Atom
from emboteam.world.catalogue import HEATERS as HEATING
from emboteam.world.catalogue import WATER_SOURCES
from emboteam.world.state import WorldState

_UNARY = {
    "is-open": "open", "is-on": "on", "sliced": "form", "available": "form", "broken": "broken",
    "dirty": "dirty", "filled": "liquid", "has-coffee": "liquid", "has-water": "liquid",
    "has-wine": "liquid", "hot": "temp", "cold": "temp", "cooked": "cooked",
}


@dataclass(frozen=True)
class Footprint:
    """``writes`` set a variable; ``updates`` add or remove one element of a set variable
    (``contents``): two updates commute (apples put in one fridge end up there in either
    order), an update and a read of the whole set do not."""

    reads: frozenset[str]
    writes: frozenset[str]
    updates: frozenset[str] = frozenset()


def _chain(state: WorldState, o: str) -> list[str]:
    return [o, *state.ancestors(o)] if o in state.objects else [o]


def _locs(state: WorldState, o: str) -> set[str]:
    return {f"loc:{a}" for a in _chain(state, o)}


_NONE: frozenset[str] = frozenset()


def _read(robot: str, pred: str, args: tuple[str, ...], quantified: frozenset[str], state: WorldState) -> set[str]:
    """The variables a condition ``(pred args)`` reads (an atom's or a literal's, whose sign
    does not matter: only what is read)."""
    if pred == "at":
        if args[0] != robot:
            return set()
        return {f"pose:{robot}"} if args[1] in quantified else {f"pose:{robot}", *_locs(state, args[1])}
    if pred == "holding":
        return {f"hand:{args[0]}", f"loc:{args[1]}"}
    if pred == "hand-empty":
        return {f"hand:{args[0]}"}
    if pred in ("in", "within"):
        if args[0] in quantified:
            return {f"contents:{args[1]}"}
        return {f"loc:{args[0]}"} if pred == "in" else _locs(state, args[0])
    if pred in ("carried", "chilled-place"):
        return _locs(state, args[0])
    if pred == "hidden":
        o = args[0]
        encl = [a for a in _chain(state, o)[1:]
                if state.objects[a].has("openable") and state.objects[a].has("receptacle")]
        return _locs(state, o) | {f"open:{a}" for a in encl}
    if pred == "heated-place":
        c = args[0]
        return _locs(state, c) | {f"on:{a}" for a in _chain(state, c)
                                  if a in state.objects and state.objects[a].type in HEATING}
    if pred == "watered-place":
        chain = set(_chain(state, args[0]))
        return _locs(state, args[0]) | {f"on:{f.id}" for f in state.objects.values()
                                        if f.type in WATER_SOURCES and chain.intersection(f.controls)}
    kind = _UNARY.get(pred)
    return {f"{kind}:{args[0]}"} if kind is not None else set()


def _written(robot: str, atom: Atom, state: WorldState) -> tuple[set[str], set[str]]:
    """(writes, updates) of one effect literal."""
    pred, args = atom.pred, atom.args
    if pred == "at":
        return ({f"pose:{robot}"} if args[0] == robot else set()), set()
    if pred == "holding":
        return {f"hand:{args[0]}", f"loc:{args[1]}"}, set()
    if pred == "hand-empty":
        return {f"hand:{args[0]}"}, set()
    if pred == "in":
        return {f"loc:{args[0]}"}, {f"contents:{a}" for a in _chain(state, args[1])}
    kind = _UNARY.get(pred)
    return ({f"{kind}:{args[0]}"} if kind is not None else set()), set()


def footprint(robot: str, grounding: Grounding, state: WorldState) -> Footprint:
    """Reads and writes of a step grounded on ``state`` (the state before it)."""
    reads: set[str] = set()
    for lit in grounding.pre:
        reads |= _read(robot, lit.predicate, lit.args, _NONE, state)
    for atom, quantified in grounding.evaluated:
        reads |= _read(robot, atom.pred, atom.args, quantified, state)
    writes: set[str] = set()
    updates: set[str] = set()
    for atom, _ in grounding.fired:
        w, u = _written(robot, atom, state)
        writes |= w
        updates |= u
    return Footprint(reads=frozenset(reads), writes=frozenset(writes), updates=frozenset(updates - writes))
