"""Noun phrases and the structures the clause grammar fills: a noun phrase (``Head``)
with its count, adjectives, where it is and what it holds; an object with its
destination (``Target``); an act with its objects (``Frame``); a parsed clause.

``parse_np`` reads one noun phrase: determiners, numbers and quantifiers ("all three",
"both of them", "the lot"), measure words ("two rolls of foil", "a head of lettuce"),
pieces ("a slice of bread"), adjectives, and a relative clause that picks the object
out ("the cabinet it's in", "the mug that is dirty"; "the apple that is in the fridge" is
rewritten before, by :mod:`~emboteam.pfg.offline.idioms`).
The place helpers tell a place that describes a noun phrase ("the lettuce sitting on the
counter") from a destination.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.clauses import Clause
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.patterns import pattern_tables
from emboteam.pfg.offline.tagger import Item, NounReading
from emboteam.world.catalogue import load_catalogue

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
    #: "all the lights except the desk lamp": what the phrase leaves out
    excluded: list[Head] = field(default_factory=list)

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


_W = word_tables("phrases")
# --- noun phrases ---------------------------------------------------------------------
_PIECE_NOUNS = _W.set("piece_nouns")


def is_piece_word(it: Item) -> bool:
    """"slice", "pieces": a word that names the pieces of what follows or precedes."""
    return it.text in _PIECE_NOUNS


def np_start(it: Item) -> bool:
    return bool(it.det or it.quant or it.number is not None or it.noun is not None
                or it.pron is not None or it.liquid is not None or it.recipe is not None
                or is_piece_word(it) or it.ordinal is not None)


@dataclass
class _NP:
    """A noun phrase being read: the words, where the reader is, what it found so far."""

    items: list[Item]
    j: int
    h: Head = field(default_factory=Head)
    words: list[str] = field(default_factory=list)

    @property
    def it(self) -> Item:
        return self.items[self.j]

    @property
    def nxt(self) -> Item | None:
        return self.items[self.j + 1] if self.j + 1 < len(self.items) else None

    def take(self, text: str, k: int = 1) -> str:
        """Keep ``text`` as part of the phrase and move on ``k`` items."""
        self.words.append(text)
        self.j += k
        return _NEXT

    def skip_of(self) -> None:
        if self.j < len(self.items) and self.items[self.j].text == "of":
            self.j += 1


#: what a noun-phrase rule decides: the word belongs to the phrase (go on), the phrase
#: ended, or (None) the rule does not apply
_NEXT, _STOP = "next", "stop"
_ENDS_PHRASE = pattern_tables("phrases").pattern("ends_phrase")
NPRule = Callable[[_NP], str | None]


def _ends_phrase(s: _NP) -> str | None:
    """Punctuation, a conjunction, a sequence word, a robot, "containing", a negation, a
    copula, "instead of", "except": the phrase ends before them."""
    return _STOP if _ENDS_PHRASE.at(s.items, s.j) else None


def _measure_of(s: _NP) -> str | None:
    """"a roll of foil", "the three rolls of foil", "a head of lettuce": the measure counts
    the thing named after "of"."""
    it, nxt, h = s.it, s.nxt, s.h
    if it.text in lx.MEASURE_WORDS and h.noun is None and h.pron is None and nxt is not None \
            and nxt.text == "of" and s.j + 2 < len(s.items) and np_start(s.items[s.j + 2]):
        h.plural = h.plural or it.text.endswith("s")
        return s.take(f"{it.text} of", 2)
    return None


def _the_lot(s: _NP) -> str | None:
    """"the lot", "the whole lot": everything just listed."""
    it, nxt = s.it, s.nxt
    if it.text == "lot" and s.h.noun is None and (nxt is None or not np_start(nxt)):
        s.h.pron = "them"
        s.take(it.text)
        return _STOP
    return None


def _quantifier(s: _NP) -> str | None:
    """"all", "both", "every", "everything" (and "all of")."""
    it, h = s.it, s.h
    if it.quant is None or h.noun is not None:
        return None
    h.quant = it.quant
    if it.quant == "both":
        h.count = 2
    if it.quant == "everything":
        h.noun = NounReading(lx.nouns()["everything"], "everything", True)
    s.take(it.text)
    s.skip_of()
    return _NEXT


def _one_of(s: _NP) -> str | None:
    if s.it.text == "one" and s.nxt is not None and s.nxt.text == "of":
        s.h.count = 1
        return s.take("one of", 2)
    return None


def _adjectives_then_noun(items: list[Item], k: int, most: int = 2) -> bool:
    """Do up to ``most`` plain words from ``k`` lead to a noun ("that grotty old cloth")?"""
    for m in range(k, min(k + most + 1, len(items))):
        it = items[m]
        if it.noun is not None:
            return True
        if it.verb is not None or it.prep is not None or it.punct is not None or it.conj is not None or it.det:
            return False
    return False


def _determiner(s: _NP) -> str | None:
    """Articles, demonstratives and possessives ("the", "these", "my", "some"); a
    determiner after the noun starts a new phrase ("give the plate a rinse")."""
    it, nxt, h = s.it, s.nxt, s.h
    if not it.det:
        return None
    if h.noun is not None:
        return _STOP
    after = s.items[s.j + 2] if s.j + 2 < len(s.items) else None
    # "that old cloth"; "toss that empty bottle": a word that could be a verb, between a
    # demonstrative in object position and a noun, is an adjective (not "the knife that
    # cut bread")
    before = s.items[s.j - 1] if s.j > 0 else None
    object_position = before is not None and (before.verb is not None or before.prep is not None)
    adjective = nxt is not None and (nxt.verb is None or (object_position and nxt.verb.form == "base")) \
        and nxt.prep is None and nxt.punct is None and nxt.conj is None and after is not None \
        and (after.noun is not None or _adjectives_then_noun(s.items, s.j + 2))
    if not (it.text not in ("this", "that", "these", "those", "some", "one")
            or ((nxt is not None and (np_start(nxt) or nxt.state is not None)
                 and nxt.verb is None) or (nxt is not None and (
                     nxt.noun is not None or nxt.liquid is not None
                     or nxt.recipe is not None)) or adjective)):
        return None
    if it.text == "one":
        h.count = 1
    elif it.text in ("the", "this", "that", "these", "those", "my", "your", "our",
                     "his", "her", "their", "its"):
        h.definite = True
    elif it.text == "some":
        h.vague_count = True
    return s.take(it.text)


def _number(s: _NP) -> str | None:
    """"two apples", "a few", "three of the mugs"."""
    it, h = s.it, s.h
    if not ((it.number is not None and h.noun is None and it.pron is None) or (
            it.number is not None and it.text in lx.NUMBERS and it.text != "one"
            and h.noun is None)):
        return None
    h.count = it.number
    h.vague_count = it.text in lx.VAGUE_COUNTS
    s.take(it.text)
    s.skip_of()
    return _NEXT


def _ordinal(s: _NP) -> str | None:
    if s.it.ordinal is not None and s.h.noun is None:
        s.h.ordinal = s.it.ordinal
        return s.take(s.it.text)
    return None


def _piece_word(s: _NP) -> str | None:
    """"a slice of bread", "pieces of apple": the pieces of what follows."""
    if not (is_piece_word(s.it) and s.it.noun is None):
        return None
    s.h.piece = True
    s.take(s.it.text)
    s.skip_of()
    if s.j + 1 < len(s.items) and s.items[s.j].text in ("off", "from") and (
            s.items[s.j + 1].det or s.items[s.j + 1].pron in ("it", "that", "this")):
        s.j += 1        # "cut a slice off the loaf": the pieces of the loaf
    return _NEXT


def _measure_after_noun(s: _NP) -> str | None:
    """"the foil rolls", "soap bars"."""
    it, h = s.it, s.h
    if it.text in lx.MEASURE_WORDS and h.noun is not None and h.noun.concept.kind == "object":
        h.plural = h.plural or it.text.endswith("s")
        return s.take(it.text)
    return None


def names_only(head: Head | NounReading, has: tuple[str, ...], lacks: tuple[str, ...] = ()) -> bool:
    """Does the phrase name catalogue types, every one with the properties ``has`` and none
    of ``lacks`` ("receptacle", not "pickupable": a fridge, a counter)?"""
    noun = head.noun if isinstance(head, Head) else head
    cat = load_catalogue()
    types = [cat.type(t) for t in (noun.concept.types if noun is not None else ()) if t in cat.types]
    return bool(types) and all(all(t.has(p) for p in has) and not any(t.has(p) for p in lacks) for t in types)


def _furniture(noun: NounReading) -> bool:
    """Does the noun name only furniture things stand on (a side table, a counter)?"""
    return names_only(noun, ("receptacle",), ("pickupable", "openable"))


def _noun(s: _NP) -> str | None:
    """The head noun (a room before it is a modifier: "the kitchen light"), and what a
    container holds: "a glass of water", "a mug of coffee"."""
    it, h, items = s.it, s.h, s.items
    if it.noun is None or (it.verb is not None and h.noun is not None and it.verb.form == "s"):
        return None
    if h.noun is not None and h.noun.concept.kind == "room":
        h.noun = None
    if h.noun is not None and _furniture(h.noun) and it.noun.concept.kind in ("object", "lamps", "lights") \
            and not _furniture(it.noun):
        # "the side table lamp", "the counter knife": the thing on that furniture
        h.location.append(("on", Head(text=f"the {h.noun.phrase}", noun=h.noun, definite=True, role="place")))
    h.noun = it.noun
    h.plural = h.plural or it.noun.plural
    if it.recipe is not None:
        h.recipe = it.recipe
    elif s.j > 0 and items[s.j - 1].recipe is not None:
        h.recipe = None     # "a toast rack", "the coffee mug": a dish just before the head names its kind
    s.take(it.text)
    if it.liquid is not None:
        h.liquid = it.liquid
    j, n = s.j, len(items)
    if j + 1 < n and items[j].text == "of" and items[j + 1].liquid is not None:
        h.contents = items[j + 1].liquid
        s.take(f"of {h.contents}", 2)
    return _NEXT


def _dish_or_liquid(s: _NP) -> str | None:
    """A dish ("toast", "coffee") or a liquid ("water") without a noun."""
    it, h = s.it, s.h
    if h.noun is not None:
        return None
    if it.recipe is not None:
        h.recipe = it.recipe
        h.liquid = it.liquid
        return s.take(it.text)
    if it.liquid is not None:
        h.liquid = it.liquid
        h.recipe = lx.RECIPES.get(it.liquid)
        return s.take(it.text)
    return None


def _pronoun(s: _NP) -> str | None:
    """"it", "them", "this", "some": the phrase is (or ends with) a pronoun."""
    it, h = s.it, s.h
    if not ((it.pron is not None and h.noun is None and it.text not in ("this", "that")) or (
            it.text in ("this", "that", "these", "those", "some", "one"))):
        return None
    if h.noun is None:
        h.pron = it.text
        s.take(it.text)
    return _STOP


def _state_adjective(s: _NP) -> str | None:
    """"the dirty mug", "sliced bread" (pieces), "toasted bread" (cooked pieces)."""
    it, nxt, h = s.it, s.nxt, s.h
    after_det = s.j > 0 and s.items[s.j - 1].det     # "the open box": an adjective, not the verb
    if not (it.state is not None and (it.text not in ("on", "off", "in", "open") or (it.text == "open" and after_det))
            and h.noun is None
            and nxt is not None and (nxt.noun is not None or is_piece_word(nxt)
                                     or nxt.state is not None)):
        return None
    assert it.state is not None
    stat, pos = it.state
    if stat is Stat.SLICED or it.text in ("cracked",):
        h.piece = True
    elif stat is Stat.TOASTED:
        h.piece = True
        h.filters.append((Stat.COOKED, True))
    else:
        h.filters.append((stat, pos))
    return s.take(it.text)


def _verb_or_preposition(s: _NP) -> str | None:
    """A verb, a preposition, a particle or a state word ends the phrase."""
    it, h = s.it, s.h
    if it.verb is not None and h.noun is None and it.noun is None and not it.det:
        return _STOP
    if it.prep is not None or it.particle is not None or it.state is not None:
        return _STOP
    if it.verb is not None and h.noun is not None:
        return _STOP
    return None


def _other_word(s: _NP) -> str | None:
    """An unknown word (an adjective or a noun we do not know) is kept, and noted while
    no noun is found; a common word after the noun ends the phrase."""
    it, h = s.it, s.h
    if it.text not in lx.COMMON_WORDS and not it.text.isdigit():
        if h.noun is None:
            h.unknown.append(it.corrected_from or it.text)
    elif h.noun is not None:
        return _STOP
    return s.take(it.text)


#: the noun-phrase rules, in order: the first that applies decides each word
NP_RULES: tuple[NPRule, ...] = (
    _ends_phrase, _measure_of, _the_lot, _quantifier, _one_of, _determiner, _number, _ordinal,
    _piece_word, _measure_after_noun, _noun, _dish_or_liquid, _pronoun, _state_adjective,
    _verb_or_preposition, _other_word,
)


def parse_np(items: list[Item], i: int) -> tuple[Head | None, int]:
    """A noun phrase starting at ``items[i]`` and the index after it (:data:`NP_RULES`
    read it word by word)."""
    s = _NP(items, i)
    n = len(items)
    while s.j < n:
        decision = next(d for rule in NP_RULES if (d := rule(s)) is not None)
        if decision == _STOP:
            break
    return _finish_np(s, i)


def _finish_np(s: _NP, i: int) -> tuple[Head | None, int]:
    """What a read noun phrase stands for once its words are known: "them all", a bare
    quantifier ("all three": the objects just listed), a relative clause after the noun."""
    items, h, words, j, n = s.items, s.h, s.words, s.j, len(s.items)
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


_RELATIVE = _W.set("relative")
_IS_IN, _CLAUSE_BOUNDARY, _POSITION_THEN_PLACE = (pattern_tables("phrases").pattern(name) for name in (
    "is_in", "clause_boundary", "position_then_place"))


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
    end = _IS_IN.end(items, m) if inner is not None else None
    if end is not None and _CLAUSE_BOUNDARY.at(items, end):
        h.container_of = inner
        words.extend(x.text for x in items[j:end])
        return end
    if not (k > j and k + 1 < n and items[k].text in ("is", "are", "was", "were")):
        return j
    p = k + 1
    if _POSITION_THEN_PLACE.at(items, p):
        return j        # "the apple that's (sitting) in the fridge": where it is, read by idioms.py
    nxt = items[p]
    ends = p + 1 >= n or not np_start(items[p + 1])
    if nxt.state is not None and (nxt.prep is None or ends):
        h.filters.append(nxt.state)
        words.extend(x.text for x in items[j:k + 2])
        return k + 2
    return j


def fix_ellipsis(prev: Head, nxt: Head) -> None:
    """"the desk and floor lamps": a modifier-only conjunct borrows the next head noun."""
    if prev.noun is None or nxt.noun is None or " " not in nxt.noun.phrase or " " in prev.noun.phrase:
        return      # ("the bar of soap and the soap bottle": a whole name, no modifier)
    head_word = nxt.noun.phrase.split()[-1]
    cand = f"{prev.noun.phrase.split()[-1]} {head_word}"
    table = lx.nouns()
    if cand in table and cand != prev.noun.phrase:
        prev.noun = NounReading(table[cand], cand, nxt.noun.plural)
        prev.plural = nxt.plural or prev.plural


MODIFIER_PREPS = _W.set("modifier_preps")


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
_POSITION_VERBS = _W.set("position_verbs")


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


_PRE_PREDICATE = _W.set("pre_predicate")


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
