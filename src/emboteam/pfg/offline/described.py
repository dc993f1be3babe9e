"""Things named by use, look or a landmark, not by name: "the thing you boil water in",
"the round one you eat cereal from", "the plastic disc", "the roll by the soap stays".
``data/described.json`` knows, per AI2-THOR type, its name, uses and looks; the code knows
the shape of a description (determiner, head, relative clause, use, preposition) and
inflects a use's first word. The scene picks among types sharing a use (a plural head
takes each it has); the name replaces the description before the reader reads the text.
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
#: verbs of where a thing is, not what it is for ("the paper that lies on the floor")
_POSTURES = frozenset({"lie", "lies", "lying", "lay", "sit", "sits", "sitting", "sat", "stand", "stands",
                       "standing", "stood", "rest", "rests", "resting", "hang", "hangs", "hanging"})
#: a noun and a comma, dash or bracket right before "the one ...": an aside about that noun
_APPOSED = re.compile(r"[a-z]\s*[,(\-\u2013\u2014]\s*$", re.IGNORECASE)
#: heads that name many things at once: each type the scene has for the use
_PLURAL_HEADS = frozenset({"things", "thingies", "ones", "tools", "stuff"})


class Thing(Strict):
    """A type, the name the lexicon knows it by and what people use it for."""
    type: str
    name: str
    uses: tuple[str, ...]
    _types = field_validator("type")(lambda cls, v: known_types([v])[0])


class Look(Thing):
    """A type and the descriptions of its look that name it after a determiner."""
    uses: tuple[str, ...] = ()
    words: tuple[str, ...]


class Relations(Strict):
    """The words of a relation, and the verbs after it or destinations that show it only
    names the thing."""
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
    """A use as a regular expression: first word inflected, a determiner for any (or none),
    "me" for any object pronoun; a trailing preposition (the tool's, the place's) is the
    group ``prep``, which "the thing that boils water", "for cutting" leave out."""
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


def _alt(words: Collection[str]) -> str:
    return "|".join(sorted(map(re.escape, words), key=len, reverse=True))


@cache
def _data() -> tuple[DescribedFile, re.Pattern[str], tuple[tuple[re.Pattern[str], str, bool, bool], ...],
                     re.Pattern[str], dict[str, tuple[str, str]]]:
    data = load("described.json", DescribedFile)
    heads = _alt(data.heads)
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
    looks = {w.lower(): (look.type, look.name) for look in data.looks for w in look.words}
    look = re.compile(rf"\b(?:the|that|this|a|an|my|your) ({_alt(looks)})\b", re.IGNORECASE)
    return data, description, uses, look, looks


@cache
def _relation_patterns() -> tuple[re.Pattern[str], re.Pattern[str], re.Pattern[str]]:
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
    return named, aside, re.compile(rf"\b(?:{_alt(rel.words)}) ", re.IGNORECASE)


def _named_by_relation(text: str) -> str:
    """The relation that only names a thing dropped: the landmark is where it is."""
    named, aside, gate = _relation_patterns()
    return named.sub(lambda m: m.group(1), aside.sub(" ", text)) if gate.search(text) else text


#: load and compile the tables ahead of the first instruction
warm_described = _relation_patterns


def _pick(types: list[str], scene_types: Collection[str] | None, plural: bool) -> list[str]:
    """Each type the scene has of those a description fits when the head is plural, else
    the first (table order); without a scene, any."""
    present = [t for t in dict.fromkeys(types) if scene_types is None or t in scene_types]
    return present if plural else present[:1]


def _described_by_use(text: str, scene_types: Collection[str] | None) -> str:
    data, description, uses, _, _ = _data()
    names = {t.type: t.name for t in data.things}
    out: list[str] = []
    at = 0
    for m in description.finditer(text):
        if m.start() < at:
            continue
        best_end, types = -1, []
        # "the one standing by ...": no description without a relative pronoun, a user or a purpose
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
        if chosen:
            out.append(text[at:m.start()] + " and ".join(f"the {names[t]}" for t in chosen))
            at = best_end
    out.append(text[at:])
    return "".join(out)


def name_described(text: str, scene_types: Collection[str] | None = None) -> str:
    """Each thing described by its use or look named (for the scene's types when given),
    and with a scene, each landmark that only says where a thing is dropped."""
    text = _described_by_use(text, scene_types)
    *_, look, looks = _data()

    def named(m: re.Match[str]) -> str:    # "the plastic disc" -> "the cd"
        type_, name = looks[m.group(1).lower()]
        return f"the {name}" if scene_types is None or type_ in scene_types else m.group(0)

    text = look.sub(named, text)
    return _named_by_relation(text) if scene_types is not None else text
