"""Constructions recognised around the clause grammar: light verbs ("give the plate a
rinse"), clauses that only name the means ("the microwave is fine"), wishes that are only
noun phrases ("a boiled egg, please"), "with" joining dishes in a wish ("toast with my
coffee"), durations ("for a couple of minutes"), and reports of where things are
("I left a book on the sofa": a place, not a destination).
"""

from __future__ import annotations

import re
from dataclasses import replace

from pydantic import field_validator

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline import phrases
from emboteam.pfg.offline.knowledge import Rewrite, Strict, load, word_tables
from emboteam.pfg.offline.patterns import pattern_tables
from emboteam.pfg.offline.phrases import DESIRABLE, Frame, Head, Target, np_list, parse_np, skip_locative
from emboteam.pfg.offline.tagger import Item

Act = lx.Act


class ConstructionsFile(Strict):
    """``data/constructions.json``."""

    about: str = ""
    duration: str
    light_acts: frozenset[Act]

    @field_validator("duration")
    @classmethod
    def _compiles(cls, value: str) -> str:
        return Rewrite(pattern=value, replace="").pattern


_DATA = load("constructions.json", ConstructionsFile)
#: "for a couple of minutes", "for a bit": the act lasts (a loaded appliance is run)
DURATION = re.compile(_DATA.duration)


def with_as_and(items: list[Item]) -> list[Item]:
    """"some toast with my coffee": in a wish, a dish "with" another is both wanted."""
    out = list(items)
    for k, it in enumerate(out):
        if it.prep == "with" and k > 0:
            head, _ = parse_np(out, k + 1)
            if head is not None and head.recipe is not None:
                out[k] = Item("and", conj="and")
    return out


def places_to_locations(frame: Frame) -> None:
    """A report of where something is ("I left a book on the sofa", "the remote is in one
    of the drawers") is no request: the place says where the object is, for later
    pronouns and for picking the instance."""
    for t in frame.targets:
        if t.dest and t.prep in ("in", "on", "at", "to"):
            place = t.dest[0]
            place.role = "place"
            t.head.location.append(("in" if t.prep != "on" else "on", place))
            t.dest = []


_W = word_tables("constructions")
_A_THEN_ADJECTIVES, _PART_OF = (pattern_tables("constructions").pattern(name) for name in ("a_then_adjectives",
                                                                                          "part_of"))
#: what a noun phrase can be said to be when it is only the means: "the microwave is fine"
_INSTRUMENT_OK = _W.set("instrument_ok")
#: "the pan could really do with a good scrub", "the mug badly needs a wash": the words
#: between the thing and the verbal noun of a light-verb construction
_BEFORE_VERBAL_NOUN = _W.set("before_verbal_noun")
#: what may stand between the means and its approval ("the microwave is totally fine")
_BEFORE_INSTRUMENT_OK = _W.set("before_instrument_ok")
#: acts a noun can name in "give X a rinse", "the pan could do with a scrub"
_LIGHT_ACTS = _DATA.light_acts


def instrument_clause(items: list[Item], mentions: list[Head]) -> Head | None:
    """"the microwave is fine", "the stove will do", "use the big pan": a clause that only
    names the means of the act of the clause next to it (the means is never a goal)."""
    n = len(items)
    if items[0].text in ("use", "using") and items[0].noun is None:
        head, k = parse_np(items, 1)
        if head is not None and head.noun is not None and skip_locative(items, k) >= n:
            head.role = "place"
            mentions.append(head)
            return head
        return None
    head, k = parse_np(items, 0)
    if head is None or head.noun is None or k >= n:
        return None
    m = k
    while m < n and items[m].text in _BEFORE_INSTRUMENT_OK:
        m += 1
    rest = {x.text for x in items[m:]}
    if m > k and m < n and (items[m].text in _INSTRUMENT_OK or items[m].text == "do") \
            and rest <= _INSTRUMENT_OK | {"do", "to", "use", "for", "this", "that", "it"}:
        head.role = "place"
        mentions.append(head)
        return head
    return None


def _verbal_noun(items: list[Item], k: int) -> int | None:
    """The index of V in "a [adjectives] V" at ``k`` ("a good scrub", "a quick rinse",
    "some water") when V names an act."""
    n = len(items)
    m = _A_THEN_ADJECTIVES.end(items, k)
    if m is None:
        return None
    verb = items[m].verb if m < n else None
    if verb is None or verb.sense.act not in _LIGHT_ACTS:
        return None
    after = items[m + 1] if m + 1 < n else None
    if after is not None and after.noun is not None and after.prep is None:
        return None      # "a wash basin": a noun phrase, not an act
    return m


def light_verb(items: list[Item]) -> list[Item]:
    """Light-verb constructions as the plain verb: "give the plate a rinse" -> "rinse the
    plate"; "the pan could do with a good scrub", "the mug needs a wash" -> "scrub the
    pan", "wash the mug"."""
    first = items[0]
    if first.verb is not None and first.verb.lemma == "give":
        head, k = parse_np(items, 1)
        if head is not None and k > 1:
            v = _verbal_noun(items, k)
            if v is not None:
                return [items[v], *items[1:k], *items[v + 1:]]
        return items
    head, k = parse_np(items, 0)
    if head is None or (head.noun is None and head.pron is None):
        return items
    k = skip_locative(items, k)       # "the pan on the stove needs a good scrub"
    m = k
    while m < len(items) and items[m].text in _BEFORE_VERBAL_NOUN:
        m += 1
    if m == k:
        return items
    v = _verbal_noun(items, m)
    if v is None:
        return items
    return [items[v], *items[:k], *items[v + 1:]]


#: verbs that make something happen to an object: "get the kettle boiling"
_CAUSATIVES = _W.set("causatives")
_NO_ACT = frozenset({Act.CAUSE, Act.GO, Act.MAKE, Act.VAGUE})


def causative_progressive(items: list[Item]) -> list[Item]:
    """"get it heating", "have the kettle boiling", "set the toaster going" -> "heat it",
    "boil the kettle": the participle is the act, the causative verb only asks for it."""
    first = items[0]
    if first.verb is None or first.verb.lemma not in _CAUSATIVES:
        return items
    head, k = parse_np(items, 1)
    if head is None or k >= len(items):
        return items
    verb = items[k].verb
    if verb is None or verb.form != "ing" or verb.sense.act in _NO_ACT:
        return items
    base = replace(items[k], verb=replace(verb, form="base"), text=verb.lemma, noun=None, state=None)
    return [base, *items[1:k], *items[k + 1:]]


def absent_from(items: list[Item], text: str) -> Frame | None:
    """"there's no loo roll on the holder", "no soap in the dish": a complaint that
    something is missing from its place asks to put it there (``items`` start after
    "there is"); without a place there is nothing to ask."""
    if not items or not items[0].neg or items[0].text != "no":
        return None
    head, k = parse_np(items, 1)
    if head is None or head.noun is None or k >= len(items):
        return None
    prep = lx.PREPOSITIONS.get(items[k].text)
    if prep not in ("in", "on", "at") or k + 1 >= len(items):
        return None
    place, _ = parse_np(items, k + 1)
    if place is None or place.noun is None:
        return None
    place.role = "dest"
    return Frame(Act.PLACE, "put", [Target(head, [place], "in" if prep == "in" else "on")], text=text,
                 wish=True)


def noun_phrase_wish(items: list[Item], mentions: list[Head]) -> Frame | None:
    """A clause that is only noun phrases naming a dish or a state: "a boiled egg,
    please", "two slices of toast", "a cold apple would be great" (the politeness is
    stripped before): what they name is wanted."""
    heads = np_list(items)
    if not heads or not any(h.recipe is not None or (not h.definite and any(
            st in DESIRABLE for st, _ in h.filters)) for h in heads):
        return None
    mentions.extend(heads)
    return Frame(Act.CAUSE, "want", [Target(h) for h in heads], wish=True,
                 text=" ".join(x.text for x in items))


def parts_as_places(items: list[Item]) -> list[Item]:
    """"on the side of the bath", "on the edge of the bathtub", "on top of the counter": the
    place is the bath, the bathtub, the counter (in/on is the only relation a goal states)."""
    out: list[Item] = []
    k = 0
    while k < len(items):
        out.append(items[k])
        end = _PART_OF.end(items, k)
        k = end - 1 if end is not None else k + 1      # "on the side of the bath" -> "on the bath"
    return out


def _small_thing(it: Item) -> bool:
    """A noun that names only things one can pick up (a book, a pen), not furniture."""
    return it.noun is not None and it.noun.concept.kind == "object" and it.verb is None \
        and phrases.names_only(it.noun, ("pickupable",))


def commaless_lists(items: list[Item]) -> list[Item]:
    """"put the book pen & pencil in the box": two things named side by side, before an
    "and" that ends the list, are two items of it (no compound noun is two pickupable
    things: "bread knife" is one word of the lexicon)."""
    out: list[Item] = []
    for k, it in enumerate(items):
        out.append(it)
        if not (_small_thing(it) and k + 1 < len(items) and _small_thing(items[k + 1])):
            continue
        m = k + 1
        while m < len(items) and (_small_thing(items[m]) or items[m].det):
            m += 1
        if m < len(items) and items[m].conj == "and":
            out.append(Item(text=",", punct=","))
    return out


#: verbs that non-native speakers often put after their object ("the book put on sofa",
#: "desk lamp turn off", "the wine bottle bring to fridge")
_OBJECT_FIRST_VERBS = _W.set("object_first_verbs")
_CLAUSE_OPENERS = _W.set("clause_openers")
#: verbs whose base form is also a participle or a state: only with "it" after them
_PARTICIPLE_LIKE = _W.set("participle_like")
_PIECE_WORDS = _W.set("piece_words")
_NP_WORDS = _W.set("np_words")


def _object_first_np(items: list[Item], j: int) -> int:
    """The end of a noun phrase at ``j`` whose next word is one of the verbs above (``j``
    when there is none): determiners, numbers, adjectives and nouns ("watch" is a noun
    here, though it could be a verb)."""
    k = j
    named = False
    while k < len(items):
        it = items[k]
        nxt = items[k + 1] if k + 1 < len(items) else None
        verb_next = nxt is not None and nxt.verb is not None and nxt.verb.form == "base" \
            and nxt.verb.lemma in _OBJECT_FIRST_VERBS
        if (it.noun is not None or it.text in _PIECE_WORDS) and (
                it.verb is None or verb_next or (nxt is not None and (
                    nxt.noun is not None or nxt.conj == "and" or (it.text in _PIECE_WORDS and nxt.prep == "of")))):
            named = True
        elif it.det or it.number is not None or it.quant is not None or it.text in _NP_WORDS:
            pass
        elif named and it.prep == "from" and nxt is not None and (nxt.det or nxt.noun is not None):
            pass        # "the lettuce from sink put it in fridge": where it is, inside the phrase
        elif named and it.conj == "and" and nxt is not None and (nxt.det or nxt.noun is not None):
            pass        # "my phone and keys put in safe": a list of objects
        elif named and it.prep == "of" and nxt is not None and (nxt.pron in ("it", "them") or nxt.det):
            pass        # "one slice of it put on the plate": a part of what was named
        elif named and it.pron in ("it", "them") and k > j and items[k - 1].prep == "of":
            pass
        else:
            break
        k += 1
        if named and verb_next:
            return k
    return j


def object_first(items: list[Item]) -> list[Item]:
    """"the book put on sofa", "desk lamp make off", "labtop close it": an object before
    its verb (non-native word order), at the start of a clause, is read after it ("put the
    book on sofa"); a pronoun that repeats the object after the verb ("close laptop it")
    then refers to it, and a particle stays after the object ("turn desk lamp off")."""
    out: list[Item] = []
    k = 0
    start = True
    while k < len(items):
        it = items[k]
        if start and it.text in _CLAUSE_OPENERS and it.noun is None:
            out.append(it)
            k += 1
            continue
        end = _object_first_np(items, k) if start else k
        if end > k:
            verb = items[end]
            rest = end + 1
            nxt = items[rest] if rest < len(items) else None
            if verb.verb is not None and verb.verb.lemma in _PARTICIPLE_LIKE \
                    and not (nxt is not None and nxt.pron in ("it", "them")):
                # "laptop shut, ...", "the card shut away inside the box": a state or a
                # passive, not a verb after its object (unless "it" repeats the object)
                out.append(it)
                start = False
                k += 1
                continue
            if nxt is not None and (nxt.det or (nxt.noun is not None and nxt.prep is None)):
                out.append(it)  # the verb has an object of its own: not this construction
                start = False
                k += 1
                continue
            out += [verb, *items[k:end]]     # "desk lamp turn off": "turn desk lamp off"
            k = rest
            start = False
            continue
        out.append(it)
        start = it.punct is not None or it.conj == "and" or it.seq is not None
        k += 1
    return out
