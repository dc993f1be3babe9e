"""Things named by their use or their look, not by their name: "the thing you boil water
in", "the thing I pay with", "the round one you eat cereal from", "everything I write
with", "the thing over the window that lets the light in", "the plastic disc".

The knowledge is ``data/described.json``: per AI2-THOR type, the name the lexicon knows
it by, the uses a person says of it and the looks that name it. The code only knows the
shape of such a description (a determiner, a head like "thing" or "one", an optional
place, a relative clause with or without its subject, the use, a trailing preposition)
and inflects the use's first word. The scene settles which of the types sharing a use is
meant ("the thing I write with": a pen where there is one, else a pencil); a plural head
("everything I write with") names every such type the scene has. The description is
rewritten to the name before the reader reads the text, so the grammar never sees it.
"""

from __future__ import annotations

import re
from collections.abc import Collection
from functools import cache

from pydantic import field_validator

from emboteam.pfg.offline.knowledge import Strict, known_types, load

#: words a use writes for "any determiner" and "any object pronoun"
_DETERMINERS = ("the", "a", "an", "my", "your", "our", "his", "her", "their", "some")
_PRONOUNS = ("me", "you", "us", "him", "her", "them")
_PREPOSITIONS = ("with", "in", "into", "on", "onto", "from", "out of", "off", "by", "at", "to", "under",
                 "against", "in front of")
#: who uses it: "the thing (that) you/I/we ... "
_SUBJECTS = r"(?:you|i|we|u|people|they|he|she|one|my (?:mum|dad|wife|husband|partner|son|daughter|kids))"
#: heads that name many things at once: each type the scene has for the use
#: verbs of where a thing is, not what it is for ("the paper that lies on the floor")
_POSTURES = frozenset({"lie", "lies", "lying", "lay", "sit", "sits", "sitting", "sat", "stand", "stands",
                       "standing", "stood", "rest", "rests", "resting", "hang", "hangs", "hanging"})
#: a noun and a comma, dash or bracket right before "the one ...": an aside about that noun
_APPOSED = re.compile(r"[a-z]\s*[,(\-\u2013\u2014]\s*$", re.IGNORECASE)
_PLURAL_HEADS = frozenset({"things", "thingies", "ones", "tools", "stuff"})


class Thing(Strict):
    """A type, the name the lexicon knows it by and what people use it for."""

    type: str
    name: str
    uses: tuple[str, ...]

    _types = field_validator("type")(lambda cls, v: known_types([v])[0])


class Look(Strict):
    """A type and the descriptions of its look that name it after a determiner."""

    type: str
    name: str
    words: tuple[str, ...]

    _types = field_validator("type")(lambda cls, v: known_types([v])[0])


class Relations(Strict):
    """A thing named by what it is next to: the words of the relation, the verbs after a
    subject and the prepositions of a destination that show the relation only names it."""

    why: str = ""
    words: tuple[str, ...]
    subject_verbs: tuple[str, ...]
    destinations: tuple[str, ...]


class DescribedFile(Strict):
    """``data/described.json``."""

    about: str = ""
    #: the nouns a description is built on ("the thing", "the one", "the bottle that ...")
    heads: tuple[str, ...]
    things: tuple[Thing, ...]
    looks: tuple[Look, ...]
    relations: Relations


def _inflected(word: str) -> str:
    """A verb's forms: "boil" -> boil, boils, boiled, boiling; "make" -> makes, making."""
    if word.endswith("e") and len(word) > 2:
        return rf"{word[:-1]}(?:e|es|ed|ing)"
    if word.endswith("y") and len(word) > 2 and word[-2] not in "aeiou":
        return rf"{word[:-1]}(?:y|ies|ied|ying)"
    return rf"{word}(?:s|es|ed|ing|{word[-1]}ing|{word[-1]}ed)?"


def _use_pattern(use: str) -> str:
    """A use as a regular expression: its first word inflected, a determiner for any
    determiner (or none), "me" for any object pronoun; a trailing preposition (the thing
    as the tool or place of the use) is the group ``prep``, left out where the thing is
    what does it ("the thing that boils water") or what it is for ("for cutting")."""
    words = use.split()
    prep = next((p for p in sorted(_PREPOSITIONS, key=len, reverse=True) if use.endswith(f" {p}")), None)
    if prep:
        words = words[:-len(prep.split())]
    out: list[str] = []
    for k, word in enumerate(words):
        if word in _DETERMINERS:
            out.append(rf"(?:(?:{'|'.join(_DETERMINERS)}) )?")
        elif word in _PRONOUNS:
            out.append(rf"(?:{'|'.join(_PRONOUNS)}) ")
        else:
            out.append((_inflected(word) if k == 0 else re.escape(word)) + " ")
    body = "".join(out).rstrip()
    # "the one you cut in half" is the thing cut, not the knife
    return body + (rf"(?P<prep> {re.escape(prep)}\b(?! half| halves| two| pieces| slices| bits| quarters))?" if prep else "") + r"\b"


@cache
def _data() -> tuple[DescribedFile, re.Pattern[str], tuple[tuple[re.Pattern[str], str, bool, bool], ...],
                     tuple[tuple[re.Pattern[str], str, str], ...]]:
    data = load("described.json", DescribedFile)
    heads = "|".join(sorted(map(re.escape, data.heads), key=len, reverse=True))
    # "the (round) thing (over the window) (that|which) (you) (use) (to|for) ...": not after a
    # quantifier ("everything I write with", "all the stuff that runs on electricity" are
    # properties of many things: doubts/properties.py reads them)
    description = re.compile(
        rf"\b(?<!all )(?:the|that|this|a|an|those|these|my|your) (?:([a-z]+) )?({heads})"
        rf"(?: (?:over|on|by|above|under|near|in|at) (?:the |a |my )?[a-z]+(?= that| which))?"
        rf"( that| which)?(?: ({_SUBJECTS}))?(?: (use|uses|need|needs|have|has)(?: to)?)?"
        rf"( to| for)? ", re.IGNORECASE)
    uses = tuple((re.compile(_use_pattern(u), re.IGNORECASE), t.type, u.endswith(_PREPOSITIONS),
                  (len(u.split()) <= 2 and u.endswith(_PREPOSITIONS)) or len(u.split()) == 1)
                 for t in data.things for u in t.uses)
    looks = tuple((re.compile(rf"\b(?:the|that|this|a|an|my|your) {re.escape(w)}\b", re.IGNORECASE), look.type, look.name)
                  for look in data.looks for w in look.words)
    return data, description, uses, looks


def _alt(words: Collection[str]) -> str:
    return "|".join(sorted(map(re.escape, words), key=len, reverse=True))


@cache
def _relation_patterns() -> tuple[re.Pattern[str], re.Pattern[str]]:
    """"(the roll) by the soap (stays)", "(the knife) next to the kettle (into a drawer)";
    "- the one standing by the wine -" after a noun."""
    rel = _data()[0].relations
    # a noun phrase's words: none of the relation's, a verb's or a preposition's
    word = rf"(?!(?:{_alt({*rel.words, *rel.subject_verbs, *rel.destinations, 'to', 'next', 'and', 'or', 'put'})})\b)[a-z]+"
    landmark = rf"(?:the|a|an|my|your|our|his|her|their|that|this) {word}(?: {word})?"
    relation = (rf"(?:,? (?:the one |which is |that is |that's |which's )?(?:standing |sitting |lying |resting )?)?"
                rf"(?:{_alt(rel.words)}) {landmark}")
    named = re.compile(
        rf"((?:^|[.!?;:,(/\n]|\band|\bthen|\bbut|\balso|\bplus|\bput|\bmove|\btake|\bbring|\bleave|\bget|\bset|\bstick|\bpop)\s*"
        rf"(?:the|my|your|our|that|this|those|these) (?:{word} ){{0,2}}?{word})(?<!\bone)({relation})"
        rf"(?=,? (?:{_alt(rel.subject_verbs)})\b| (?:{_alt(rel.destinations)}) (?:the|a|an|my|your|our|its|their)\b)",
        re.IGNORECASE)
    aside = re.compile(rf"\s+[-\u2013\u2014,]\s*the one (?:that is |which is |that's |which's )?"
                       rf"(?:standing |sitting |lying |resting )?(?:{_alt(rel.words)}) {landmark}\s*[-\u2013\u2014,]\s*",
                       re.IGNORECASE)
    return named, aside


def _named_by_relation(text: str) -> str:
    """The relation that only names a thing dropped: the landmark is where it is."""
    named, aside = _relation_patterns()
    return named.sub(lambda m: m.group(1), aside.sub(" ", text))


def warm_described() -> None:
    """Load and compile the table ahead of the first instruction."""
    _data()
    _relation_patterns()


def _names() -> dict[str, str]:
    return {t.type: t.name for t in _data()[0].things}


def _pick(types: list[str], scene_types: Collection[str] | None, plural: bool) -> list[str]:
    """The types a description names in this scene: every one the scene has when the
    head is plural, else the first the scene has (table order); none when it has none
    (without a scene: the table's first)."""
    present = [t for t in dict.fromkeys(types) if scene_types is None or t in scene_types]
    return present if plural else present[:1]


def _described_by_use(text: str, scene_types: Collection[str] | None) -> str:
    _, description, uses, _ = _data()
    names = _names()
    out: list[str] = []
    at = 0
    for m in description.finditer(text):
        if m.start() < at:
            continue
        best_end, types = -1, []
        # "the one standing by ...", "the one cut in half": no description without a
        # relative pronoun, a person using it or a purpose
        if not any(m.group(k) for k in (3, 4, 5, 6)):
            continue
        head = (m.group(2) or "").lower()
        # "the chair - the one I sit on": an aside that picks one of a thing already named
        if head in ("one", "ones") and _APPOSED.search(text, 0, m.start()):
            continue
        # "the thing you cut bread with": said of a person, a tool or a place keeps its preposition
        said_of_user = m.group(4) is not None and m.group(5) is None
        # "the thing that flips" / "that lies on the floor": a bare verb or a posture said of
        # the thing itself is no use (switches are flipped too; a thing lies where it is)
        said_of_itself = m.group(4) is None and m.group(5) is None and m.group(6) is None
        for pattern, type_, tool, bare in uses:
            u = pattern.match(text, m.end())
            if u is None or (said_of_user and tool and u.group("prep") is None) \
                    or (said_of_itself and bare and (tool or u.group(0).split()[0].lower() in _POSTURES)):
                continue
            if u.end() > best_end:
                best_end, types = u.end(), [type_]
            elif u.end() == best_end:
                types.append(type_)
        if not types:
            continue
        chosen = _pick(types, scene_types, head in _PLURAL_HEADS)
        if not chosen:
            continue
        out.append(text[at:m.start()])
        out.append(" and ".join(f"the {names.get(t, t.lower())}" for t in chosen))
        at = best_end
    out.append(text[at:])
    return "".join(out)


def _described_by_look(text: str, scene_types: Collection[str] | None) -> str:
    """"the plastic disc" -> "the cd": only where the scene has the thing it looks like."""
    for pattern, type_, name in _data()[3]:
        if scene_types is None or type_ in scene_types:
            text = pattern.sub(f"the {name}", text)
    return text


def name_described(text: str, scene_types: Collection[str] | None = None) -> str:
    """The text with each thing described by its use or look replaced by its name (for
    the scene's types when given; without a scene, by the table's first type)."""
    text = _described_by_look(_described_by_use(text, scene_types), scene_types)
    return _named_by_relation(text) if scene_types is not None else text
