"""Things picked out by a property instead of a name ("everything small on the TV stand",
"all the breakables", "anything over four kilos", "whatever runs on electricity").

The vocabulary is data (``properties.json``, schema checked at load): a phrase names a
property, a property is a list of alternative tests over a scene object, likeliest first.
A test reads the object's own metadata (AI2-THOR flags, mass) or, where the metadata says
nothing (what runs on electricity, what can be eaten), a table of types. A vague property
("small", "heavy") has several tests: the contents point of doubt offers one alternative
per test instead of guessing one silently. A measure ("over four kilos") is one test.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from pydantic import Field, field_validator

from emboteam.pfg.offline.doubts.rule_words import Words, starts_at
from emboteam.pfg.offline.knowledge import Strict, known_types, read
from emboteam.pfg.offline.tagger import Item
from emboteam.world.catalogue import Property
from emboteam.world.state import ObjectState

PROPERTIES_FILE = Path(__file__).with_name("properties.json")


class Test(Strict):
    """What an object must be: every field given holds."""

    types: list[str] = Field(default_factory=list)
    flags: list[Property] = Field(default_factory=list)
    mass_min: float | None = Field(None, ge=0)
    mass_max: float | None = Field(None, ge=0)

    _types = field_validator("types")(known_types)

    def holds(self, o: ObjectState) -> bool:
        return ((not self.types or o.type in self.types) and all(o.has(f) for f in self.flags)
                and (self.mass_min is None or o.mass > self.mass_min)
                and (self.mass_max is None or o.mass <= self.mass_max))


class Property_(Strict):
    name: str
    words: list[Words] = Field(min_length=1)
    tests: list[Test] = Field(min_length=1)


class Measures(Strict):
    above: list[Words]
    below: list[Words]
    #: kilograms per unit
    units: dict[str, float]


class PropertiesFile(Strict):
    about: str = ""
    properties: list[Property_]
    measures: Measures
    #: hedges that may stand inside a property's words ("that you could actually eat")
    fillers: list[str] = Field(default_factory=list)


@cache
def load_properties(path: Path = PROPERTIES_FILE) -> PropertiesFile:
    return read(path, PropertiesFile)


@cache
def _openers() -> frozenset[str]:
    """The words a property or a measure may start with (most tokens start none)."""
    data = load_properties()
    phrases = [*(w for prop in data.properties for w in prop.words), *data.measures.above, *data.measures.below]
    return frozenset(w[0] for w in phrases)


@dataclass(frozen=True)
class Picked:
    """A property found in the words: where it is, its name and its alternative tests."""

    start: int
    end: int
    name: str
    tests: tuple[Test, ...]
    #: named as an exception ("apart from what's plugged in"): the things WITHOUT it
    negated: bool = False


def _number(item: Item) -> float | None:
    if item.number is not None:
        return float(item.number)
    try:
        return float(item.text)
    except ValueError:
        return None


def _measure(items: Sequence[Item], k: int, table: Measures) -> Picked | None:
    """"over four kilos", "less than 500 grams": a mass test."""
    for side, phrases in (("mass_min", table.above), ("mass_max", table.below)):
        for words in phrases:
            n = k + len(words)
            if starts_at(items, k, words) and n + 1 < len(items) + 1 and n < len(items):
                value = _number(items[n])
                unit = items[n + 1].text if n + 1 < len(items) else ""
                if value is not None and unit in table.units:
                    return Picked(k, n + 2, side, (Test.model_validate({side: value * table.units[unit]}),))
    return None


def _matched(items: Sequence[Item], k: int, words: Words, fillers: frozenset[str]) -> int | None:
    """Where ``words`` end when they stand from ``k`` on, hedges between them skipped."""
    j = k
    for n, w in enumerate(words):
        while n and j < len(items) and items[j].text in fillers and items[j].text != w:
            j += 1
        if j >= len(items) or items[j].text != w:
            return None
        j += 1
    return j


def picked_at(items: Sequence[Item], k: int, names_thing: Callable[[int], bool]) -> Picked | None:
    """The property whose words start at ``k``; not an adjective of a thing named right
    after it ("the small lamp" names a lamp, not a set)."""
    if items[k].text not in _openers():
        return None
    data = load_properties()
    found = _measure(items, k, data.measures)
    if found is not None:
        return found
    for prop in data.properties:
        for words in prop.words:
            end = _matched(items, k, words, frozenset(data.fillers))
            if end is not None:
                nxt = end + 1 if end < len(items) and items[end].det else end
                if nxt < len(items) and names_thing(nxt):
                    continue
                return Picked(k, end, prop.name, tuple(prop.tests))
    return None


def properties_in(items: Sequence[Item], start: int, end: int,
                  names_thing: Callable[[int], bool]) -> list[Picked]:
    """Every property named between ``start`` and ``end``."""
    out: list[Picked] = []
    k = start
    while k < end:
        found = picked_at(items, k, names_thing)
        if found is not None:
            out.append(found)
            k = found.end
        else:
            k += 1
    return out


def alternatives(picked: Sequence[Picked]) -> list[tuple[str, Callable[[ObjectState], bool]]]:
    """One (description, test) per way of reading the properties together: the likeliest
    test of each, then each further test of a vague one with the others at their likeliest."""
    if not picked:
        return []
    first = [p.tests[0] for p in picked]
    ways = [first, *([*first[:i], t, *first[i + 1:]] for i, p in enumerate(picked) for t in p.tests[1:])]

    def describe(tests: list[Test]) -> str:
        return " and ".join(f"{'not ' if p.negated else ''}{p.name} ({t.model_dump(exclude_defaults=True)})"
                            for p, t in zip(picked, tests, strict=True))

    def test(tests: list[Test]) -> Callable[[ObjectState], bool]:
        return lambda o: all(t.holds(o) != p.negated for p, t in zip(picked, tests, strict=True))

    return [(describe(w), test(w)) for w in ways]
