"""Groundings reused across the states of one episode, exactly.

A step's grounding (:func:`emboteam.pddl.domain.ground`) is a deterministic function of
its schema, its binding, the universe's constants (objects, robots, statics) and the
answers the state gives it: the truth of the fluents it evaluates and the values its
quantified variables are generated from, asked in an order that itself depends only on
the earlier answers. Planning grounds the same steps again and again on states that
differ only where the step does not look (a unit's plan replayed after the units accepted
before it in the round, a reordered plan replayed from the start, a rebuilt one
simulated), and the search over bindings costs several times the questions it asks.

So each grounding is kept with the questions it asked and their answers (a
:class:`Recorded`); a later grounding of the same schema and binding asks the state those
questions again, in the same order, and takes the kept grounding when every answer is
the same: it would have taken the very same path to the very same result. Nothing is
assumed about which state variables a step reads.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Generic, Protocol, TypeVar

from emboteam.pddl import vocabulary

if TYPE_CHECKING:
    from emboteam.pddl.schema import Atom

#: how many groundings are kept per schema and binding (each checked in turn; the newest
#: replaces the oldest): states of one episode seldom give a step more than a few
KEPT = 4

#: a question and its answer: ``(pred, args, truth)`` of a fluent, or ``(pred, a, b, var,
#: values)`` of a generated variable
Answer = tuple[object, ...]

K = TypeVar("K")
T = TypeVar("T")


class _Asked(Protocol):
    """What :class:`Recorder` asks of a universe (:class:`emboteam.pddl.domain.Universe`)."""

    def fluent(self, evaluator: vocabulary.Evaluator, args: tuple[str, ...]) -> bool: ...

    def static(self, pred: str, args: tuple[str, ...]) -> bool: ...

    def values(self, pred: str, a: str, b: str, var: str) -> list[str] | None: ...


@dataclass(frozen=True, slots=True)
class Recorded(Generic[T]):
    """A grounding and the answers it was computed from, in the order asked."""

    answers: tuple[Answer, ...]
    result: T


class Recorder:
    """The universe's ``truth`` and ``generate``, with every answer of the live state noted
    (statics are constants of the universe: not noted)."""

    __slots__ = ("answers", "universe")

    def __init__(self, universe: _Asked) -> None:
        self.universe = universe
        self.answers: list[Answer] = []

    def truth(self, pred: str, args: tuple[str, ...]) -> bool:
        entry = vocabulary.FLUENTS.get(pred)
        if entry is None:
            return self.universe.static(pred, args)
        value = self.universe.fluent(entry[1], args)
        self.answers.append((pred, args, value))
        return value

    def generate(self, atom: Atom, binding: Mapping[str, str], var: str) -> Sequence[str] | None:
        if not atom.positive or len(atom.args) != 2:
            return None
        a, b = (binding.get(x, x) for x in atom.args)
        found = self.universe.values(atom.pred, a, b, var)
        self.answers.append((atom.pred, a, b, var, found))
        return found


def same_answers(universe: _Asked, answers: Sequence[Answer]) -> bool:
    """Does ``universe``'s state answer every question as it was answered before?"""
    fluents = vocabulary.FLUENTS
    try:
        for q in answers:
            if len(q) == 3:
                pred, args, value = q
                if universe.fluent(fluents[pred][1], args) != value:  # type: ignore[index, arg-type]
                    return False
            elif universe.values(*q[:4]) != q[4]:  # type: ignore[arg-type]
                return False
    except (KeyError, ValueError, AttributeError):
        return False
    return True


def reused(kept: dict[K, list[Recorded[T]]], key: K, universe: _Asked, compute: Callable[[Recorder], T]) -> T:
    """The grounding ``compute`` would give on ``universe`` for ``key``: a kept one whose
    answers ``universe`` repeats, or a new one, computed through a :class:`Recorder` and
    kept."""
    entries = kept.get(key)
    if entries is not None:
        for entry in entries:
            if same_answers(universe, entry.answers):
                return entry.result
    recorder = Recorder(universe)
    result = compute(recorder)
    entries = kept.setdefault(key, [])
    if len(entries) >= KEPT:
        del entries[0]
    entries.append(Recorded(tuple(recorder.answers), result))
    return result
