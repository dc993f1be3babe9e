"""Tagging: tokens -> items, each a word or a multi-word unit with every reading it can
have (a noun, a verb, a state word, a preposition ...). The clause parser picks one
reading from the context: "microwave" is a verb at the start of a clause and a noun after
"the".

Multi-word units are matched longest first: noun phrases of the lexicon ("coffee table",
"toilet paper holder", plurals included), prepositions ("on top of"), sequence markers
("after that") and robot names ("robot 2", "the second robot"). Typos are corrected here,
once, so everything downstream sees lexicon words.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.force import read_force
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.morphology import (
    correct,
    is_english_word,
    singular,
    singular_candidates,
    unswap,
    verb_lemma,
)
from emboteam.pfg.offline.text import PUNCT, tokenize


@dataclass(frozen=True, slots=True)
class NounReading:
    concept: lx.Concept
    phrase: str
    plural: bool
    #: "a slice of bread", "apple slices": the pieces, not the whole
    piece: bool = False


@dataclass(frozen=True, slots=True)
class VerbReading:
    lemma: str
    form: str   # base | ing | ed | s
    sense: lx.VerbSense


@dataclass(slots=True)
class Item:
    """One word or multi-word unit with all its possible readings."""

    text: str
    noun: NounReading | None = None
    verb: VerbReading | None = None
    state: tuple[lx.Stat, bool] | None = None
    prep: str | None = None
    particle: str | None = None
    number: int | None = None
    det: bool = False
    quant: str | None = None
    pron: str | None = None
    neg: bool = False
    copula: bool = False
    punct: str | None = None
    #: "robot 2" -> ("number", 2); "the second robot" -> ("ordinal", 2); "last" -> ("ordinal", -1)
    robot: tuple[str, int] | None = None
    liquid: str | None = None
    recipe: str | None = None
    seq: str | None = None            # a sequence marker ("then", "after that")
    sub: str | None = None            # a subordinator relation (after/before/while/...)
    conj: str | None = None           # and / or
    ordinal: int | None = None
    corrected_from: str | None = None
    extra: dict[str, str] = field(default_factory=dict)

    def is_content(self) -> bool:
        return self.noun is not None or self.verb is not None or self.state is not None

    def __repr__(self) -> str:
        tags = [k for k in ("noun", "verb", "state", "prep", "particle", "number", "quant",
                            "pron", "punct", "robot", "liquid", "recipe", "seq", "sub", "conj")
                if getattr(self, k) not in (None, False)]
        tags += ["det"] if self.det else []
        tags += ["neg"] if self.neg else []
        tags += ["cop"] if self.copula else []
        return f"{self.text}<{','.join(tags)}>"


_MAX_SPAN = 5


def _noun_at(words: list[str], i: int) -> tuple[int, NounReading] | None:
    """The longest noun phrase of the lexicon starting at ``words[i]``."""
    table = lx.nouns()
    longest = min(_MAX_SPAN, len(words) - i)
    # no span runs over punctuation: the longest ends before the first mark
    longest = next((k for k in range(longest) if words[i + k] in PUNCT), longest)
    for n in range(longest, 0, -1):
        span = words[i:i + n]
        phrase = " ".join(span)
        if phrase in lx.PLURAL_NOUNS:
            return n, NounReading(lx.PLURAL_NOUNS[phrase], phrase, True)
        if phrase in table:
            return n, NounReading(table[phrase], phrase, False)
        for last in singular_candidates(span[-1])[:-1]:
            phrase = " ".join([*span[:-1], last])
            if phrase in table:
                return n, NounReading(table[phrase], phrase, True)
        if n >= 3 and span[1] == "of":
            # "two bottles of wine", "loaves of bread": the measure word is the plural one
            for first in singular_candidates(span[0])[:-1]:
                for last in singular_candidates(span[-1]):
                    phrase = " ".join([first, *span[1:-1], last])
                    if phrase in table:
                        return n, NounReading(table[phrase], phrase, True)
    return None


def _multi(words: list[str], i: int, phrases: dict[str, str] | tuple[str, ...],
           sizes: tuple[int, ...] = (4, 3, 2)) -> tuple[int, str] | None:
    for n in sizes:
        if len(words) - i < n:
            continue
        phrase = " ".join(words[i:i + n])
        if phrase in phrases:
            return n, phrase
    return None


_W = word_tables("tagger")
#: words after which a clause's verb comes
_CLAUSE_OPENERS = _W.set("clause_openers")
#: "turn of the tv": after these, "of" is a typo of "off"
_SWITCHING = _W.set("switching")


def _repair(words: list[str]) -> tuple[list[str], dict[int, str]]:
    """Join words split by a space ("micro wave") and correct typos ("frigde")."""
    vocab = lx.vocabulary()
    out: list[str] = []
    fixed: dict[int, str] = {}
    i = 0
    while i < len(words):
        w = words[i]
        if i + 1 < len(words) and w not in PUNCT:
            joined = w + words[i + 1]
            if joined in lx.noun_words() and (w not in vocab or words[i + 1] not in vocab):
                out.append(joined)
                i += 2
                continue
        if w not in vocab and not w.isdigit() and w not in PUNCT \
                and not singular(w, lx.noun_words())[1] and w not in lx.PLURAL_NOUNS:
            after_det = bool(out) and (out[-1] in lx.DETERMINERS or out[-1] in lx.NUMBERS
                                       or out[-1].isdigit())
            # a real English word is a typo only where the lexicon's words stand: an object
            # after a determiner ("the coach"), a verb starting a clause ("brake the egg");
            # elsewhere it is a word the parser does not need ("I keep losing my keys")
            slot = after_det or not out or out[-1] in PUNCT or out[-1] in _CLAUSE_OPENERS
            real = not slot and is_english_word(w)
            fix = unswap(w) or (None if real else correct(w, after_det))
            if fix is None and not real and w.endswith("s"):
                stem = correct(w[:-1], after_det)
                fix = stem + "s" if stem is not None else None
            if fix is not None and verb_lemma(w) is None:
                fixed[len(out)] = w
                w = fix
        out.append(w)
        i += 1
    # "turn of the tv": "of" right after a switching verb is "off"
    for k in range(len(out) - 1):
        if out[k] in _SWITCHING and out[k + 1] == "of":
            out[k + 1] = "off"
    return out, fixed


def _same(words: frozenset[str]) -> dict[str, str]:
    return {w: w for w in words}


#: the readings a single word has by its table: the item's field and the table, word -> value
_READINGS: tuple[tuple[str, dict[str, Any]], ...] = (
    ("state", lx.STATES), ("prep", lx.PREPOSITIONS), ("particle", _same(lx.PARTICLES)),
    ("number", lx.NUMBERS), ("quant", _same(lx.QUANTIFIERS)), ("pron", _same(lx.PRONOUNS)),
    ("punct", _same(PUNCT)), ("liquid", _same(lx.LIQUIDS)), ("sub", lx.SUBORDINATORS),
    ("conj", lx.CONJUNCTIONS), ("ordinal", lx.ORDINALS))
#: the yes-or-no readings of a word: the item's field and its words
_FLAGS = (("det", lx.DETERMINERS), ("neg", lx.NEGATIONS), ("copula", lx.COPULAS))


def _collective(reading: NounReading) -> NounReading:
    """"the cutlery": a collective noun is every piece of it, as a plural."""
    if reading.phrase in lx.MASS_NOUNS and not reading.plural:
        return NounReading(reading.concept, reading.phrase, True, reading.piece)
    return reading


#: the lexicon's idioms, compiled once
_IDIOMS = tuple((re.compile(pattern), repl) for pattern, repl in lx.IDIOMS)


def tag(text: str) -> list[Item]:
    """Items of an instruction, in order."""
    normal = read_force(" ".join(t.text for t in tokenize(text)))
    for pattern, repl in _IDIOMS:
        normal = pattern.sub(repl, normal)
    words, fixed = _repair(normal.split())
    items: list[Item] = []
    i = 0
    while i < len(words):
        noun = _noun_at(words, i)
        item, n = _robot_at(words, i) or _unit_at(words, i, noun) or (_word(words[i], fixed.get(i), noun), 1)
        items.append(item)
        i += n
    return _place_not_switch(items)


def _robot_at(words: list[str], i: int) -> tuple[Item, int] | None:
    """A robot's name at ``i``: "robot 2", "robot number two", "the second robot"."""
    w = words[i]
    if w in lx.ROBOT_WORDS and i + 1 < len(words):
        k = 2 if words[i + 1] in ("number", "no", "nr") and i + 2 < len(words) else 1
        nxt = words[i + k] if i + k < len(words) else ""
        num = int(nxt) if nxt.isdigit() else lx.NUMBERS.get(nxt) if nxt in (
            "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten") else None
        if num is not None:
            return Item(f"robot {num}", robot=("number", num)), k + 1
    if w in lx.ORDINALS and i + 1 < len(words) and words[i + 1] in ("robot", "bot", "agent"):
        return Item(f"{w} robot", robot=("ordinal", lx.ORDINALS[w])), 2
    return None


#: the prepositions and subordinators of several words (the lexicon's tables are fixed at
#: import: found once, not per word)
_MULTI_WORD_PREPS = {p: p for p in lx.PREPOSITIONS if " " in p}
_MULTI_WORD_SUBS = {s: s for s in lx.SUBORDINATORS if " " in s}


def _unit_at(words: list[str], i: int, noun: tuple[int, NounReading] | None) -> tuple[Item, int] | None:
    """A unit of several words at ``i``: a preposition ("on top of", unless a longer noun
    starts there), a subordinator, a sequence marker ("after that"), a noun phrase."""
    prep = _multi(words, i, _MULTI_WORD_PREPS)
    if prep is not None and (noun is None or prep[0] >= noun[0]):
        return Item(prep[1], prep=lx.PREPOSITIONS[prep[1]]), prep[0]
    sub = _multi(words, i, _MULTI_WORD_SUBS, (3, 2))
    if sub is not None:
        return Item(sub[1], sub=lx.SUBORDINATORS[sub[1]]), sub[0]
    seq = _multi(words, i, lx.SEQUENCE_MARKERS, (4, 3, 2, 1))
    if seq is not None and seq[1] != "after":
        return Item(seq[1], seq=seq[1]), seq[0]
    if noun is not None and noun[0] > 1:
        n, reading = noun[0], _collective(noun[1])
        phrase = " ".join(words[i:i + n])
        return Item(phrase, noun=reading, recipe=lx.RECIPES.get(phrase) or lx.RECIPES.get(reading.phrase)), n
    return None


def _word(w: str, corrected_from: str | None, noun: tuple[int, NounReading] | None) -> Item:
    """One word with every reading the lexicon gives it."""
    item = Item(w, corrected_from=corrected_from, noun=_collective(noun[1]) if noun else None,
                recipe=lx.RECIPES.get(w))
    vl = verb_lemma(w)
    if vl is not None and vl[0] in lx.VERBS:
        item.verb = VerbReading(vl[0], vl[1], lx.VERBS[vl[0]])
    for name, table in _READINGS:
        if w in table:
            setattr(item, name, table[w])
    for name, flagged in _FLAGS:
        setattr(item, name, w in flagged)
    if w.isdigit() and int(w) > 0:     # "0 sugar" asks for none of a thing: no count
        item.number = int(w)
    return item


def _place_not_switch(items: list[Item]) -> list[Item]:
    """"turn the tap on to rinse it": "on to" before a verb is the particle and an
    infinitive, not "onto"; "once it's on there": "on" before "there"/"here" is a place,
    not switched on."""
    out: list[Item] = []
    for k, it in enumerate(items):
        nxt = items[k + 1] if k + 1 < len(items) else None
        if it.text == "on to" and nxt is not None and nxt.verb is not None and nxt.noun is None:
            out.extend(tag("on") + tag("to"))
            continue
        if it.text == "on" and nxt is not None and nxt.text in ("there", "here"):
            it.state = None
            it.particle = None
        out.append(it)
    return out
