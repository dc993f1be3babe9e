"""The words of the reading-level points of doubt: exclusions over a receptacle's
contents (:mod:`.contents`), exclusive purposes (:mod:`.exclusive`), a narrative's states stated as they should
be (``stated``: :mod:`.device_state`). Data (``rule_words.json``), checked at load by the schema below: a
malformed entry is a :class:`~emboteam.pfg.offline.knowledge.KnowledgeDataError` naming
the file and the entry.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache
from pathlib import Path
from typing import Literal

from pydantic import Field, field_validator

from emboteam.pfg.offline.knowledge import Strict as _Closed
from emboteam.pfg.offline.knowledge import known_types, read
from emboteam.pfg.offline.lexicon import Act
from emboteam.pfg.offline.tagger import Item

RULE_WORDS_FILE = Path(__file__).with_name("rule_words.json")

#: a sequence of words, matched on consecutive tokens ("apart from")
Words = list[str]


class Contents(_Closed):
    quantifiers: list[str]
    emptying_verbs: list[str]
    source_preps: list[str]
    pronoun_places: list[str]
    excluders: list[Words]
    #: excluders that follow their thing ("the knife excepted")
    post_excluders: list[Words]
    #: words that tie an excepted thing to its own place ("..., which goes in a drawer")
    own_place_links: list[str]
    #: prepositions of a landmark after a place ("the counter by the sink")
    landmark_preps: list[str]
    #: verbs that keep the thing just before them out of the set ("the soap stays")
    stay_verbs: list[str]
    trash_acts: list[str]
    trash_place: str
    #: quantifiers of what is left ("the rest", "everything else"): the things the
    #: reading places anywhere else are no part of the set
    remainder: list[str] = Field(default_factory=list)
    #: words that add named things to a keep just said ("... stays where it is, and so do
    #: the book and the bowl")
    stay_too: list[Words] = Field(default_factory=list)
    #: words that add a keep in a later sentence to the exceptions just said ("... except the
    #: soap. Wait, no, the spray stays out too")
    also_stays: list[Words] = Field(default_factory=list)
    #: pronoun places that name the source right after the quantifier ("everything there")
    pronoun_places_after: list[str] = Field(default_factory=list)
    #: pronoun adverbs that carry their own preposition and name the place said before
    #: anywhere in reach ("all items thereon", "whatever lies therein")
    pronoun_sources: list[str] = Field(default_factory=list)
    #: copulas: a "not" after one says what a thing is not ("the sponge is not food")
    copulas: list[str] = Field(default_factory=list)
    #: words that stand for the quantified whole's noun after an excluder ("every lamp but
    #: the desk one")
    pro_forms: list[str] = Field(default_factory=list)
    reach: int = Field(8, ge=1, le=30)
    note: str = ""


class Others(_Closed):
    #: words for the instances of a kind not singled out ("the other ones", "the spare")
    others: list[str]
    #: what stands before them ("the", "both")
    determiners: list[str]
    #: the words of them that open a clause with no determiner ("of the two, one stays")
    openers: list[str]
    #: keeping words after them ("stays", "where they are")
    keepers: list[str]
    #: prepositions of the place that names which ones ("the one on the holder stays")
    place_preps: list[str]


class Resumed(_Closed):
    #: quantified pronouns that take up the plural thing said before ("all of them")
    pronouns: list[Words]


class Cue(_Closed):
    words: Words = Field(min_length=1)
    #: where the thing kept on stands: before the cue, after it, either (after first), or
    #: the cue names it itself ("by the candle lit")
    kept: Literal["before", "after", "either", "inside"]
    #: verbs that, said before the cue in its sentence, make it an idiom of its own
    #: ("leave the candle alone": do not touch it, not "the candle alone on")
    not_after: list[str] = Field(default_factory=list)


class Exclusive(_Closed):
    cues: list[Cue]
    lights: list[str]
    screens: list[str]
    #: words that, before the cue in its sentence, make "only" restrictive ("turn off
    #: only the floor lamp"): no exclusive purpose (a verb of switching off counts too)
    restrictive: list[str]
    #: acts that, before an exception cue ("except", "apart from") in its sentence, make it an exception to that act
    #: ("everything on the counter goes in the drawers except the candle"): no purpose of light
    excepted_from: list[Act]
    #: words that do the same without a verb ("desk cleared: all of it into the drawers, except ...")
    excepted_from_words: list[str]
    reach: int = Field(6, ge=1, le=30)

    _known = field_validator("lights", "screens")(known_types)


class Stated(_Closed):
    #: words that make the instruction a narrative (:attr:`.context.DoubtContext.narrative`)
    narrative_cues: list[Words]


class Stays(_Closed):
    #: words that keep a thing as it is ("stays where it is", "leave the lamp on")
    keepers: list[str]


class Correction(_Closed):
    #: words that say a self-correction was made (the rules that keep away from its places:
    #: ``next_place``, :mod:`.destination`; the correction itself is read by ``pfg/offline/corrections.py``)
    cues: list[str]


class Contradiction(_Closed):
    #: words in or between two opposed requests that make the later one settle it (a
    #: self-correction, "sorry, I mean leave it on"; a rule, "if it is off it ought to be on")
    cues: list[str]


class Nouns(_Closed):
    """Words that make a mention of a thing where the tagger saw none (:mod:`.context`)."""
    #: words for the pieces of a thing cut up ("one slice in the toaster"): after a
    #: determiner or a number they name the slices of a thing the instruction names
    pieces: list[str]
    #: adjectives that only stand before a noun ("spare roll", "fresh roll"): a word that
    #: is also a verb names a thing right after one
    attributes: list[str]


class Undo(_Closed):
    #: words that ask to undo a move ("undo", "put it back", "the way it was")
    cues: list[Words]
    #: words before the place a thing was moved from or lived in ("from", "it lived on")
    sources: list[Words]
    #: how many words a source word may stand before its place
    lead: int = Field(3, ge=1, le=6)
    note: str = ""


class Compare(_Closed):
    """A thing singled out by comparison (:mod:`.compare`)."""
    #: comparatives and superlatives that pick the greatest mass ("heavier", "bigger")
    more: list[str]
    #: those that pick the least ("lighter", "smaller")
    less: list[str]
    #: words that may stand between the comparative and the name ("the bigger one")
    heads: list[str]
    #: what names the pool ("of the two", "from the two")
    pool_cues: list[Words]
    #: what leaves a thing out of the pool ("not the laptop")
    excluders: list[Words]
    #: what ends the clause of the thing picked ("the bigger goes in a cupboard; ...")
    clause_ends: list[str]
    #: keeping words after it: the others stay where they are ("the small one stays")
    keepers: list[str]
    note: str = ""


class RuleWords(_Closed):
    about: str = ""
    sentence_ends: list[str]
    nouns: Nouns
    contents: Contents
    others: Others
    resumed: Resumed
    exclusive: Exclusive
    stated: Stated
    stays: Stays
    correction: Correction
    contradiction: Contradiction
    undo: Undo
    compare: Compare


@cache
def load_rule_words(path: Path = RULE_WORDS_FILE) -> RuleWords:
    return read(path, RuleWords)


def starts_at(items: Sequence[Item], k: int, words: Words) -> bool:
    """Whether the tokens from ``k`` on are ``words``."""
    return k + len(words) <= len(items) and all(items[k + i].text == w for i, w in enumerate(words))


#: phrase list (by its words) -> its phrases by first word, so that a search looks only at
#: the phrases a token can start. Keyed by value, not by id(): callers also pass lists built
#: for the call, and a freed list's id is reused by the next one, which then found the old
#: list's phrases (readings that depended on what ran before in the process).
_BY_FIRST: dict[tuple[tuple[str, ...], ...], dict[str, list[Words]]] = {}


def _by_first(phrases: Sequence[Words]) -> dict[str, list[Words]]:
    key = tuple(map(tuple, phrases))    # map: no Python frame per phrase (a hot path)
    index = _BY_FIRST.get(key)
    if index is None:
        index = {}
        for words in phrases:
            index.setdefault(words[0], []).append(words)
        _BY_FIRST[key] = index
    return index


def find(items: Sequence[Item], lo: int, hi: int, phrases: Sequence[Words]) -> list[tuple[int, int]]:
    """(start, end) of every phrase found between ``lo`` and ``hi``, in order (the first
    phrase of the list that matches at a position)."""
    index = _by_first(phrases)
    out = []
    for k in range(lo, min(hi, len(items))):
        for words in index.get(items[k].text, ()):
            if starts_at(items, k, words):
                out.append((k, k + len(words)))
                break
    return out


def sentence_bounds(items: Sequence[Item], k: int) -> tuple[int, int]:
    """[start, end) of the sentence around position ``k`` (between sentence-ending marks)."""
    ends = set(load_rule_words().sentence_ends)
    start = k
    while start > 0 and items[start - 1].punct not in ends:
        start -= 1
    end = k
    while end < len(items) and items[end].punct not in ends:
        end += 1
    return start, end
