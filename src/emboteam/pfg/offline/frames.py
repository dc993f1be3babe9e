"""The clause grammar: one clause -> frames (an act, its objects, where they go, a state).

Three shapes cover household instructions:

- imperative: ``[preamble] VERB [particle] NP (and NP)* [PP]* [particle|STATE]``
  ("could you put the apple and the tomato in the fridge", "turn the tv off",
  "leave the fridge open", "put the apple in the fridge and the bread on the counter");
- statement or wish: ``NP [modal] [not] (STATE | PARTICIPLE | PP | GO-verb PP)``
  ("the fridge should be closed", "the bread sliced", "bread on plate",
  "the towel belongs on the holder", "the potato won't cook itself");
- a person as subject: ``someone left the fridge open``, ``nobody needs the lights on``.

A statement of how things are ("the fridge is open", "somebody left the lights on",
"it's too dark") is read as a complaint: the goal is the opposite state. A clause that
yields nothing (small talk: "thanks!", "when you get a chance") is dropped; its nouns
still count as mentions for pronouns.
"""

from __future__ import annotations

import re
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


@dataclass
class ParsedClause:
    clause: Clause
    frames: list[Frame]
    mentions: list[Head]
    unknown: list[str]


# --- preamble: politeness, hedges and framing that carry no content -------------------
_WHO = r"(?:you|someone|somebody|anyone|anybody|one of you|the robots?|robots?|the team|team|guys)"
_PREAMBLE = [re.compile(r"^(?:" + p + r")\b\s*") for p in (
    r"please|kindly|just|also|now|ok|okay|alright|all right|so|well|oh|hey|hi|hello|um|uh|"
    r"hmm|and|but|first|firstly|to begin|to start|then|quickly|right|yes|yeah|finally",
    r"(?:could|can|would|will|might) " + _WHO + r"(?: please)?(?: kindly)?(?: possibly)?",
    r"(?:would|do) " + _WHO + r" mind|mind",
    r"(?:i|we) (?:would|will|do|really)? ?(?:want|need|like|love|wish|expect|require|ask) "
    + _WHO + r"? ?to",
    r"(?:i|we) (?:would|will)? ?(?:want|need|like|love) to",
    _WHO + r" (?:should|must|need to|needs to|have to|has to|will|can|could|might|may|"
    r"ought to|are to|is to|would)",
    r"let us|let s|lets",
    r"go ahead and|go and|try to|try and|be sure to|make sure to|remember to|"
    r"do not forget to|never forget to|dont forget to",
    r"make sure that|make sure|ensure that|ensure|see to it that|check that|verify that",
    r"help me|help us|help",
    r"(?:it would be|it will be|that would be|would be) (?:really |very |so )?"
    r"(?:great|nice|good|lovely|awesome|helpful|wonderful|cool|ideal|perfect)",
    r"(?:is it|would it be|will it be|it is) possible (?:for " + _WHO + r" )?to",
    r"(?:your|the|our) (?:task|job|goal|mission|assignment) is to",
    r"i would appreciate it if " + _WHO + r" (?:could|would|can)",
    r"what (?:i|we) (?:want|need|would like|would love) is",
    r"(?:be )?(?:so kind as to|kind enough to|a dear and|a star and)",
    r"time to|it is time to|now is the time to",
    r"to",
)]
_TRAILING = re.compile(r"\s*\b(?:please|for me|for us|thanks|thank you|if you can|if possible|"
                       r"right now|now|asap|when you can|would you|will you|as well|too|"
                       r"okay|ok|real quick|for a moment|for a second|again)$")
#: words dropped anywhere outside noun phrases
_MID_FILLERS = frozenset({"please", "also", "just", "quickly", "carefully", "gently", "kindly",
                          "immediately", "really", "actually", "again", "back", "right",
                          "away", "as", "well", "then", "way", "first"})


#: preambles that turn what follows into a wish ("make sure the fridge is closed")
_WISH = re.compile(r"^(?:make sure|ensure|see to it|check that|verify that|what (?:i|we)|"
                   r"(?:i|we) (?:would|will|do|really)? ?(?:want|need|like|love)|it would be)")


def _strip_preamble(items: list[Item], flags: dict[str, bool]) -> list[Item]:
    changed = True
    while changed and items:
        changed = False
        text = " ".join(i.text for i in items)
        for pat in _PREAMBLE:
            m = pat.match(text)
            if m and m.end() > 0:
                if _WISH.match(text):
                    flags["directive"] = True
                consumed = text[: m.end()].split()
                k, used = 0, 0
                while k < len(items) and used < len(consumed):
                    used += len(items[k].text.split())
                    k += 1
                if used == len(consumed) and k > 0:
                    # never drop a verb that begins the clause (the "so" of "so that" aside)
                    items = items[k:]
                    changed = True
                    break
    while items:
        text = " ".join(i.text for i in items)
        m = _TRAILING.search(text)
        if not m or (m.start() == 0 and len(items) == len(text.split()) == len(m.group().split())):
            break
        n_words = len(m.group().split())
        k, used = len(items), 0
        while k > 0 and used < n_words:
            k -= 1
            used += len(items[k].text.split())
        if used != n_words or k == 0:
            break
        items = items[:k]
    return items


# --- noun phrases ---------------------------------------------------------------------
_PIECE_NOUNS = frozenset({"slice", "piece", "chunk", "wedge", "bit", "half", "segment",
                          "portion", "sliver", "slices", "pieces", "chunks", "wedges", "bits",
                          "halves", "segments", "portions", "slivers"})


def _is_piece_word(it: Item) -> bool:
    """"slice", "pieces": a word that names the pieces of what follows or precedes."""
    return it.text in _PIECE_NOUNS


def _np_start(it: Item) -> bool:
    return bool(it.det or it.quant or it.number is not None or it.noun is not None
                or it.pron is not None or it.liquid is not None or it.recipe is not None
                or _is_piece_word(it) or it.ordinal is not None)


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
        if it.det and (it.text not in ("this", "that", "these", "those", "some", "one")
                       or ((nxt is not None and (_np_start(nxt) or nxt.state is not None)
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
        if _is_piece_word(it) and it.noun is None:
            h.piece = True
            words.append(it.text)
            j += 1
            if j < n and items[j].text == "of":
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
                and nxt is not None and (nxt.noun is not None or _is_piece_word(nxt) or nxt.state is not None):
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
    h.text = " ".join(words)
    if h.noun is None and h.pron is None and h.liquid is None and h.recipe is None \
            and not h.piece and not h.unknown:
        return (None, j) if words else (None, i)
    if h.noun is not None:
        h.unknown = []
    return h, j


def _fix_ellipsis(prev: Head, nxt: Head) -> None:
    """"the desk and floor lamps": a modifier-only conjunct borrows the next head noun."""
    if prev.noun is None or nxt.noun is None or " " not in nxt.noun.phrase:
        return
    head_word = nxt.noun.phrase.split()[-1]
    cand = f"{prev.noun.phrase.split()[-1]} {head_word}"
    table = lx.nouns()
    if cand in table and cand != prev.noun.phrase:
        prev.noun = NounReading(table[cand], cand, nxt.noun.plural)
        prev.plural = nxt.plural or prev.plural


# --- clause parsing ---------------------------------------------------------------------
_HUMAN_SUBJECTS = frozenset({"i", "we", "you", "someone", "somebody", "nobody", "anyone",
                             "anybody", "everyone", "everybody", "they", "he", "she",
                             "no one", "no"})
_WANT = frozenset({"want", "need", "like", "love", "prefer", "wish", "require"})
_REFLEXIVE = frozenset({"itself", "themselves", "himself", "herself"})


def _skip_aux(items: list[Item], j: int, frame_flags: dict[str, bool]) -> int:
    """Skip copulas, modals, negation and adverbs before a predicate, noting them."""
    while j < len(items):
        it = items[j]
        t = it.text
        nxt_item = items[j + 1] if j + 1 < len(items) else None
        if it.verb is not None and it.verb.lemma in _WANT and nxt_item is not None and \
                nxt_item.text not in ("to", "be") and (nxt_item.verb is None or nxt_item.det):
            break      # "i need the potato cooked": the wish itself
        if it.neg:
            frame_flags["neg"] = not frame_flags.get("neg", False)
        elif (t in lx.MODALS and it.verb is None) or t in ("should", "must", "ought", "can",
                                                          "could", "would", "will", "shall",
                                                          "might", "may") or (t in ("needs", "need", "has", "have", "had") and j + 1 < len(items) and \
                (items[j + 1].text in ("to", "be") or items[j + 1].verb is not None)):
            frame_flags["modal"] = True
        elif t == "too":
            frame_flags["too"] = True
        elif t in ("going", "gonna") and j + 1 < len(items) and items[j + 1].text == "to":
            frame_flags["modal"] = True
        elif t == "to" and not (nxt_item is not None and (nxt_item.text == "be" or nxt_item.verb)):
            break      # "towel to towel holder": a place, not an infinitive
        elif it.copula or t in ("still", "already", "always", "now", "currently", "way", "so",
                                "very", "really", "again", "kept", "be", "been", "being",
                                "all", "nice", "and", "both", "completely", "fully",
                                "properly", "totally", "pretty", "bit", "a", "little",
                                "somewhat", "quite", "rather", "extremely", "super", "well",
                                "nicely", "brightly"):
            pass
        else:
            break
        j += 1
    return j


def _parse_tail(items: list[Item], j: int, frame: Frame, pending: list[Target],
                mentions: list[Head]) -> int:
    """Objects, prepositional phrases and a trailing particle or state after a verb."""
    n = len(items)
    last_np: list[Target] = []
    while j < n:
        it = items[j]
        if it.conj is not None or it.punct is not None or it.text in ("as well as", "along with",
                                                                       "together with"):
            if it.conj == "or" and pending:
                # "the apple or the tomato": alternatives of the last object
                head, k = parse_np(items, j + 1)
                if head is not None:
                    mentions.append(head)
                    pending[-1].head.alternatives.append(head)
                    j = k
                    continue
            j += 1
            continue
        if (it.text in _MID_FILLERS and it.noun is None and it.verb is None and it.prep is None \
                and it.state is None) or it.text in ("me", "us", "here", "there", "him", "her"):
            if it.text in ("me", "us", "here", "him", "her"):
                frame.recipient = True
            j += 1
            continue
        if it.text in lx.CONTAINING and pending:
            # "a plate containing an egg and a tomato"
            j += 1
            while j < n:
                held, k = parse_np(items, j)
                if held is None:
                    break
                mentions.append(held)
                pending[-1].head.holds.append(held)
                j = k
                if j < n and items[j].conj == "and" and j + 1 < n and _np_start(items[j + 1]):
                    j += 1
                    continue
                break
            continue
        if it.neg:
            # "on the holder, not on the counter": a rejected alternative
            j += 1
            if j < n and items[j].prep is not None:
                _, j = parse_np(items, j + 1)
            continue
        if it.prep is not None and it.prep != "of" and not (
                it.particle is not None and (j + 1 >= n or not _np_start(items[j + 1]))):
            prep = it.prep
            head, k = parse_np(items, j + 1)
            if head is None:
                j += 1
                continue
            mentions.append(head)
            j = k
            if prep == "with" and pending and j + 1 < n and items[j].prep in ("in", "on") \
                    and items[j + 1].pron in ("it", "them") and not (
                        head.liquid is not None and head.noun is None):
                pending[-1].head.holds.append(head)     # "the bowl with the apple in it"
                j += 2
                continue
            if prep == "with":
                if head.liquid is not None:
                    frame.liquid = head.liquid
                    # "with coffee in it"
                    if j + 1 < n and items[j].prep == "in" and items[j + 1].pron is not None:
                        j += 2
                continue
            if prep == "for":
                continue
            if prep == "from":
                for t in last_np or pending[-1:]:
                    t.head.location.append(("from", head))
                continue
            if head.noun is not None and head.noun.concept.kind == "room" and prep in ("in", "at", "on"):
                # "the light in the kitchen": the room the user is in; "in a well lit
                # room": and how that room should be
                for stat, pos in head.filters:
                    if stat in (Stat.BRIGHT, Stat.SWITCH):
                        frame.room_states.append((Stat.BRIGHT, pos))
                continue
            waiting = [t for t in pending if not t.dest]
            if waiting:
                for t in waiting:
                    t.dest = [head, *head.alternatives]
                    t.prep = prep
            elif last_np:
                # a second place for the same objects: the first was where they are
                for t in last_np:
                    if t.dest and t.prep is not None:
                        t.head.location.append((t.prep, t.dest[0]))
                    t.dest = [head, *head.alternatives]
                    t.prep = prep
            elif frame.targets or pending:
                for t in pending:
                    t.dest = [head]
                    t.prep = prep
            else:
                frame.means = head
            continue
        if (it.particle is not None or it.state is not None) and (
                j + 1 >= n or not _np_start(items[j + 1]) or (items[j + 1].pron == "it" and False)):
            if it.particle in ("on", "off") or it.state is not None:
                if it.state is not None:
                    frame.state = it.state
                frame.particle = it.particle or frame.particle
            j += 1
            continue
        head, k = parse_np(items, j)
        if head is None:
            if k > j:
                j = k
                continue
            if it.verb is not None or it.copula:
                break
            j += 1
            continue
        mentions.append(head)
        if pending and head.noun is not None:
            _fix_ellipsis(pending[-1].head, head)
        t = Target(head)
        if last_np and items[j - 1].conj is None and items[j - 1].punct is None \
                and not pending[-1].dest:
            last_np = [t]
        else:
            last_np = [t] if not pending or pending[-1].dest else [*last_np, t]
        pending.append(t)
        j = k
    return j


def _verb_frame(items: list[Item], v: int, flags: dict[str, bool], mentions: list[Head],
                subjects: list[Target] | None = None) -> Frame:
    it = items[v]
    assert it.verb is not None
    sense = it.verb.sense
    frame = Frame(sense.act, it.verb.lemma, weak=sense.weak, negated=flags.get("neg", False),
                  text=" ".join(x.text for x in items))
    j = v + 1
    n = len(items)
    # a particle right after the verb ("turn on", "pick up", "throw away")
    if j < n and items[j].particle is not None:
        p = items[j].particle
        key = (it.verb.lemma, p)
        if key in lx.PARTICLE_VERBS:
            frame.act = lx.PARTICLE_VERBS[key].act
            frame.weak = lx.PARTICLE_VERBS[key].weak
            frame.particle = p
            j += 1
        elif (sense.act is Act.SWITCH and p in ("on", "off")) or (p in ("up", "down", "away", "out", "back", "over", "around", "aside") and items[j].prep is None):
            frame.particle = p
            j += 1
    pending: list[Target] = list(subjects or [])
    _parse_tail(items, j, frame, pending, mentions)
    frame.targets = pending
    if frame.act is Act.SWITCH:
        if frame.particle in ("on", "off"):
            frame.act = Act.SWITCH_ON if frame.particle == "on" else Act.SWITCH_OFF
        elif frame.state is not None and frame.state[0] is Stat.SWITCH:
            frame.act = Act.SWITCH_ON if frame.state[1] else Act.SWITCH_OFF
    if frame.act is Act.SWITCH and frame.particle is None and frame.state is None and \
            it.verb.lemma == "switch":
        frame.act = Act.TOGGLE
    return frame


def _state_frames(items: list[Item], mentions: list[Head], flags: dict[str, bool]) -> list[Frame]:
    """``NP [aux] predicate (, NP [aux] predicate)*``"""
    frames: list[Frame] = []
    j = 0
    n = len(items)
    while j < n and (items[j].text in ("could", "can", "would", "will", "should", "must", "may")
                     or items[j].conj is not None or items[j].punct is not None):
        if items[j].copula:
            flags["modal"] = True
        j += 1
    while j < n:
        subjects: list[Target] = []
        while j < n:
            head, k = parse_np(items, j)
            if head is None:
                break
            mentions.append(head)
            if subjects and head.noun is not None:
                _fix_ellipsis(subjects[-1].head, head)
            subjects.append(Target(head))
            j = k
            if j < n and (items[j].conj == "and" or items[j].punct == ",") and j + 1 < n \
                    and _np_start(items[j + 1]) and items[j + 1].verb is None:
                j += 1
                continue
            break
        if not subjects:
            break
        local = dict(flags)
        j = _skip_aux(items, j, local)
        if j >= n:
            break
        it = items[j]
        frame = Frame(None, "", targets=subjects, negated=local.get("neg", False),
                      too=local.get("too", False), text=" ".join(x.text for x in items))
        frame.report = not local.get("modal", False) and not flags.get("directive", False) \
            and any(x.copula and x.text in ("is", "are", "was", "were", "am") for x in items[:j]) \
            and not local.get("terse", False)
        is_participle = it.verb is not None and (it.verb.form in ("ed", "ing") or (
            it.verb.form == "base" and (local.get("modal") or it.text in lx.IRREGULAR_VERBS)))
        pp_here = it.prep is not None and j + 1 < n and _np_start(items[j + 1])
        if it.state is not None and not pp_here and not (
                it.verb is not None and it.verb.sense.act is Act.GO) and (
                it.verb is None or it.verb.form != "ed" or it.text in lx.STATES):
            frame.state = it.state
            j += 1
            # "with coffee in it", "in the sink"
            rest: list[Target] = []
            j = _parse_tail_until_next(items, j, frame, rest, mentions)
        elif it.verb is not None and (is_participle or it.verb.sense.act is Act.GO):
            sub = _verb_frame(items[j:], 0, {"neg": frame.negated}, mentions, subjects)
            end = len(items)
            for t in sub.targets:
                if t.head.pron in _REFLEXIVE or "by" in t.head.text:
                    frame.negated = False
            sub.targets = [t for t in sub.targets if t.head.pron not in _REFLEXIVE]
            if any(x.text in _REFLEXIVE for x in items[j:]) or "by themselves" in sub.text \
                    or "by itself" in sub.text:
                frame.negated = False
                frame.report = False
            frame.targets = sub.targets
            dest = next((t for t in sub.targets if t.dest), None)
            frame.act = sub.act
            frame.verb = sub.verb
            frame.particle = sub.particle
            frame.liquid = sub.liquid
            frame.means = sub.means
            frame.state = sub.state
            if sub.act is Act.GO or (sub.act in (Act.PLACE, Act.TRASH) and dest is not None):
                frame.act = Act.PLACE if sub.act is Act.GO else sub.act
                frame.report = False
                for t in subjects:
                    if dest is not None:
                        t.dest, t.prep = dest.dest, dest.prep
                    elif sub.targets and sub.targets[0].dest:
                        t.dest, t.prep = sub.targets[0].dest, sub.targets[0].prep
            if sub.act is Act.SWITCH and sub.particle in ("on", "off"):
                frame.act = Act.SWITCH_ON if sub.particle == "on" else Act.SWITCH_OFF
            elif sub.act is Act.SWITCH and it.text in ("switched", "turned") and sub.state:
                frame.act = Act.SWITCH_ON if sub.state[1] else Act.SWITCH_OFF
            if frame.act is Act.SWITCH_ON and it.text == "lit":
                frame.act = Act.SWITCH_ON
            j = end
        elif it.prep is not None or it.particle in ("on", "off"):
            if it.particle in ("on", "off") and (j + 1 >= n or not _np_start(items[j + 1])):
                frame.state = (Stat.SWITCH, it.particle == "on")
                j += 1
            else:
                frame.act = Act.PLACE
                rest = subjects
                j = _parse_tail_until_next(items, j, frame, rest, mentions)
                if frame.report and not any(t.dest for t in subjects):
                    frame.act = None
        else:
            frames.append(frame)
            break
        frames.append(frame)
        # "the laptop shut and the desk lamp off": another subject and predicate
        while j < n and (items[j].conj is not None or items[j].punct is not None):
            j += 1
    return [f for f in frames if f.act is not None or f.state is not None]


def _parse_tail_until_next(items: list[Item], j: int, frame: Frame, rest: list[Target],
                           mentions: list[Head]) -> int:
    """Prepositional phrases after a predicate, up to a conjunction that starts another
    subject ("bread sliced and the slices in the toaster")."""
    n = len(items)
    end = j
    while end < n:
        it = items[end]
        if (it.conj is not None or it.punct is not None) and end + 1 < n and _np_start(items[end + 1]) \
                and items[end + 1].prep is None:
            break
        end += 1
    pending = list(rest)
    _parse_tail(items[j:end], 0, frame, pending, mentions)
    return end


def parse_clause(clause: Clause) -> ParsedClause:
    """The frames of one clause (possibly none), and every noun phrase it mentions."""
    items = [i for i in clause.items if not (i.text in ("please", "kindly") and i.noun is None)]
    mentions: list[Head] = []
    flags: dict[str, bool] = {}
    items = _strip_preamble(items, flags)
    if clause.link in ("after", "before", "if", "by", "purpose", "while"):
        flags["directive"] = True
    # leading negation: "don't leave the lights on", "never turn on ..."
    while items and (items[0].neg or (items[0].text in ("do", "does", "did")
                     and len(items) > 1 and items[1].neg)):
        if items[0].neg:
            flags["neg"] = not flags.get("neg", False)
        items = items[1:]
    if items and items[0].text == "need" and len(items) > 1 and items[1].text == "to":
        items = items[2:]
    # "(robot 1) should slice ...", "(robot 2) will open ...": a modal before a verb
    while len(items) > 1 and items[0].text in ("should", "must", "will", "can", "shall", "could",
                                               "would", "to", "is", "needs", "has") \
            and ((items[1].verb is not None and items[1].noun is None) or items[1].text == "to"):
        items = items[1:]
    unknown: list[str] = []
    frames: list[Frame] = []
    if not items:
        return ParsedClause(clause, [], mentions, unknown)
    first = items[0]
    human = first.text in _HUMAN_SUBJECTS and first.noun is None
    if human:
        # "someone left the fridge open", "nobody needs the lights on", "i need X on Y"
        if first.text in ("nobody", "no"):
            flags["neg"] = not flags.get("neg", False)
        j = _skip_aux(items, 1 if first.text != "no" else 2, flags)
        wanted = items[j].verb if j < len(items) else None
        if wanted is not None and wanted.lemma in _WANT \
                and j + 1 < len(items) and items[j + 1].text != "to":
            # "i need the alarm clock on the desk", "i want the tv on": a wish about objects
            rest = items[j + 1:]
            wish = dict(flags, directive=True, terse=True)
            found = _state_frames(rest, mentions, wish)
            if not found:
                frame = _verb_frame(items, j, flags, mentions)
                frame.report = False
                found = [frame]
            frames.extend(found)
        elif j < len(items) and items[j].verb is not None:
            v = items[j]
            assert v.verb is not None
            frame = _verb_frame(items, j, flags, mentions)
            if v.verb.lemma in _WANT:
                frame.report = False
            elif not flags.get("modal") and v.verb.form in ("ed", "ing", "s") and \
                    clause.link not in ("if", "after", "before", "by"):
                frame.report = True
            frames.append(frame)
    elif first.verb is not None and (
            (first.verb.form in ("base", "ing") and (first.noun is None or _takes_object(items)))
            or (first.verb.form == "s" and clause.robot is not None)
            or (first.noun is None and first.state is None and first.verb.form != "s")):
        frames.append(_verb_frame(items, 0, flags, mentions))
    else:
        terse = not any(i.copula for i in items)
        flags["terse"] = terse
        if terse:
            flags["directive"] = True
        frames.extend(_state_frames(items, mentions, flags))
    for f in frames:
        if f.act is Act.CAUSE and f.verb in _WANT:
            f.report = False
    for h in mentions:
        unknown.extend(h.unknown)
    return ParsedClause(clause, frames, mentions, unknown)


def _takes_object(items: list[Item]) -> bool:
    from emboteam.pfg.offline.clauses import verb_here
    return verb_here(items, 0)
