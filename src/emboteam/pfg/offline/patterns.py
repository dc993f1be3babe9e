"""Token patterns as data: the word sequences the grammar tests for ("there is", "do not"
+ verb, "why is/are", "a modal before a verb") are lists of token constraints in
``data/patterns.json``, as spaCy's Matcher patterns are (``{"LOWER": {"IN": [...]}}``,
``{"OP": "?"}``), interpreted here.

Written by hand rather than with spaCy's Matcher: the tokens are the tagger's
:class:`~emboteam.pfg.offline.tagger.Item` (a word with every reading it can have: noun,
verb form, preposition, state ...), which spaCy would need as custom extensions on a
``Doc`` built per clause, and the patterns are tested at one position many times per
instruction, where building a ``Doc`` would cost more than the whole parse (under 5 ms).
The interpreter is a few dozen lines; the constraints are spaCy's names where spaCy
has one (``LOWER``, ``OP``, ``IN``, ``NOT_IN``), the tagger's readings otherwise.

A pattern name has one or several alternative patterns (spaCy's ``Matcher.add(key,
[p1, p2])``); the first that matches at the position decides.
"""

from __future__ import annotations

from collections.abc import Callable
from operator import attrgetter
from typing import Literal

from pydantic import Field, model_validator

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.knowledge import KnowledgeDataError, Strict, WordTables, load, word_tables
from emboteam.pfg.offline.tagger import Item, VerbReading


class Words(Strict):
    """``{"IN": [...]}`` or ``{"NOT_IN": [...]}``: the item has the reading (a verb, a
    preposition ...) and its value is (not) among the words. A list may be ``"@table"``: the
    module's word table of that name in ``words.json``, or ``"@lexicon.name"``."""

    IN: tuple[str, ...] | str | None = None
    NOT_IN: tuple[str, ...] | str | None = None


#: a reading: present (true), absent (false), or its value among words
Reading = bool | Words | None


class Token(Strict):
    """One token's constraints (all must hold); ``OP`` as in spaCy: ``?`` optional, ``*``
    any number, ``+`` one or more, ``!`` not this; ``END``: no token left (zero width)."""

    LOWER: str | Words | None = None
    DET: bool | None = None
    NEG: bool | None = None
    COPULA: bool | None = None
    NOUN: Reading = None
    VERB: Reading = None
    PRON: Reading = None
    PREP: Reading = None
    PARTICLE: Reading = None
    STATE: Reading = None
    PUNCT: Reading = None
    CONJ: Reading = None
    NUMBER: Reading = None
    SEQ: Reading = None
    SUB: Reading = None
    ROBOT: Reading = None
    QUANT: Reading = None
    VERB_FORM: str | Words | None = None
    VERB_LEMMA: str | Words | None = None
    VERB_ACT: str | Words | None = None
    OP: Literal["?", "*", "+", "!"] | None = None
    END: bool | None = None


class Pattern(Strict):
    """Alternative token sequences; in a rule table also what a match decides (``then``),
    how many items it takes (``advance``) and a word that may not come just before it
    (``not_after``)."""

    why: str = ""
    patterns: tuple[tuple[Token, ...], ...]
    then: str = ""
    advance: int = 1
    not_after: Words | None = None
    #: the match may start this many words after the position, from .. to (a search window)
    within: tuple[int, int] = (0, 0)

    @model_validator(mode="after")
    def _not_empty(self) -> Pattern:
        if not self.patterns or any(not p for p in self.patterns):
            raise ValueError("a pattern needs at least one token")
        if not 0 <= self.within[0] <= self.within[1]:
            raise ValueError(f"within {list(self.within)}: from 0 up, and from <= to")
        return self


class ModulePatterns(Strict):
    """A module's named patterns and its rule tables (ordered: the first rule that
    matches decides)."""

    patterns: dict[str, Pattern] = Field(default_factory=dict)
    rules: dict[str, tuple[Pattern, ...]] = Field(default_factory=dict)


class PatternsFile(Strict):
    """``data/patterns.json``: token patterns and rule tables by module."""

    about: str = ""
    modules: dict[str, ModulePatterns]


def _words(value: str | Words, tables: WordTables) -> tuple[frozenset[str], bool]:
    """The word set of a constraint and whether it must hold (IN) or not (NOT_IN)."""
    if isinstance(value, str):
        return frozenset((value,)), True
    raw, inside = (value.IN, True) if value.IN is not None else (value.NOT_IN or (), False)
    if isinstance(raw, str) and raw.startswith("@lexicon."):
        name = raw.removeprefix("@lexicon.").upper()
        if not isinstance(getattr(lx, name, None), frozenset | tuple | dict):
            raise KnowledgeDataError(PatternTables.FILE, raw, "the lexicon has no such word list")
        return frozenset(getattr(lx, name)), inside
    if isinstance(raw, str):
        return tables.set(raw.removeprefix("@")), inside
    return frozenset(raw), inside


#: a compiled token: does the item meet every constraint?
Check = Callable[[Item], bool]
_FLAGS = frozenset({"det", "neg", "copula"})
_VERB_PARTS: dict[str, Callable[[VerbReading], str]] = {
    "verb_form": attrgetter("form"), "verb_lemma": attrgetter("lemma"), "verb_act": lambda v: v.sense.act.value}


def _check(attr: str, words: frozenset[str] | None, want: bool) -> Check:
    """One constraint as a test of an item (closures: the patterns are tested many times
    per instruction)."""
    if words is None:
        if attr in _FLAGS:
            return lambda it: bool(getattr(it, attr)) is want
        return lambda it: (getattr(it, attr) is not None) is want
    if attr == "lower":
        return lambda it: (it.text in words) is want
    if attr in _VERB_PARTS:
        part = _VERB_PARTS[attr]
        return lambda it: it.verb is not None and (part(it.verb) in words) is want
    return lambda it: (v := getattr(it, attr)) is not None and (v in words) is want


def _compile(token: Token, tables: WordTables) -> tuple[Check, frozenset[str] | None]:
    """The token's test, and the words its item must be one of when it says (else None)."""
    checks: list[Check] = []
    first: frozenset[str] | None = None
    for name, value in token:
        if value is None or name in ("OP", "END"):
            continue
        words, want = (None, value) if isinstance(value, bool) else _words(value, tables)
        checks.append(_check(name.lower(), words, want))
        first = words if name == "LOWER" and want else first

    def check(item: Item) -> bool:
        for one in checks:  # noqa: SIM110 (a loop, not all(): no generator per item)
            if not one(item):
                return False
        return True

    return (checks[0] if len(checks) == 1 else check), first


class Compiled:
    """One alternative, ready to match: each token's test, its OP and whether it is END."""

    def __init__(self, tokens: tuple[Token, ...], tables: WordTables) -> None:
        compiled = [_compile(t, tables) for t in tokens]
        self.steps = tuple((check, t.OP, bool(t.END)) for (check, _), t in zip(compiled, tokens, strict=True))
        #: the words the first item must be one of (None: any), to refuse most positions at once
        self.first = compiled[0][1] if tokens[0].OP is None and not tokens[0].END else None
        #: the test of an alternative of one plain token (a quarter of them), else None:
        #: matched without the general walk
        self.one = compiled[0][0] if len(tokens) == 1 and tokens[0].OP is None and not tokens[0].END else None

    def end(self, items: list[Item], j: int) -> int | None:
        """The index after the match at ``items[j]``, or None. ``?``, ``*`` and ``+`` take
        every item they can and never give one back (a possessive quantifier): the grammar's
        word tests look ahead that way."""
        n = len(items)
        if self.one is not None:
            return j + 1 if j < n and self.one(items[j]) else None
        for check, op, at_end in self.steps:
            if op is None and not at_end:
                if j >= n or not check(items[j]):
                    return None
                j += 1
            elif at_end:
                if j != n:
                    return None
            elif op in ("*", "+"):
                start = j
                while j < n and check(items[j]):
                    j += 1
                if op == "+" and j == start:
                    return None
            elif op == "?":
                j += 1 if j < n and check(items[j]) else 0
            elif j >= n or check(items[j]):     # "!": any item but one that fits
                return None
            else:
                j += 1
        return j


class Rule:
    """A compiled pattern and what a match decides."""

    def __init__(self, pattern: Pattern, tables: WordTables) -> None:
        self.alternatives = tuple(Compiled(p, tables) for p in pattern.patterns)
        self.then, self.advance = pattern.then, pattern.advance
        self.offsets = range(pattern.within[0], pattern.within[1] + 1)
        self.here = pattern.within == (0, 0)
        self.not_after = _words(pattern.not_after, tables) if pattern.not_after is not None else None
        # the alternatives that may match at a word, in their order, by the word (any other
        # word: ``self.any_word``): most positions are refused by one dict look-up
        self.any_word = tuple(a for a in self.alternatives if a.first is None)
        firsts = {w for a in self.alternatives if a.first is not None for w in a.first}
        self.by_word = {w: tuple(a for a in self.alternatives if a.first is None or w in a.first) for w in firsts}

    def end(self, items: list[Item], j: int = 0) -> int | None:
        """The index after the first alternative that matches at ``items[j]`` (or in the
        window after it), or None."""
        if self.here:
            return self._end(items, j)
        return next((e for k in self.offsets if (e := self._end(items, j + k)) is not None), None)

    def _end(self, items: list[Item], j: int) -> int | None:
        if self.not_after is not None and j > 0 and (items[j - 1].text in self.not_after[0]) is self.not_after[1]:
            return None
        n = len(items)
        word = items[j].text if j < n else None
        for alternative in self.by_word.get(word, self.any_word) if word is not None else self.any_word:
            one = alternative.one
            if one is not None:     # :meth:`Compiled.end`'s plain token, without its call
                if j < n and one(items[j]):
                    return j + 1
                continue
            end = alternative.end(items, j)
            if end is not None:
                return end
        return None

    def at(self, items: list[Item], j: int = 0) -> bool:
        return (self._end(items, j) if self.here else self.end(items, j)) is not None


class PatternTables:
    """The patterns and rule tables of one module; one the module asks for and the file
    lacks is a :class:`KnowledgeDataError` at import, as is a ``@table`` the words file
    lacks."""

    FILE = "patterns.json"

    def __init__(self, module: str) -> None:
        self.module = module
        words = word_tables(module)
        data = load(self.FILE, PatternsFile).modules.get(module, ModulePatterns())
        self.patterns = {name: Rule(p, words) for name, p in data.patterns.items()}
        self.rules = {name: tuple(Rule(p, words) for p in table) for name, table in data.rules.items()}

    def _missing(self, kind: str, name: str) -> KnowledgeDataError:
        return KnowledgeDataError(self.FILE, f"modules -> {self.module!r} -> {kind} -> {name!r}",
                                  f"missing: the module {self.module} needs it")

    def pattern(self, name: str) -> Rule:
        if name not in self.patterns:
            raise self._missing("patterns", name)
        return self.patterns[name]

    def table(self, name: str) -> tuple[Rule, ...]:
        if name not in self.rules:
            raise self._missing("rules", name)
        return self.rules[name]


def first_rule(table: tuple[Rule, ...], items: list[Item], j: int) -> Rule | None:
    """The first rule of ``table`` that matches at ``items[j]``."""
    return next((r for r in table if r.end(items, j) is not None), None)


def pattern_tables(module: str) -> PatternTables:
    return PatternTables(module)
