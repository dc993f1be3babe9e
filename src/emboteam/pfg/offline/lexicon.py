"""The offline parser's lexicon: words and phrases and what they mean to a household
robot team. The words are data, ``data/lexicon.json``, checked against
:class:`LexiconFile` when this module is imported; this module turns them into the tables
the tagger, the grounder and the semantics read (docs/teach_a_phrasing.md):

- a name for an object: ``"phrase": "Type"`` in ``nouns`` (singular; plurals are
  derived); a name for several types in order of preference: ``["A", "B"]``, with
  fallbacks for scenes that lack them: ``{"types": [...], "fallback": [...]}``; a word of
  a category: ``{"concept": "vegetables"}`` (the categories are ``concepts``);
- a verb: its lemma in the ``words`` of its act in ``verbs``; irregular forms in
  ``irregular_verbs``; a verb whose particle changes it ("throw away") in ``particle_verbs``;
- a state word ("spotless"): in the ``words`` of its state in ``states``.

Every AI2-THOR type is also reachable by its own name, split (``coffee table``) or run
together (``coffeetable``): :func:`nouns` adds those entries from the catalogue.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from enum import Enum
from functools import cache
from typing import Any, Literal

from pydantic import Field, field_validator, model_validator

from emboteam.pfg.offline.knowledge import KnowledgeDataError, Rewrite, Strict, load
from emboteam.pfg.offline.text import split_camel
from emboteam.world.catalogue import load_catalogue


class Act(str, Enum):
    """What a verb asks for; the semantics turns each into goal conditions."""

    PLACE = "place"          # put X in/on Y
    TRASH = "trash"          # X into a garbage can
    HOLD = "hold"            # pick X up
    SLICE = "slice"
    BREAK = "break"
    OPEN = "open"
    CLOSE = "close"
    SWITCH = "switch"        # needs a particle: turn on / switch off
    SWITCH_ON = "switch_on"
    SWITCH_OFF = "switch_off"
    TOGGLE = "toggle"        # flip whatever the state is
    HEAT = "heat"
    MICROWAVE = "microwave"  # heat, and the microwave is the means
    COOK = "cook"
    TOAST = "toast"          # slice bread and cook the slices
    COOL = "cool"
    CLEAN = "clean"
    DIRTY = "dirty"
    FILL = "fill"
    POUR = "pour"            # pour LIQUID into X
    WATER = "water"          # water the plant
    MAKE = "make"            # make coffee / make the room dark
    WATCH = "watch"          # watch tv: the tv is on
    GO = "go"                # intransitive motion: X goes/belongs in Y
    CAUSE = "cause"          # leave/keep/get/have X STATE
    EMPTY = "empty"
    VAGUE = "vague"          # tidy, organise: no clear household reading
    DIM = "dim"              # dim/darken: lights off
    BRIGHTEN = "brighten"


class Stat(str, Enum):
    """A state a word can name; with a polarity it becomes one goal predicate."""

    SWITCH = "switch"
    OPEN = "open"
    HOT = "hot"
    COLD = "cold"
    COOKED = "cooked"
    CLEAN = "clean"
    SLICED = "sliced"
    BROKEN = "broken"
    FILLED = "filled"
    HELD = "held"
    BRIGHT = "bright"        # of a room: its lights
    TOASTED = "toasted"


#: states whose negation is another state ("not open" = closed)
INVERTIBLE = frozenset({Stat.SWITCH, Stat.OPEN, Stat.CLEAN, Stat.BRIGHT})


@dataclass(frozen=True, slots=True)
class VerbSense:
    act: Act
    #: a generic verb (get, have, go): a clause with it and an unknown noun is small talk
    #: ("when you get a chance"), not an error
    weak: bool = False


@dataclass(frozen=True, slots=True)
class Concept:
    """What a noun names: object types (in order of preference), with fallbacks for
    scenes that lack all of them."""

    name: str
    types: tuple[str, ...] = ()
    fallback: tuple[str, ...] = ()
    kind: str = "object"   # object | category | lights | lamps | room | liquid | anything | recipe


def _obj(*types: str, fallback: tuple[str, ...] = ()) -> Concept:
    return Concept(split_camel(types[0]).lower(), types, fallback)


# --- the schema of data/lexicon.json ------------------------------------------------------

Words = tuple[str, ...]


class _Sense(Strict):
    """Words with one sense: ``{"act": "place", "words": ["put", ...]}``."""

    act: Act
    weak: bool = False
    words: Words = Field(min_length=1)


class _StateWords(Strict):
    state: Stat
    polarity: bool
    words: Words = Field(min_length=1)


class _ActState(Strict):
    state: Stat
    polarity: bool


class _Category(Strict):
    types: Words = ()
    kind: Literal["category", "lights", "lamps", "room", "anything"] = "category"


class _Noun(Strict):
    """``"Type"``, ``["A", "B"]`` (in order of preference), ``{"types": [...], "fallback":
    [...]}`` or ``{"concept": "NAME"}`` (one of ``concepts``)."""

    types: Words = ()
    fallback: Words = ()
    concept: str | None = None

    @model_validator(mode="before")
    @classmethod
    def _short_forms(cls, value: Any) -> Any:
        if isinstance(value, str):
            return {"types": [value]}
        if not isinstance(value, (list, dict)):
            raise ValueError('a noun is "Type", ["A", "B"], {"types": [...], "fallback": [...]} '
                             'or {"concept": "NAME"}')
        return {"types": value} if isinstance(value, list) else value

    @model_validator(mode="after")
    def _one_meaning(self) -> _Noun:
        if bool(self.types) == bool(self.concept):
            raise ValueError("a noun names object types or a concept, exactly one of them")
        return self


class LexiconFile(Strict):
    """``data/lexicon.json``: every table of the lexicon."""

    about: str = ""
    verbs: tuple[_Sense, ...]
    verb_places: dict[str, Words]
    particle_verbs: tuple[_Sense, ...]
    particles: frozenset[str]
    irregular_verbs: dict[str, str]
    states: tuple[_StateWords, ...]
    act_state: dict[Act, _ActState]
    prepositions: dict[str, str]
    determiners: frozenset[str]
    quantifiers: frozenset[str]
    pronouns: frozenset[str]
    negations: frozenset[str]
    copulas: frozenset[str]
    modals: frozenset[str]
    numbers: dict[str, int]
    vague_counts: frozenset[str]
    ordinals: dict[str, int]
    sequence_markers: Words
    subordinators: dict[str, str]
    conjunctions: dict[str, Literal["and", "or"]]
    filler_words: frozenset[str]
    common_words: frozenset[str]
    idioms: tuple[Rewrite, ...]
    vague_phrases: tuple[str, ...]
    recipes: dict[str, str]
    vague_nouns: frozenset[str]
    liquids: frozenset[str]
    concepts: dict[str, _Category]
    nouns: dict[str, _Noun]
    plural_nouns: dict[str, _Noun]
    measure_words: frozenset[str]
    containing: frozenset[str]
    mass_nouns: frozenset[str]
    switched_by: dict[str, Words]
    robot_words: frozenset[str]

    @field_validator("vague_phrases")
    @classmethod
    def _patterns(cls, value: tuple[str, ...]) -> tuple[str, ...]:
        return tuple(Rewrite(pattern=p, replace="").pattern for p in value)

    @field_validator("particle_verbs")
    @classmethod
    def _two_words(cls, value: tuple[_Sense, ...]) -> tuple[_Sense, ...]:
        for sense in value:
            for pair in sense.words:
                if len(pair.split()) != 2:
                    raise ValueError(f"{pair!r}: a particle verb is two words, the verb and its particle")
        return value

    @model_validator(mode="after")
    def _known_concepts(self) -> LexiconFile:
        for table in ("nouns", "plural_nouns"):
            for phrase, noun in getattr(self, table).items():
                if noun.concept is not None and noun.concept not in self.concepts:
                    raise ValueError(f"{table} -> {phrase!r}: no concept {noun.concept!r} "
                                     f"(concepts: {', '.join(self.concepts)})")
        return self


_FILE = "lexicon.json"
_LEX = load(_FILE, LexiconFile)


def _noun(noun: _Noun) -> Concept:
    if noun.concept is not None:
        category = _LEX.concepts[noun.concept]
        return Concept(noun.concept, category.types, kind=category.kind)
    return _obj(*noun.types, fallback=noun.fallback)


VERBS: dict[str, VerbSense] = {w: VerbSense(s.act, s.weak) for s in _LEX.verbs for w in s.words}
#: verbs that name where things go: "shelve the book" is ``inside(Book, Shelf)``
VERB_PLACES: dict[str, tuple[str, ...]] = _LEX.verb_places
#: (verb, particle) -> sense, where the particle changes what the verb means
PARTICLE_VERBS: dict[tuple[str, str], VerbSense] = {
    (w.split()[0], w.split()[1]): VerbSense(s.act, s.weak) for s in _LEX.particle_verbs for w in s.words}
#: particles that may follow a verb (or its object)
PARTICLES = _LEX.particles
#: irregular inflections -> lemma (regular ones are handled by rules in morphology)
IRREGULAR_VERBS: dict[str, str] = _LEX.irregular_verbs
#: state words: adjectives and participles a goal can be stated with
STATES: dict[str, tuple[Stat, bool]] = {w: (s.state, s.polarity) for s in _LEX.states for w in s.words}
#: the state each act brings about (for negation: "don't turn on" = off)
ACT_STATE: dict[Act, tuple[Stat, bool]] = {a: (s.state, s.polarity) for a, s in _LEX.act_state.items()}
#: prepositions -> a canonical role
PREPOSITIONS: dict[str, str] = _LEX.prepositions
DETERMINERS = _LEX.determiners
QUANTIFIERS = _LEX.quantifiers
PRONOUNS = _LEX.pronouns
NEGATIONS = _LEX.negations
#: copulas and modals: "the fridge should be closed", "the tv must be off"
COPULAS = _LEX.copulas
#: modal words that make a statement a wish ("should be closed") rather than a report
#: of how things are ("is open"); patterns.json reads them as ``@lexicon.modals``
MODALS = _LEX.modals
NUMBERS: dict[str, int] = _LEX.numbers
#: counts that are estimates: clamp them to what the scene has
VAGUE_COUNTS = _LEX.vague_counts
ORDINALS: dict[str, int] = _LEX.ordinals
#: connectives that order what follows after what precedes
SEQUENCE_MARKERS: tuple[str, ...] = _LEX.sequence_markers
#: subordinators: (word, relation); "after X" -> the main clause follows X
SUBORDINATORS: dict[str, str] = _LEX.subordinators
#: coordinating words and the coordination they make ("plus" joins as "and")
CONJUNCTIONS: dict[str, str] = dict(_LEX.conjunctions)
#: words that carry no content for the parser: politeness, discourse, hedges. Matched
#: anywhere outside noun phrases and dropped. Also the words spelling correction must
#: never "correct" into object names.
FILLER_WORDS = _LEX.filler_words
#: ordinary English words that are not in the lexicon but must not be spelling-corrected
#: into one of its words ("there" is one transposition from "three")
COMMON_WORDS = FILLER_WORDS | _LEX.common_words
#: fixed expressions, rewritten before tagging (regular expressions on normalised text)
IDIOMS: tuple[tuple[str, str], ...] = tuple((r.pattern, r.replace) for r in _LEX.idioms)
#: chores with no single household reading: an instruction with one of them is refused
#: with a clear message rather than guessed at
VAGUE_PHRASES: tuple[str, ...] = _LEX.vague_phrases
#: a recipe: a dish whose household reading is clear
RECIPES: dict[str, str] = _LEX.recipes
#: meals and chores with no single household reading: a clear error instead of a guess
VAGUE_NOUNS = _LEX.vague_nouns
LIQUIDS = _LEX.liquids
_NOUNS: dict[str, Concept] = {phrase: _noun(n) for phrase, n in _LEX.nouns.items()}
#: plural forms that mean something else than their singular ("dishes" = all dishware)
PLURAL_NOUNS: dict[str, Concept] = {phrase: _noun(n) for phrase, n in _LEX.plural_nouns.items()}
#: measure and collective words: "a roll of foil", "two loaves of bread", "a head of
#: lettuce", "a pair of boots" name the thing after "of"
MEASURE_WORDS = _LEX.measure_words
#: "a plate containing an egg": the words that introduce what a container holds
CONTAINING = _LEX.containing
#: collective nouns of categories: "the cutlery" is every piece of cutlery
MASS_NOUNS = _LEX.mass_nouns
#: what is switched instead of an object that cannot be (the stove by its knobs)
SWITCHED_BY: dict[str, tuple[str, ...]] = _LEX.switched_by
#: robot words: "robot 2", "the second robot", "bot 3"
ROBOT_WORDS = _LEX.robot_words


@cache
def nouns() -> dict[str, Concept]:
    """All noun phrases (singular), hand-written synonyms first, then every catalogue type
    by its own name, split and run together."""
    out = dict(_NOUNS)
    cat = load_catalogue()
    for table, entries in (("nouns", _NOUNS), ("plural_nouns", PLURAL_NOUNS)):
        for phrase, concept in entries.items():
            unknown = [t for t in (*concept.types, *concept.fallback) if t not in cat.types]
            if unknown:
                raise KnowledgeDataError(_FILE, f"{table} -> {phrase!r}", f"no object type {unknown[0]!r} in the catalogue")
    source = {piece for piece, _ in cat.slice_products.values()}
    for name in cat.types:
        if name in source:
            continue
        spaced = split_camel(name).lower()
        for key in (spaced, spaced.replace(" ", "")):
            out.setdefault(key, _obj(name))
    _add_compound_heads(out, cat.types, source)
    return out


def _add_compound_heads(out: dict[str, Concept], types: Iterable[str], source: set[str]) -> None:
    """"Put the mug in the coffee machine and switch the machine on": the last word of a
    compound type name ("machine", "control", "chain") names that type when the word means
    nothing else to the parser; several types sharing the word are one concept (the
    grounder keeps those in the scene)."""
    reserved = COMMON_WORDS | ROBOT_WORDS | MEASURE_WORDS | PARTICLES | set(VERBS) | set(STATES)
    heads: dict[str, list[str]] = {}
    for name in types:
        words = split_camel(name).lower().split()
        if len(words) > 1 and name not in source:
            heads.setdefault(words[-1], []).append(name)
    for word, named in sorted(heads.items()):
        if word not in out and word not in reserved:
            out[word] = Concept(word, tuple(sorted(named)))


@cache
def noun_words() -> frozenset[str]:
    """Every word that occurs in a noun phrase."""
    words: set[str] = set()
    for phrase in list(nouns()) + list(PLURAL_NOUNS) + list(RECIPES):
        words.update(phrase.split())
    return frozenset(words)


@cache
def vocabulary() -> frozenset[str]:
    """Every word the parser knows: the targets of spelling correction."""
    words = set(noun_words()) | set(VERBS) | set(STATES) | set(PARTICLES) | set(NUMBERS)
    words |= {w for p in PREPOSITIONS for w in p.split()}
    words |= {w for p in SEQUENCE_MARKERS for w in p.split()}
    words |= set(LIQUIDS) | set(IRREGULAR_VERBS) | DETERMINERS | QUANTIFIERS | PRONOUNS
    words |= NEGATIONS | COPULAS | set(ORDINALS) | ROBOT_WORDS | COMMON_WORDS | CONTAINING
    words |= MEASURE_WORDS
    words |= {verb for verb, _ in PARTICLE_VERBS}      # "fire (up)" is no typo of "file"
    return frozenset(words)


#: content words spelling correction may produce (never a function word: "there" must
#: not become "three")
@cache
def correction_targets(nouns_only: bool = False) -> frozenset[str]:
    words = set(noun_words()) | set(LIQUIDS)
    if not nouns_only:
        words |= set(VERBS) | set(STATES) | CONTAINING
    return frozenset(w for w in words if len(w) >= 3) - COMMON_WORDS

