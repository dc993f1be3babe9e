"""What each act and state asks of its object, as data (``data/acts.json``, checked
against :class:`ActsFile` at import): the capability an object needs, the goal predicate
an act or a state is, how a condition is described, and the dishes with a clear
household reading. :mod:`~emboteam.pfg.offline.semantics` interprets them."""

from __future__ import annotations

from typing import Literal

from pydantic import model_validator

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.knowledge import KnowledgeDataError, Strict, load
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Predicate

#: a capability of an object type (``ObjectType.has``-like, as the grounder reads it)
Capability = Literal["hold", "slice", "break", "open", "switch", "cook", "dirty", "fill"]


class _ActRule(Strict):
    needs: Capability | None
    #: the one state an act is, when it is one ("slice" is ``sliced``); else its own rule
    predicate: Predicate | None = None


class _StateRule(Strict):
    needs: Capability | None
    true: Predicate | None = None
    false: Predicate | None = None
    #: what an object wished to have the state must be able to become ("a clean plate":
    #: one that gets dirty)
    wished_needs: Capability | None = None


class _Goal(Strict):
    predicate: Predicate
    liquid: str | None = None


class Dish(Strict):
    """A dish: the goal conditions of what it is served in (a mug of coffee, the egg), or
    one condition on each of the types the scene has (``each_of``: a salad)."""

    served_in: str | None = None
    each_of: tuple[str, ...] = ()
    #: an appliance the scene must have to make it
    needs_type: str | None = None
    conditions: tuple[_Goal, ...]

    @model_validator(mode="after")
    def _one_subject(self) -> Dish:
        if (self.served_in is None) == (not self.each_of):
            raise ValueError("a dish is served_in one type or made of each_of several, exactly one")
        return self

    def types(self) -> tuple[str, ...]:
        return (*self.each_of, *filter(None, (self.served_in, self.needs_type)))


class _Tool(Strict):
    act: lx.Act
    #: what the thing it is used on must be (a catalogue property: "sliceable")
    used_on: str


class ActsFile(Strict):
    """``data/acts.json``."""

    about: str = ""
    acts: dict[lx.Act, _ActRule]
    states: dict[lx.Stat, _StateRule]
    describe: dict[Predicate, str]
    dishes: dict[str, Dish]
    cookware: frozenset[str]
    stove_vessels: frozenset[str]
    disposal: frozenset[str]
    tools: dict[str, _Tool]

    @model_validator(mode="after")
    def _complete(self) -> ActsFile:
        missing = [s.value for s in lx.Stat if s not in self.states]
        if missing:
            raise ValueError(f"states: no rule for {missing[0]!r}")
        for pred in Predicate:
            phrase = self.describe.get(pred, "")
            if "{s}" not in phrase:
                raise ValueError(f"describe -> {pred.value!r}: a description with {{s}} for the object is needed")
        return self


_FILE = "acts.json"
_ACTS = load(_FILE, ActsFile)

#: which capability an act needs of its object, for grounding and for a pronoun's antecedent
ACT_NEEDS: dict[lx.Act, str | None] = {a: r.needs for a, r in _ACTS.acts.items()}
#: acts that are one state of their object
ACT_PREDICATE: dict[lx.Act, Predicate] = {a: r.predicate for a, r in _ACTS.acts.items() if r.predicate}
STAT_NEEDS: dict[lx.Stat, str | None] = {s: r.needs for s, r in _ACTS.states.items()}
#: the capability a wished state asks of the object ("a clean plate": one that gets dirty)
WISHED_NEEDS: dict[lx.Stat, str | None] = {s: r.wished_needs for s, r in _ACTS.states.items()}
STAT_PREDICATE: dict[tuple[lx.Stat, bool], Predicate] = {
    (s, positive): pred for s, r in _ACTS.states.items()
    for positive, pred in ((True, r.true), (False, r.false)) if pred is not None}
DESCRIBE: dict[Predicate, str] = _ACTS.describe
DISHES: dict[str, Dish] = _ACTS.dishes
#: things whose temperature is a tool's, not food's ("the pan's hot" is a warning)
COOKWARE = _ACTS.cookware
#: what boils or fries on a burner and stays there
STOVE_VESSELS = _ACTS.stove_vessels
#: containers no piece of furniture stands in ("on the counter in the bin"; "in the safe
#: on the dresser" is where the safe is)
DISPOSAL = _ACTS.disposal
#: what a tool does to what it is used on ("use a knife on the bread")
TOOLS = _ACTS.tools


def _check_types() -> None:
    """Every type named is in the catalogue, and every recipe of the lexicon is a
    dish (or toast, which :class:`~emboteam.pfg.offline.semantics.Semantics` makes by its
    own rule: it counts slices)."""
    catalogue = load_catalogue().types
    named = [(f"dishes -> {name!r}", dish.types()) for name, dish in DISHES.items()]
    named += [(table, tuple(getattr(_ACTS, table))) for table in ("cookware", "stove_vessels", "disposal", "tools")]
    for entry, types in named:
        unknown = [t for t in types if t not in catalogue]
        if unknown:
            raise KnowledgeDataError(_FILE, entry, f"no object type {unknown[0]!r} in the catalogue")
    for phrase, recipe in lx.RECIPES.items():
        if recipe not in DISHES and recipe != "toast":
            raise KnowledgeDataError("lexicon.json", f"recipes -> {phrase!r}", f"no dish {recipe!r} in {_FILE}")


_check_types()
