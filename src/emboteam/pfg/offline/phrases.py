"""Noun phrases and the structures the clause grammar fills: a noun phrase (``Head``)
with its count, adjectives, where it is and what it holds; an object with its
destination (``Target``); an act with its objects (``Frame``); a parsed clause.

``parse_np`` reads one noun phrase: determiners, numbers and quantifiers ("all three",
"both of them", "the lot"), measure words ("two rolls of foil", "a head of lettuce"),
pieces ("a slice of bread"), adjectives, and a relative clause that picks the object
out ("the cabinet it's in", "the mug that is dirty", "the apple that is in the fridge").
The place helpers tell a place that describes a noun phrase ("the lettuce sitting on the
counter") from a destination.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.clauses import Clause
from emboteam.pfg.offline.tagger import Item, NounReading

Act = lx.Act
Stat = lx.Stat


@dataclass
class Head:
    """A noun phrase: what it names and how many."""

    text: str = ""
    noun: NounReading | None = None
    pron: str | None = None
    count: int | None = None
    vague_count: bool = False
    quant: str | None = None
    definite: bool = False
    plural: bool = False
    piece: bool = False
    ordinal: int | None = None
    filters: list[tuple[Stat, bool]] = field(default_factory=list)
    #: where it is: ("in", landmark) from "the apple in the fridge", "from the dresser"
    location: list[tuple[str, Head]] = field(default_factory=list)
    #: the phrase names a liquid ("water", "some coffee", "the wine")
    liquid: str | None = None
    #: what a container holds: "a glass of water", "a mug of coffee"
    contents: str | None = None
    recipe: str | None = None
    unknown: list[str] = field(default_factory=list)
    #: "the apple or the tomato": one of them
    alternatives: list[Head] = field(default_factory=list)
    #: "a plate containing an egg", "the bowl with the apple in it": what it must hold
    holds: list[Head] = field(default_factory=list)
    #: "object" (acted on) or "place" (where something goes or is): for pronouns
    role: str = "object"
    #: "the cabinet it's in", "the drawer the spoon is in": the one that holds this
    container_of: Head | None = None

    @property
    def is_empty(self) -> bool:
        return (self.noun is None and self.pron is None and self.liquid is None
                and self.recipe is None and not self.unknown and not self.piece)

    def label(self) -> str:
        return self.text.strip() or (self.noun.phrase if self.noun else self.pron or "?")


@dataclass
class Target:
    head: Head
    dest: list[Head] = field(default_factory=list)
    prep: str | None = None
    #: "turn the TV on and the lights off": the particle said for this object
    particle: str | None = None
    #: "leave the fridge closed and the light on": the state said for this object
    state: tuple[Stat, bool] | None = None


@dataclass
class Frame:
    act: Act | None
    verb: str
    targets: list[Target] = field(default_factory=list)
    state: tuple[Stat, bool] | None = None
    liquid: str | None = None
    #: "heat X in the microwave": the appliance named as the means
    means: Head | None = None
    #: "open a book in a well lit room": states of the room the act happens in
    room_states: list[tuple[Stat, bool]] = field(default_factory=list)
    negated: bool = False
    #: a report of how things are (read as a complaint), not a request
    report: bool = False
    too: bool = False
    #: "bring me X", "hand it over": X ends up with the person
    recipient: bool = False
    weak: bool = False
    particle: str | None = None
    text: str = ""
    #: "with the big knife", "using the stove": tools and appliances named as the means
    instruments: list[Head] = field(default_factory=list)
    #: a wish for objects ("I'd like a cold apple", "a boiled egg would be great"): the
    #: states of an indefinite object are what is wanted, not which one to take
    wish: bool = False
    #: "get a hot potato ready": prepared, not handed over
    ready: bool = False
    #: "for a couple of minutes": the act lasts (an appliance is run, not just loaded)
    timed: bool = False
    #: a report of a past act ("someone left the fridge open", "nobody closed it")
    past: bool = False


@dataclass
class ParsedClause:
    clause: Clause
    frames: list[Frame]
    mentions: list[Head]
    unknown: list[str]
    #: "the microwave is fine", "use the stove": the clause only names the means of a
    #: neighbouring clause's act
    means: Head | None = None
    #: the clause opened a wish ("make sure the fridge is closed, the stove off ..."): the
    #: statements after it in the sentence are wishes too, not complaints
    directive: bool = False
    #: "... Oh, and the tomato too.": only objects, for the act of the clause before
    also: list[Head] = field(default_factory=list)


# --- noun phrases ---------------------------------------------------------------------
_PIECE_NOUNS = frozenset({"slice", "piece", "chunk", "wedge", "bit", "half", "segment",
                          "portion", "sliver", "slices", "pieces", "chunks", "wedges", "bits",
                          "halves", "segments", "portions", "slivers"})


def is_piece_word(it: Item) -> bool:
    """"slice", "pieces": a word that names the pieces of what follows or precedes."""
    return it.text in _PIECE_NOUNS


def np_start(it: Item) -> bool:
    return bool(it.det or it.quant or it.number is not None or it.noun is not None
                or it.pron is not None or it.liquid is not None or it.recipe is not None
                or is_piece_word(it) or it.ordinal is not None)


_HUMAN_OBJECTS = frozenset({"me", "us", "here", "over here", "him", "her", "my hand"})


def parse_np(items: list[Item], i: int) -> tuple[Head | None, int]:
    """A noun phrase starting at ``items[i]`` and the index after it."""
    h = Head()
    j = i
    words: list[str] = []
    n = len(items)
    while j < n:
        it = items[j]
        nxt = items[j + 1] if j + 1 < n else None
        if it.punct is not None or it.conj is not None or it.seq is not None or it.robot is not None \
                or it.text in lx.CONTAINING:
            break
        if it.neg or ((it.copula and it.text not in ("one",)) and it.noun is None):
            break
        if it.text == "except" or (it.text in ("instead", "apart") and nxt is not None
                                   and nxt.text in ("of", "from")):
            break      # "the mug instead of the cup": a rejected alternative follows
        if it.text in lx.MEASURE_WORDS and h.noun is None and h.pron is None and nxt is not None \
                and nxt.text == "of" and j + 2 < n and np_start(items[j + 2]):
            # "a roll of foil", "the three rolls of foil", "a head of lettuce": the
            # measure counts the thing named after "of"
            h.plural = h.plural or it.text.endswith("s")
            words.append(f"{it.text} of")
            j += 2
            continue
        if it.text == "lot" and h.noun is None and (nxt is None or not np_start(nxt)):
            h.pron = "them"     # "the lot", "the whole lot": everything just listed
            words.append(it.text)
            j += 1
            break
        if it.quant is not None and h.noun is None:
            h.quant = it.quant
            if it.quant == "both":
                h.count = 2
            if it.quant == "everything":
                h.noun = NounReading(lx.nouns()["everything"], "everything", True)
            words.append(it.text)
            j += 1
            if j < n and items[j].text == "of":
                j += 1
            continue
        if it.text == "one" and nxt is not None and nxt.text == "of":
            h.count = 1
            words.append("one of")
            j += 2
            continue
        if it.det and h.noun is not None:
            break      # "give the plate a rinse": a new noun phrase begins
        if it.det and (it.text not in ("this", "that", "these", "those", "some", "one")
                       or ((nxt is not None and (np_start(nxt) or nxt.state is not None)
                           and nxt.verb is None) or (nxt is not None and (
                               nxt.noun is not None or nxt.liquid is not None
                               or nxt.recipe is not None)))):
            if it.text == "one":
                h.count = 1
            elif it.text in ("the", "this", "that", "these", "those", "my", "your", "our",
                             "his", "her", "their", "its"):
                h.definite = True
                if it.text in ("these", "those"):
                    h.plural = True
            elif it.text == "some":
                h.vague_count = True
            words.append(it.text)
            j += 1
            continue
        if (it.number is not None and h.noun is None and it.pron is None) or (
                it.number is not None and it.text in lx.NUMBERS and it.text != "one"
                and h.noun is None):
            h.count = it.number
            h.vague_count = it.text in lx.VAGUE_COUNTS
            words.append(it.text)
            j += 1
            if j < n and items[j].text == "of":
                j += 1
            continue
        if it.ordinal is not None and h.noun is None:
            h.ordinal = it.ordinal
            words.append(it.text)
            j += 1
            continue
        if is_piece_word(it) and it.noun is None:
            h.piece = True
            words.append(it.text)
            j += 1
            if j < n and items[j].text == "of":
                j += 1
            continue
        if it.text in lx.MEASURE_WORDS and h.noun is not None and h.noun.concept.kind == "object":
            h.plural = h.plural or it.text.endswith("s")     # "the foil rolls", "soap bars"
            words.append(it.text)
            j += 1
            continue
        if it.noun is not None and not (it.verb is not None and h.noun is not None
                                        and it.verb.form == "s"):
            if h.noun is not None and h.noun.concept.kind == "room":
                h.noun = None          # "the kitchen light": the room is a modifier
            if h.noun is not None and it.noun.concept.kind == "room":
                words.append(it.text)  # "the lights in the room" handled as location
                j += 1
                continue
            h.noun = it.noun
            h.plural = h.plural or it.noun.plural
            if it.recipe is not None:
                h.recipe = it.recipe
            words.append(it.text)
            j += 1
            # "a glass of water", "a mug of coffee"
            if it.liquid is not None:
                h.liquid = it.liquid
            if j + 1 < n and items[j].text == "of" and items[j + 1].liquid is not None:
                h.contents = items[j + 1].liquid
                words.append(f"of {h.contents}")
                j += 2
            elif j + 2 < n and items[j].text == "of" and items[j + 1].det and items[j + 2].noun is not None \
                    and h.noun.concept.kind == "anything":
                j += 1     # "all of the ..." spelled with a noun: "everything of the"
            continue
        if it.recipe is not None and h.noun is None:
            h.recipe = it.recipe
            h.liquid = it.liquid
            words.append(it.text)
            j += 1
            continue
        if it.liquid is not None and h.noun is None:
            h.liquid = it.liquid
            h.recipe = lx.RECIPES.get(it.liquid)
            words.append(it.text)
            j += 1
            continue
        if (it.pron is not None and h.noun is None and it.text not in ("this", "that")) or (
                it.text in ("this", "that", "these", "those", "some", "one")):
            if h.noun is None:
                h.pron = it.text
                words.append(it.text)
                j += 1
            break
        if it.state is not None and it.text not in ("on", "off", "in", "open") and h.noun is None \
                and nxt is not None and (nxt.noun is not None or is_piece_word(nxt) or nxt.state is not None):
            stat, pos = it.state
            if stat is Stat.SLICED or it.text in ("cracked",):
                h.piece = True
            elif stat is Stat.TOASTED:
                h.piece = True
                h.filters.append((Stat.COOKED, True))
            else:
                h.filters.append((stat, pos))
            words.append(it.text)
            j += 1
            continue
        if it.verb is not None and h.noun is None and it.noun is None and not it.det:
            break
        if it.prep is not None or it.particle is not None or it.state is not None:
            break
        if it.verb is not None and h.noun is not None:
            break
        # an unknown word (an adjective we do not know, or a noun we do not know)
        if it.text not in lx.COMMON_WORDS and not it.text.isdigit():
            if h.noun is None:
                h.unknown.append(it.corrected_from or it.text)
        elif h.noun is not None:
            break
        words.append(it.text)
        j += 1
    if j == i:
        return None, i
    if h.pron in ("them", "they", "these", "those") and j < n and items[j].text in (
            "all", "both", "each", "together"):
        words.append(items[j].text)        # "them all", "them both"
        j += 1
    if h.noun is None and h.pron is None and h.liquid is None and h.recipe is None \
            and not h.piece and not h.unknown and (h.quant is not None or h.count is not None) \
            and (j >= n or not np_start(items[j])):
        # "all three", "both", "each": the objects just listed
        h.pron = "them" if (h.count or 2) > 1 or h.quant in ("all", "both", "each") else "it"
    if h.noun is not None:
        j = _relative_clause(items, j, h, words)
    h.text = " ".join(words)
    if h.noun is None and h.pron is None and h.liquid is None and h.recipe is None \
            and not h.piece and not h.unknown:
        return (None, j) if words else (None, i)
    if h.noun is not None:
        h.unknown = []
    return h, j


_RELATIVE = frozenset({"that", "which", "where", "who"})
_LOCATIVE = frozenset({"in", "on", "inside", "into"})


def _relative_clause(items: list[Item], j: int, h: Head, words: list[str]) -> int:
    """A relative clause that picks out one object: "the cabinet it's in", "the drawer
    where they are" (the one containing what the pronoun refers to), "the mug that is
    dirty" (a state filter). Returns the index after it (``j`` when there is none)."""
    n = len(items)
    k = j + 1 if j < n and items[j].text in _RELATIVE else j
    inner, m = (None, k)
    if k < n and (items[k].det or items[k].pron in ("it", "they", "them")):
        inner, m = parse_np(items, k) if items[k].det else (
            Head(text=items[k].text, pron=items[k].text), k + 1)
    if inner is not None and m < n and items[m].text in ("is", "are", "was", "were"):
        end = m + 1
        if end < n and items[end].text in _LOCATIVE:
            end += 1
        if end >= n or items[end].punct is not None or items[end].conj is not None \
                or items[end].seq is not None or items[end].verb is not None:
            h.container_of = inner
            words.extend(x.text for x in items[j:end])
            return end
    if not (k > j and k + 1 < n and items[k].text in ("is", "are", "was", "were")):
        return j
    nxt = items[k + 1]
    ends = k + 2 >= n or not np_start(items[k + 2])
    if nxt.state is not None and (nxt.prep is None or ends):
        h.filters.append(nxt.state)
        words.extend(x.text for x in items[j:k + 2])
        return k + 2
    if nxt.prep in ("in", "on") and not ends:
        land, end = parse_np(items, k + 2)
        if land is not None:
            land.role = "place"
            h.location.append((nxt.prep, land))
            words.extend(x.text for x in items[j:end])
            return end
    return j


def fix_ellipsis(prev: Head, nxt: Head) -> None:
    """"the desk and floor lamps": a modifier-only conjunct borrows the next head noun."""
    if prev.noun is None or nxt.noun is None or " " not in nxt.noun.phrase:
        return
    head_word = nxt.noun.phrase.split()[-1]
    cand = f"{prev.noun.phrase.split()[-1]} {head_word}"
    table = lx.nouns()
    if cand in table and cand != prev.noun.phrase:
        prev.noun = NounReading(table[cand], cand, nxt.noun.plural)
        prev.plural = nxt.plural or prev.plural


MODIFIER_PREPS = frozenset({"in", "on", "from"})


def predicate_at(items: list[Item], k: int) -> bool:
    """Does a predicate start at ``items[k]`` (a copula, modal or verb, maybe after an
    adverb): "... should be", "... needs to go", "... goes", "... belong"?"""
    while k < len(items) and items[k].text in _PRE_PREDICATE:
        k += 1
    if k >= len(items):
        return False
    it = items[k]
    return bool(it.copula or (it.verb is not None and it.noun is None and it.prep is None))


#: participles that only say where something is: "the lettuce sitting on the counter"
_POSITION_VERBS = frozenset({"sit", "lie", "stand", "rest", "leave", "keep", "store", "place",
                             "put", "hang", "stay", "find", "wait", "remain"})


def position_participle(it: Item) -> bool:
    """"sitting", "left", "stored": a participle that only says where something is."""
    return it.verb is not None and it.verb.form in ("ing", "ed") and \
        it.verb.lemma in _POSITION_VERBS


def skip_locative(items: list[Item], k: int) -> int:
    """The index after a place that describes the noun phrase ending at ``k``, with an
    optional participle ("on the stove", "sitting on the counter"); ``k`` if none."""
    n = len(items)
    m = k
    if m < n and position_participle(items[m]):
        m += 1
    if m + 1 < n and items[m].prep in MODIFIER_PREPS and np_start(items[m + 1]):
        _, end = parse_np(items, m + 1)
        if end > m + 1:
            return end
    return k


def predicate_start(items: list[Item], k: int) -> bool:
    """Does a second predicate (no new subject) start at ``k``: "on the desk", "sliced",
    "put on a plate"?"""
    if k >= len(items):
        return False
    it = items[k]
    if it.prep in ("in", "on") and k + 1 < len(items) and np_start(items[k + 1]):
        return True
    return (it.state is not None and it.prep is None) or (
        it.verb is not None and it.verb.form == "ed" and it.noun is None)


def list_end(items: list[Item], j: int) -> int:
    """The index after a list of noun phrases with places ("the bread on the counter and
    the egg on the table"), where its predicate would start."""
    n = len(items)
    while j < n:
        it = items[j]
        if it.prep in MODIFIER_PREPS or it.conj == "and" or it.punct == "," or np_start(it):
            if it.verb is not None and it.noun is None and not it.det:
                break
            j += 1
            continue
        break
    return j


_PRE_PREDICATE = frozenset({"still", "really", "currently", "also", "always", "probably",
                            "definitely", "somehow", "all", "both", "now"})


#: states an indefinite noun phrase can ask for ("a cold apple", "a clean plate")
DESIRABLE = frozenset({Stat.HOT, Stat.COLD, Stat.COOKED, Stat.CLEAN, Stat.TOASTED,
                       Stat.FILLED})


def np_list(items: list[Item]) -> list[Head] | None:
    """The noun phrases of a clause that is nothing else ("the fork and the spoon"),
    else None."""
    heads: list[Head] = []
    j = 0
    n = len(items)
    while j < n:
        head, k = parse_np(items, j)
        if head is None or k == j:
            return None
        heads.append(head)
        j = k
        if j < n and (items[j].conj == "and" or items[j].punct == ","):
            j += 1
            continue
        if j < n:
            return None
    return heads or None


def unknown_words(mentions: list[Head]) -> list[str]:
    return [w for h in mentions for w in h.unknown]
