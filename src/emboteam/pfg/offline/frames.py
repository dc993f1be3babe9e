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
from collections.abc import Callable
from dataclasses import dataclass, field

from pydantic import model_validator

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.acts import DISPOSAL, TOOLS
from emboteam.pfg.offline.clauses import Clause, team_subject, verb_here
from emboteam.pfg.offline.constructions import (
    DURATION,
    absent_from,
    causative_progressive,
    instrument_clause,
    light_verb,
    noun_phrase_wish,
    places_to_locations,
    with_as_and,
)
from emboteam.pfg.offline.knowledge import Strict, load, word_tables
from emboteam.pfg.offline.patterns import first_rule, pattern_tables
from emboteam.pfg.offline.phrases import (
    MODIFIER_PREPS,
    Frame,
    Head,
    ParsedClause,
    Target,
    fix_ellipsis,
    is_piece_word,
    list_end,
    np_list,
    np_start,
    parse_np,
    position_participle,
    predicate_at,
    predicate_start,
    skip_locative,
    unknown_words,
)
from emboteam.pfg.offline.tagger import Item
from emboteam.world.catalogue import load_catalogue

Act = lx.Act
Stat = lx.Stat


class _Framing(Strict):
    pattern: str
    why: str = ""


class PreambleFile(Strict):
    """``data/preamble.json``: politeness, hedges and framing that carry no content."""

    about: str = ""
    who: str
    preamble: tuple[_Framing, ...]
    trailing: str
    wish: str
    ask_for: str

    def compiled(self) -> tuple[list[re.Pattern[str]], re.Pattern[str], re.Pattern[str], re.Pattern[str]]:
        """The preamble patterns ("{who}" filled in), the trailing one, the wish and ask-for ones."""
        return ([re.compile(r"^(?:" + f.pattern.replace("{who}", self.who) + r")\b\s*") for f in self.preamble],
                re.compile(r"\s*\b(?:" + self.trailing + r")$"), re.compile(self.wish), re.compile(self.ask_for))

    @model_validator(mode="after")
    def _compiles(self) -> PreambleFile:
        for where, pattern in [("who", self.who), ("trailing", self.trailing), ("wish", self.wish),
                               ("ask_for", self.ask_for), *((f"preamble[{i}]", f.pattern)
                                                           for i, f in enumerate(self.preamble))]:
            try:
                re.compile(pattern.replace("{who}", self.who))
            except re.error as exc:
                raise ValueError(f"{where}: {pattern[:60]!r} is no regular expression: {exc}") from None
        return self


# --- preamble: politeness, hedges and framing that carry no content -------------------
_PREAMBLE, _TRAILING, _WISH, _ASK_FOR = load("preamble.json", PreambleFile).compiled()
_W = word_tables("frames")
_P = pattern_tables("frames")

#: sentence adverbs and hesitations that may come before the verb ("maybe throw the CD
#: away", "um, like, wash the mug", "honestly just close it")
_LEADING_ADVERBS = _W.set("leading_adverbs")


def _drop_leading_adverbs(items: list[Item], flags: dict[str, bool]) -> list[Item]:
    """The clause without the adverbs before its verb (only when a verb follows them).
    A leading "also" before objects alone ("after that, also the candle") marks the act
    before repeated on them."""
    k = 0
    while k < len(items) and (items[k].text in _LEADING_ADVERBS or items[k].punct is not None) \
            and items[k].noun is None:
        k += 1
    if 0 < k < len(items) and items[k].verb is not None and items[k].noun is None:
        return items[k:]
    if 0 < k < len(items) and any(x.text == "also" for x in items[:k]) and np_list(items[k:]):
        flags["also"] = True
        return items[k:]
    return items


def _strip_preamble(items: list[Item], flags: dict[str, bool]) -> list[Item]:
    items = _drop_leading_adverbs(items, flags)
    changed = True
    while changed and items:
        changed = False
        while items and (items[0].punct is not None or items[0].conj == "and"):
            items = items[1:]      # "oh, and the tomato too"
        text = " ".join(i.text for i in items)
        for pat in _PREAMBLE:
            m = pat.match(text)
            if m and m.end() > 0:
                if _WISH.match(text):
                    flags["directive"] = True
                    flags["wish_scope"] = True
                if _ASK_FOR.match(text):
                    flags["recipient"] = True     # "can I have the apple": give it to me
                k = _items_holding(items, len(text[: m.end()].split()))
                if k is not None:
                    # never drop a verb that begins the clause (the "so" of "so that" aside)
                    items = items[k:]
                    changed = True
                    break
    while items:
        text = " ".join(i.text for i in items)
        m = _TRAILING.search(text)
        if not m or (m.start() == 0 and len(items) == len(text.split()) == len(m.group().split())):
            break
        if m.group().strip() in ("too", "as well", "also"):
            flags["also"] = True      # "and the tomato too": the act before, on this
        k = _items_holding(items, len(m.group().split()), from_end=True)
        if k is None or k == len(items):
            break
        items = items[:-k]
    return items


def _items_holding(items: list[Item], n_words: int, from_end: bool = False) -> int | None:
    """How many items from the start (or the end) hold exactly the first (or last)
    ``n_words`` words; None when an item of several words straddles the cut."""
    used = 0
    for count, it in enumerate(reversed(items) if from_end else items, 1):
        used += len(it.text.split())
        if used >= n_words:
            return count if used == n_words else None
    return None


# --- clause parsing ---------------------------------------------------------------------
_HUMAN_SUBJECTS = _W.set("human_subjects")
_WANT = _W.set("want")
_REFLEXIVE = _W.set("reflexive")


#: what may stand between a subject and its predicate, and what each means
_AUX_RULES = _P.table("aux")


def _skip_aux(items: list[Item], j: int, frame_flags: dict[str, bool]) -> int:
    """Skip copulas, modals, negation and adverbs before a predicate, noting them in
    ``frame_flags`` (the rules of ``patterns.json``, ``frames -> aux``)."""
    while j < len(items):
        rule = first_rule(_AUX_RULES, items, j)
        if rule is None or rule.then == "stop":
            break
        if rule.then == "neg":
            frame_flags["neg"] = not frame_flags.get("neg", False)
        elif rule.then:
            frame_flags[rule.then] = True
        j += rule.advance
    return j


@dataclass
class _Tail:
    """The words after a verb being read: where the reader is, the frame it fills, the
    objects waiting for a place (``pending``), the objects of the last noun phrase list
    (``last_np``) and where the last destination ended."""

    items: list[Item]
    j: int
    frame: Frame
    pending: list[Target]
    mentions: list[Head]
    last_np: list[Target] = field(default_factory=list)
    dest_end: int = -1

    @property
    def it(self) -> Item:
        return self.items[self.j]

    def at(self, k: int) -> Item | None:
        """The item ``k`` after the current one, if any."""
        return self.items[self.j + k] if self.j + k < len(self.items) else None


_SEPARATOR, _FILLER_OR_RECIPIENT, _REJECTION, _SWITCHED_STATE, _IN_IT, _INSIDE_AT_END = (
    _P.pattern(name) for name in ("separator", "filler_or_recipient", "rejection", "switched_state", "in_it",
                                  "inside_at_end"))
_THEY_STATE, _BE_NEAR_START, _THEY_PUT_AWAY, _THEY_GO = (
    _P.pattern(name) for name in ("they_state", "be_near_start", "they_put_away", "they_go"))
#: a tail rule's decision: the words were read (go on), the tail ended, None: not this rule
_GO, _END = "go", "end"
TailRule = Callable[[_Tail], str | None]


def _separator(s: _Tail) -> str | None:
    """Conjunctions and punctuation; "the apple or the tomato": alternatives of the last
    object."""
    if not _SEPARATOR.at(s.items, s.j):
        return None
    if s.it.conj == "or" and s.pending:
        head, k = parse_np(s.items, s.j + 1)
        if head is not None:
            s.mentions.append(head)
            s.pending[-1].head.alternatives.append(head)
            s.j = k
            return _GO
    s.j += 1
    return _GO


def _filler_or_recipient(s: _Tail) -> str | None:
    """"please", "back", "away" (kept as the particle: "put it back"), and "me", "us",
    "here": the object ends up with the person."""
    it = s.it
    if not _FILLER_OR_RECIPIENT.at(s.items, s.j):
        return None
    if it.text in ("me", "us", "here", "him", "her"):
        s.frame.recipient = True
    if it.text in ("back", "away") and s.frame.particle is None:
        s.frame.particle = it.text
    s.j += 1
    return _GO


def _containing(s: _Tail) -> str | None:
    """"a plate containing an egg and a tomato": what the last object must hold."""
    if not (s.it.text in lx.CONTAINING and s.pending):
        return None
    items, n = s.items, len(s.items)
    s.j += 1
    while s.j < n:
        held, k = parse_np(items, s.j)
        if held is None:
            break
        s.mentions.append(held)
        s.pending[-1].head.holds.append(held)
        s.j = k
        if s.j < n and items[s.j].conj == "and" and s.j + 1 < n and np_start(items[s.j + 1]):
            s.j += 1
            continue
        break
    return _GO


def _rejected_alternative(s: _Tail) -> str | None:
    """"on the holder, not on the counter", "the tomato, not the apple", "but not the CD",
    "instead of the cup", "except (for) the apple": neither object nor mention."""
    it, items, n = s.it, s.items, len(s.items)
    after = _REJECTION.end(items, s.j)
    if after is None:
        return None
    s.j = after
    if s.j < n and items[s.j].text == "for":
        s.j += 1
    if s.j < n and items[s.j].prep is not None:
        _, s.j = parse_np(items, s.j + 1)
    elif s.j < n and np_start(items[s.j]) and items[s.j].verb is None:
        left_out, k = parse_np(items, s.j)
        s.j = max(k, s.j + 1)
        if left_out is not None and left_out.text.split()[-1:] == ["one"]:
            s.j = skip_locative(items, s.j)     # "not the one in the bin": which one, not a place
        whole = s.pending[-1].head if s.pending else None
        if left_out is not None and whole is not None and not it.neg and (
                whole.quant is not None or whole.plural):
            whole.excluded.append(left_out)   # "every light except the desk lamp"
    return _GO


def _manner_or_purpose(s: _Tail) -> str | None:
    """"cut it in half", "chop it into pieces": how, not where; "leave it to dry", "put it
    in water to soak": what for."""
    it, nxt, after = s.it, s.at(1), s.at(2)
    if it.prep == "in" and nxt is not None and is_piece_word(nxt) and (
            after is None or after.noun is None):
        s.j += 2
        if s.frame.act in (None, Act.CAUSE, Act.PLACE) and not s.frame.verb:
            # "I want the bread in slices": the state of being cut, not a place
            for t in s.pending:
                if not t.dest and t.state is None:
                    t.state = (Stat.SLICED, True)
            s.frame.act = None if s.frame.act is Act.PLACE else s.frame.act
            s.frame.state = s.frame.state or (Stat.SLICED, True)
        return _GO
    if it.text == "to" and nxt is not None and not np_start(nxt) and nxt.prep is None \
            and nxt.punct is None:
        s.j += 2
        return _GO
    return None


def _prepositional_phrase(s: _Tail) -> str | None:
    """A preposition and its noun phrase: an instrument or liquid ("with"), a purpose
    ("for"), where the object comes from ("from"), the room, or where it goes."""
    it, nxt = s.it, s.at(1)
    if it.prep is None or it.prep == "of" or (
            it.particle is not None and (nxt is None or not np_start(nxt))):
        return None
    prep, at = it.prep, s.j
    head, k = parse_np(s.items, s.j + 1)
    if head is None:
        _inside_the_one_named(s, prep)
        s.j += 1
        return _GO
    s.mentions.append(head)
    s.j = k
    if prep == "by" and head.noun is not None and head.noun.concept.kind == "object":
        prep = "near"      # "put the remote by the TV": beside it, like "next to"
    if prep == "with" and _holding(s, head):
        return _GO
    head.role = "place"
    if prep == "with":
        _with_phrase(s, head)
    elif prep == "from":
        for t in s.last_np or s.pending[-1:]:
            t.head.location.append(("from", head))
    elif head.noun is not None and head.noun.concept.kind == "room" and prep in ("in", "at", "on"):
        # "the light in the kitchen": the room the user is in; "in a well lit room": and
        # how that room should be
        for stat, pos in head.filters:
            if stat in (Stat.BRIGHT, Stat.SWITCH):
                s.frame.room_states.append((Stat.BRIGHT, pos))
    elif prep != "for":
        _destination(s, head, prep, at)
    elif _taken_for_a_place(s, head):
        # "pinch the cushion off the sofa for the armchair": taken to go there
        _destination(s, head, "on", at)
    return _GO


def _taken_for_a_place(s: _Tail, head: Head) -> bool:
    """Is "for the armchair" where a taken object goes: a taking or placing verb whose
    objects have no place yet (not a label: "things for the box: ..."), and furniture that can hold things (not "a knife for the
    bread", which is no receptacle)."""
    if s.frame.act not in (Act.PLACE, Act.HOLD) or not s.frame.verb or not s.pending or any(t.dest for t in s.pending) \
            or head.noun is None or head.noun.concept.kind != "object":
        return False
    cat = load_catalogue()
    return all(t in cat.types and cat.type(t).has("receptacle") and not cat.type(t).has("pickupable")
               for t in head.noun.concept.types)


def _inside_the_one_named(s: _Tail, prep: str) -> None:
    """"open the box, put the remote inside": in the one just named."""
    if s.frame.act in (Act.PLACE, Act.SLICE, Act.BREAK) and prep in ("in", "on") and s.it.text in (
            "inside", "in", "into", "on top", "on top of") and any(not t.dest for t in s.pending):
        # ("crack it in there": into the pan just named, as "crack it into the pan")
        there = Head(text="it", pron="it", role="dest")
        s.mentions.append(there)
        for t in s.pending:
            if not t.dest:
                t.dest, t.prep = [there], prep


def _holding(s: _Tail, head: Head) -> bool:
    """"the bowl with the apple in it": what the last object holds (then True)."""
    items, j = s.items, s.j
    if not s.pending or (head.liquid is not None and head.noun is None):
        return False
    if _IN_IT.at(items, j):
        s.pending[-1].head.holds.append(head)
        s.j += 2
        return True
    if _INSIDE_AT_END.at(items, j):
        s.pending[-1].head.holds.append(head)      # "with the apple inside"
        s.j += 1
        return True
    return False


def _with_phrase(s: _Tail, head: Head) -> None:
    """"with coffee (in it)": the liquid; "with the big knife", "using the stove": an
    instrument (maybe with where it is: "with the knife on the counter")."""
    items, n = s.items, len(s.items)
    if head.liquid is not None:
        s.frame.liquid = head.liquid
        if s.j + 1 < n and items[s.j].prep == "in" and items[s.j + 1].pron is not None:
            s.j += 2
    elif head.noun is not None:
        s.frame.instruments.append(head)
        s.j = skip_locative(items, s.j)


#: acts that move nothing: a place after their object says which object
_LOCATED_ACTS = frozenset({Act.SWITCH_ON, Act.SWITCH_OFF, Act.SWITCH, Act.OPEN, Act.CLOSE, Act.SLICE,
                           Act.CLEAN, Act.BREAK})


#: acts a place after the object can only pick out ("turn off the little one on the desk")
_SWITCH_ACTS = frozenset({Act.SWITCH_ON, Act.SWITCH_OFF, Act.SWITCH})


def _fixed_then_container(targets: list[Target], head: Head) -> bool:
    """"toss the roll on the counter in the bin": a counter cannot be in a bin, so the
    first place is where the roll is and the second where it goes (unlike "in the pan on
    the stove", where the pan can stand on the stove)."""
    cat = load_catalogue()
    first = next((t.dest[0] for t in targets if t.dest), None)
    if first is None or first.noun is None or head.noun is None:
        return False
    firsts = [x for x in first.noun.concept.types if x in cat.types]
    return bool(firsts) and not any(cat.type(x).has("pickupable") for x in firsts) \
        and bool(set(head.noun.concept.types) & DISPOSAL)


def _destination(s: _Tail, head: Head, prep: str, at: int) -> None:
    """Where the waiting objects go; right after a destination, a place that says where
    that destination is ("on a plate on the table", "in the cabinet under the sink"); a
    second place for the same objects makes the first where they were; with no object,
    the appliance is the means."""
    waiting = [t for t in s.pending if not t.dest]
    if waiting and ((prep in ("under", "beneath", "below", "near") and s.frame.act in _LOCATED_ACTS) or (
            prep in ("in", "on", "by", "next to") and s.frame.act in _SWITCH_ACTS)):
        # "fire up the burner under it": which burner, not where it goes
        head.role = "place"
        for t in waiting:
            t.head.location.append((prep, head))
        return
    stated = [k for k, t in enumerate(s.pending) if t.state is not None and not t.dest]
    if stated and stated[-1] < len(s.pending) - 1:
        # "get the bread sliced and the egg into the fridge": the place is the egg's only
        waiting = [t for t in s.pending[stated[-1] + 1:] if not t.dest]
    adjacent = at == s.dest_end
    if not waiting and prep in ("under", "near") and adjacent:
        return
    if not waiting and prep in ("near", "next to", "beside") and s.pending and all(t.dest for t in s.pending):
        return      # "on the bed, next to the teddy": where on the bed, not another place
    head.role = "dest"
    s.dest_end = s.j
    if waiting:
        for t in waiting:
            t.dest = [head, *head.alternatives]
            t.prep = prep
    elif (s.last_np or s.pending) and adjacent and prep in ("in", "on") and \
            s.items[at].text in ("in", "on", "inside", "at") \
            and not (prep == "in" and _fixed_then_container(s.last_np or s.pending, head)):
        # "(cooked) in the pan on the stove": where the destination is
        for t in s.last_np or s.pending:
            if t.dest:
                t.dest[0].location.append((prep, head))
        head.role = "place"
    elif s.last_np:
        for t in s.last_np:
            if t.dest and t.prep is not None:
                t.head.location.append((t.prep, t.dest[0]))
            t.dest = [head, *head.alternatives]
            t.prep = prep
    elif s.frame.targets or s.pending:
        for t in s.pending:
            t.dest = [head]
            t.prep = prep
    else:
        s.frame.means = head


def _particle_or_state(s: _Tail) -> str | None:
    """A trailing particle or state ("turn the TV on", "leave the fridge closed"): for the
    frame and each object that has none yet; "switch the lamp on and off": both, for the
    same objects (a contradiction the front end reports)."""
    it, nxt = s.it, s.at(1)
    if not ((it.particle is not None or it.state is not None)
            and (nxt is None or not np_start(nxt))):
        return None
    pending, frame = s.pending, s.frame
    if it.particle in ("on", "off") and pending and s.j > 0 and s.items[s.j - 1].conj == "and" \
            and all(t.particle not in (None, it.particle) for t in pending):
        pending.extend(Target(t.head, t.dest, t.prep, it.particle,
                              (Stat.SWITCH, it.particle == "on")) for t in list(pending))
        s.j += 1
        return _GO
    if it.particle in ("on", "off") or it.state is not None:
        if it.state is not None:
            frame.state = it.state
        frame.particle = it.particle or frame.particle
        for t in pending:
            if t.particle is not None or t.state is not None:
                continue
            if it.particle in ("on", "off"):
                t.particle = it.particle
                t.state = (Stat.SWITCH, it.particle == "on")
            elif it.state is not None:
                t.state = it.state
    s.j += 1
    return _GO


def _object(s: _Tail) -> str | None:
    """An object of the verb (joining the list of the last noun phrases, or starting a new
    one); a verb or copula that is no noun phrase ends the tail; any other word is
    skipped."""
    items, j, it = s.items, s.j, s.it
    head, k = parse_np(items, j)
    if head is None:
        if k > j:
            s.j = k
            return _GO
        if it.verb is not None or it.copula:
            return _END
        s.j += 1
        return _GO
    s.mentions.append(head)
    pending = s.pending
    if pending and head.noun is not None:
        fix_ellipsis(pending[-1].head, head)
    t = Target(head)
    if s.last_np and items[j - 1].conj is None and items[j - 1].punct is None \
            and not pending[-1].dest:
        s.last_np = [t]
    else:
        s.last_np = [t] if not pending or pending[-1].dest else [*s.last_np, t]
    pending.append(t)
    s.j = k
    return _GO


def _switched_state(s: _Tail) -> str | None:
    """"get the fridge closed and the light switched off": "switched/turned on/off" after
    an object is that object's state."""
    nxt = s.at(1)
    if not _SWITCHED_STATE.at(s.items, s.j) or nxt is None or not s.pending:
        return None
    t = s.pending[-1]
    if t.state is not None or t.particle is not None:
        return None
    t.particle = nxt.particle
    t.state = (Stat.SWITCH, nxt.particle == "on")
    s.j += 2
    return _GO


#: the rules that read what follows a verb, in order: the first that applies decides
TAIL_RULES: tuple[TailRule, ...] = (
    _separator, _filler_or_recipient, _containing, _rejected_alternative, _manner_or_purpose,
    _prepositional_phrase, _particle_or_state, _switched_state, _object,
)


def _parse_tail(items: list[Item], j: int, frame: Frame, pending: list[Target],
                mentions: list[Head]) -> int:
    """Objects, prepositional phrases and a trailing particle or state after a verb
    (:data:`TAIL_RULES`); returns the index where the tail ends."""
    s = _Tail(items, j, frame, pending, mentions)
    while s.j < len(items):
        decision = next(d for rule in TAIL_RULES if (d := rule(s)) is not None)
        if decision == _END:
            break
    return s.j


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


def _state_word_at(items: list[Item], k: int) -> bool:
    """Is the predicate at ``k`` a bare state ("sliced", "off"), the predicate of its own
    list item ("the apple in the fridge, the bread sliced"), not one the list shares ("the
    bread on the counter and the egg on the table need to go ...")?"""
    if k >= len(items):
        return False
    it = items[k]
    return it.state is not None and not it.copula and (it.verb is None or it.verb.form == "ed")


#: what may follow "goes" for "in the one just named": "goes in", "goes back in there"
_BARE_IN = _W.set("bare_in")


def _bare_in(items: list[Item], k: int) -> bool:
    """Do only "in"-words follow a verb of going ("the apple goes in", "goes back inside")?"""
    words = [x.text for x in items[k:] if x.punct is None]
    return bool(words) and words[0] in ("in", "inside", "back") and any(w in ("in", "inside") for w in words) \
        and all(w in _BARE_IN for w in words)


def _subject_list(items: list[Item], j: int, mentions: list[Head]) -> tuple[list[Target], int]:
    """The coordinated subjects at ``j`` ("the laptop, the lamp and the TV") and the index
    after them."""
    n = len(items)
    subjects: list[Target] = []
    while j < n:
        head, k = parse_np(items, j)
        if head is None:
            break
        mentions.append(head)
        if subjects and head.noun is not None:
            fix_ellipsis(subjects[-1].head, head)
        subjects.append(Target(head))
        j = k
        # "the bread on the counter and the egg on the table need to go ...": a place
        # inside a list of subjects that a predicate follows describes its subject
        if j + 1 < n and items[j].prep in MODIFIER_PREPS and np_start(items[j + 1]) \
                and predicate_at(items, list_end(items, j)) \
                and not _state_word_at(items, list_end(items, j)):
            land, m = parse_np(items, j + 1)
            if land is not None and m < n and (items[m].conj == "and" or items[m].punct == ","):
                land.role = "place"
                mentions.append(land)
                head.location.append((str(items[j].prep), land))
                j = m
        if j < n and (items[j].conj == "and" or items[j].punct == ",") and j + 1 < n \
                and np_start(items[j + 1]) and (items[j + 1].verb is None or (
                    # "lamp and light off": a noun that could be a verb, before its state
                    items[j + 1].noun is not None and j + 2 < n
                    and (items[j + 2].state is not None or items[j + 2].particle is not None))):
            j += 1
            continue
        break
    return subjects, j


@dataclass
class _Statement:
    """A clause of subjects and their predicates being read: the frames so far, and those
    that only say where things come from (``sources``)."""

    items: list[Item]
    mentions: list[Head]
    frames: list[Frame] = field(default_factory=list)
    sources: list[Frame] = field(default_factory=list)


#: a predicate rule's decision: the index after the predicate, whether its frame is kept,
#: whether another subject may follow; None: not this rule
_Read = tuple[int, bool, bool]


def _state_predicate(st: _Statement, j: int, frame: Frame, subjects: list[Target],
                     local: dict[str, bool]) -> _Read | None:
    """"the fridge closed", "the book should be open on the desk" (and placed there)."""
    items, n, it = st.items, len(st.items), st.items[j]
    pp_here = it.prep is not None and j + 1 < n and np_start(items[j + 1])
    if it.state is None or pp_here or (it.verb is not None and it.verb.sense.act is Act.GO) or not (
            it.verb is None or it.verb.form != "ed" or it.text in lx.STATES):
        return None
    frame.state = it.state
    rest = [Target(t.head) for t in subjects]
    j = _parse_tail_until_next(items, j + 1, frame, rest, st.mentions)    # "with coffee in it", "in the sink"
    placed = [t for t in rest if t.dest]
    if placed and not frame.report:
        st.frames.append(Frame(Act.PLACE, "put", placed, text=frame.text))
    return j, True, True


def _posture_predicate(st: _Statement, j: int, frame: Frame, subjects: list[Target],
                       local: dict[str, bool]) -> _Read | None:
    """"the fork and spoon sitting in the sink, ...": where they are, no request."""
    it = st.items[j]
    if not (position_participle(it) and it.verb is not None and it.verb.form == "ing" and not local.get("modal")):
        return None
    sub = _verb_frame(st.items[j:], 0, {"neg": frame.negated}, st.mentions, subjects)
    for t in subjects:
        for d in (x for tt in sub.targets for x in tt.dest):
            d.role = "place"
            t.head.location.append(("in", d))
    return len(st.items), False, False


def _verb_predicate(st: _Statement, j: int, frame: Frame, subjects: list[Target],
                    local: dict[str, bool]) -> _Read | None:
    """A participle or a verb of going: "the bread needs to be sliced", "the fork goes in
    the drawer", "the potato won't cook itself"."""
    items, it = st.items, st.items[j]
    if it.verb is None or not (it.verb.form in ("ed", "ing") or it.verb.sense.act is Act.GO or (
            it.verb.form == "base" and (local.get("modal") or it.text in lx.IRREGULAR_VERBS))):
        return None
    sub = _verb_frame(items[j:], 0, {"neg": frame.negated}, st.mentions, subjects)
    for t in sub.targets:
        if t.head.pron in _REFLEXIVE or "by" in t.head.text:
            frame.negated = False
    sub.targets = [t for t in sub.targets if t.head.pron not in _REFLEXIVE]
    if any(x.text in _REFLEXIVE for x in items[j:]) or "by themselves" in sub.text or "by itself" in sub.text:
        frame.negated = False
        frame.report = False
    frame.targets = sub.targets
    dest = next((t for t in sub.targets if t.dest), None)
    for name in ("act", "verb", "particle", "liquid", "means", "state"):
        setattr(frame, name, getattr(sub, name))
    if sub.act is Act.GO and dest is None and _bare_in(items, j + 1):
        # "open the fridge; the apple goes in": in the one just named
        there = Head(text="it", pron="it", role="dest")
        st.mentions.append(there)
        frame.act, frame.report = Act.PLACE, False
        for t in subjects:
            t.dest, t.prep = [there], "in"
    elif sub.act is Act.GO and dest is None:
        frame.act = None         # "the toaster stays": leave it as it is
    elif dest is not None and sub.act in (Act.GO, Act.PLACE, Act.TRASH):
        frame.act = Act.PLACE if sub.act is Act.GO else sub.act
        frame.report = False
        for t in subjects:
            t.dest, t.prep = dest.dest, dest.prep
    return len(items), True, True


def _blinds_predicate(st: _Statement, j: int, frame: Frame, subjects: list[Target],
                      local: dict[str, bool]) -> _Read | None:
    """"blinds down": closed; "blinds up": open."""
    items, it = st.items, st.items[j]
    if it.particle in ("up", "down") and (j + 1 >= len(items) or not np_start(items[j + 1])) \
            and any(t.head.noun is not None and "Blinds" in t.head.noun.concept.types for t in subjects):
        frame.state = (Stat.OPEN, it.particle == "up")
        return j + 1, True, True
    return None


def _place_predicate(st: _Statement, j: int, frame: Frame, subjects: list[Target],
                     local: dict[str, bool]) -> _Read | None:
    """"bread on plate", "the loo roll off the floor (and onto the holder)" ("lights off" is a
    state: :func:`_state_predicate`)."""
    items, it = st.items, st.items[j]
    if it.prep is None and it.particle not in ("on", "off"):
        return None
    frame.act = Act.PLACE
    j = _parse_tail_until_next(items, j, frame, subjects, st.mentions)
    if frame.report and not any(t.dest for t in subjects):
        frame.act = None
    elif it.prep in ("off", "from", "out of") and not any(t.dest for t in subjects):
        st.sources.append(frame)
    return j, True, True


#: what may follow the subjects, in order: the first rule that applies reads the predicate;
#: none: the frame as it is ends the statement
PREDICATE_RULES: tuple[Callable[[_Statement, int, Frame, list[Target], dict[str, bool]], _Read | None], ...] = (
    _state_predicate, _posture_predicate, _verb_predicate, _blinds_predicate, _place_predicate,
)


def _state_frames(items: list[Item], mentions: list[Head], flags: dict[str, bool]) -> list[Frame]:
    """``NP [aux] predicate (, NP [aux] predicate)*`` (:data:`PREDICATE_RULES`)."""
    st = _Statement(items, mentions)
    j = 0
    n = len(items)
    while j < n and (items[j].text in ("could", "can", "would", "will", "should", "must", "may")
                     or items[j].conj is not None or items[j].punct is not None):
        if items[j].copula:
            flags["modal"] = True
        j += 1
    while j < n:
        subjects, j = _subject_list(items, j, mentions)
        if not subjects:
            break
        k_subj = j
        j = _locative_modifiers(items, j, subjects, mentions)
        if j + 2 < n and items[j].punct is not None and items[j + 1].prep in ("onto", "into", "in", "on", "to") \
                and np_start(items[j + 2]):
            j += 1      # "teddy bear, book and mug - onto the coffee table": the dash is no boundary
        local = dict(flags)
        j = _skip_aux(items, j, local)
        if j >= n:
            break
        frame = Frame(None, "", targets=subjects, negated=local.get("neg", False),
                      too=local.get("too", False), text=" ".join(x.text for x in items))
        frame.report = not local.get("modal", False) and not flags.get("directive", False) \
            and any((x.copula and x.text in ("is", "are", "was", "were", "am", "been"))
                    or x.text in ("has", "have") for x in items[k_subj:j]) \
            and not local.get("terse", False)
        j, kept, more_subjects = next((r for rule in PREDICATE_RULES
                                       if (r := rule(st, j, frame, subjects, local)) is not None), (j, True, False))
        if kept:
            st.frames.append(frame)
        if not more_subjects:
            break
        # "the laptop shut and the desk lamp off": another subject and predicate
        while j < n and (items[j].conj is not None or items[j].punct is not None):
            j += 1
        # "the bread needs to be sliced, toasted and put on a plate": more predicates of
        # the same subjects
        if j < n and not np_start(items[j]) and (items[j].verb is not None
                                                  or items[j].state is not None
                                                  or predicate_start(items, j)):
            more = _state_frames([*items[:k_subj], *items[j:]], [], dict(flags))
            mentions.extend(h for f in more for t in f.targets for h in (t.head, *t.dest)
                            if h not in mentions)
            st.frames.extend(more)
            break
    # "loo roll off the floor and onto the holder": where it comes from, when a later
    # predicate says where it goes
    moved = any(f.act is Act.PLACE and any(t.dest for t in f.targets) for f in st.frames)
    return [f for f in st.frames if (f.act is not None or f.state is not None)
            and not (moved and f in st.sources)]


def _after_modifiers(items: list[Item], k: int) -> int:
    """The index after places chained at ``k`` ("on the table by the coffee machine")."""
    n = len(items)
    while k + 1 < n and items[k].prep in MODIFIER_PREPS and np_start(items[k + 1]):
        land, m = parse_np(items, k + 1)
        if land is None or m <= k + 1:
            break
        k = m
    return k


def _locative_modifiers(items: list[Item], j: int, subjects: list[Target],
                        mentions: list[Head]) -> int:
    """"the mug on the counter needs to go in the sink", "the cups in the cabinet belong
    on the table": a place between a subject and its predicate says where the subject is
    now (it picks the instance), never where it goes. "bread on plate" (no predicate
    after it) stays a placement."""
    n = len(items)
    while True:
        p = j
        if p + 2 < n and position_participle(items[p]) and items[p + 1].prep in MODIFIER_PREPS:
            p += 1          # "the lettuce sitting on the counter should ..."
        if p + 2 < n and items[p].text in ("up", "down", "over", "back") and items[p + 1].prep in MODIFIER_PREPS:
            p += 1          # "the alarm clock up on the shelf should ..."
        if not (p + 1 < n and items[p].prep in MODIFIER_PREPS and np_start(items[p + 1])):
            break
        land, k = parse_np(items, p + 1)
        if land is None or not predicate_at(items, _after_modifiers(items, k)):
            break
        j = p
        land.role = "place"
        mentions.append(land)
        for t in subjects:
            if not t.head.location:
                t.head.location.append((str(items[j].prep), land))
        j = k
    return j


def _parse_tail_until_next(items: list[Item], j: int, frame: Frame, rest: list[Target],
                           mentions: list[Head]) -> int:
    """Prepositional phrases after a predicate, up to a conjunction that starts another
    subject ("bread sliced and the slices in the toaster")."""
    n = len(items)
    end = j
    while end < n:
        it = items[end]
        if (it.conj is not None or it.punct is not None) and end + 1 < n and (
                (np_start(items[end + 1]) and items[end + 1].prep is None)
                or (it.conj is not None and predicate_start(items, end + 1))):
            break     # "the mug clean and on the desk": another predicate
        end += 1
    pending = list(rest)
    _parse_tail(items[j:end], 0, frame, pending, mentions)
    return end


def parse_clause(clause: Clause, directive: bool = False) -> ParsedClause:
    """The frames of one clause (possibly none), and every noun phrase it mentions.
    ``directive``: the clause continues a wish ("make sure X is closed, Y is off")."""
    items = [i for i in clause.items if not (i.text in ("please", "kindly") and i.noun is None)]
    mentions: list[Head] = []
    flags: dict[str, bool] = {"directive": True, "wish_scope": True} if directive else {}
    items = _strip_preamble(items, flags)
    parsed = _parse_items(clause, items, mentions, flags)
    parsed.directive = flags.get("wish_scope", False)
    return parsed


#: verbs that stand for the verb before: "so does the tomato", "the egg should too"
_PRO_VERBS = _W.set("pro_verbs")


def _parse_items(clause: Clause, items: list[Item], mentions: list[Head],
                 flags: dict[str, bool]) -> ParsedClause:
    also = _pro_verb_clause(clause, items, mentions)
    if also is not None:
        return also
    if flags.get("also") and len(items) > 1 and items[-1].text in _PRO_VERBS:
        items = items[:-1]
    if clause.link in ("after", "before", "if", "by", "purpose", "while"):
        flags["directive"] = True
    items = _why_question(items)
    asked = _yes_no_question(items)
    if asked is not None:
        mentions.append(asked)
        return ParsedClause(clause, [], mentions, unknown_words(mentions))
    items = _clause_proper(items, flags)
    if not items:
        return ParsedClause(clause, [], mentions, [])
    items = causative_progressive(light_verb(items))
    for reader in CLAUSE_READERS:
        read = reader(clause, items, mentions, flags)
        if read is not None:
            return read
    frames = _frames(clause, items, mentions, flags)
    if isinstance(frames, ParsedClause):
        return frames
    timed = bool(DURATION.search(" ".join(x.text for x in items)))
    for f in frames:
        f.timed = timed
        if f.act is Act.CAUSE and f.verb in _WANT:
            f.report = False
            f.wish = True
        if flags.get("recipient"):
            f.recipient = True
        if f.report:
            places_to_locations(f)
    return ParsedClause(clause, frames, mentions, unknown_words(mentions))


def _pro_verb_clause(clause: Clause, items: list[Item], mentions: list[Head]) -> ParsedClause | None:
    """"... and so does the tomato", "the tomato does too": the act before, on this."""
    if items and items[0].text in _PRO_VERBS and clause.link == "purpose":
        heads = np_list(items[1:])
        if heads:
            mentions.extend(heads)
            return ParsedClause(clause, [], mentions, unknown_words(mentions), also=heads)
    return None


_NOBODY, _LEADING_NEGATION, _NEED_TO, _MODAL_BEFORE_VERB, _THERE_IS = (_P.pattern(name) for name in (
    "nobody", "leading_negation", "need_to", "modal_before_verb", "there_is"))


def _clause_proper(items: list[Item], flags: dict[str, bool]) -> list[Item]:
    """The clause without what comes before its verb or subject: a rejected topic, a
    leading negation (noted in ``flags``), "need to", a team member as subject, a modal."""
    # leading negation: "don't leave the lights on", "never turn on ..." ("nobody", "no
    # one" are subjects: "nobody closed the fridge" is read with its verb below)
    nobody = _NOBODY.at(items)
    items = _without_rejected_topic(items)
    while not nobody and _LEADING_NEGATION.at(items):
        if items[0].neg:
            flags["neg"] = not flags.get("neg", False)
        items = items[1:]
    items = items[_NEED_TO.end(items) or 0:]
    # "one of you slices the bread", "the other should open the fridge": the team
    # member is left to the planner, the verb is the act
    k = team_subject(items, 0)
    if 0 < k < len(items) and (items[k].verb is not None or items[k].copula):
        items = items[k:]
        flags["subject"] = True
    # "(robot 1) should slice ...", "(robot 2) will open ...": a modal before a verb
    while _MODAL_BEFORE_VERB.at(items):
        items = items[1:]
    return items


def _there_is(clause: Clause, items: list[Item], mentions: list[Head],
              flags: dict[str, bool]) -> ParsedClause | None:
    """"there's a bottle of wine in the cupboard": introduces a referent and where it is
    (or, "there's no milk in the fridge", says what is missing)."""
    if not _THERE_IS.at(items):
        return None
    missing = absent_from(items[2:], clause.text)
    if missing is not None:
        return ParsedClause(clause, [missing], mentions, unknown_words(mentions))
    found = _state_frames(items[2:], mentions, dict(flags, directive=True, terse=True))
    for f in found:
        places_to_locations(f)
    return ParsedClause(clause, [], mentions, unknown_words(mentions))


def _means_only(clause: Clause, items: list[Item], mentions: list[Head],
                flags: dict[str, bool]) -> ParsedClause | None:
    """"the microwave is fine": the clause only names the means."""
    means = instrument_clause(items, mentions)
    return ParsedClause(clause, [], mentions, [], means=means) if means is not None else None


def _frames(clause: Clause, items: list[Item], mentions: list[Head],
            flags: dict[str, bool]) -> list[Frame] | ParsedClause:
    """The frames of a clause by its shape: a person as subject, a verb first, else a
    statement or wish about objects."""
    first = items[0]
    if first.text in _HUMAN_SUBJECTS and first.noun is None and not (
            first.text in ("they", "them") and _things_they(items)):
        return _human_subject(clause, items, mentions, flags)
    if first.verb is not None and (
            (first.verb.form in ("base", "ing") and (first.noun is None or verb_here(items, 0)))
            or (first.verb.form == "s" and (clause.robot is not None or flags.get("subject")))
            or (first.noun is None and first.state is None and first.verb.form != "s")):
        return [_verb_frame(items, 0, flags, mentions)]
    terse = not any(i.copula for i in items)
    flags["terse"] = terse
    wished = noun_phrase_wish(items, mentions)
    if wished is not None and flags.get("neg"):
        return []       # "No coffee today": the dish is called off, nothing is made
    frames = [wished] if wished is not None else _state_frames(items, mentions, flags)
    if not frames and flags.get("also"):
        heads = np_list(items)
        if heads:
            mentions.extend(h for h in heads if h not in mentions)
            return ParsedClause(clause, [], mentions, unknown_words(mentions), also=heads)
    return frames


def _human_subject(clause: Clause, items: list[Item], mentions: list[Head],
                   flags: dict[str, bool]) -> list[Frame]:
    """"someone left the fridge open", "nobody needs the lights on", "i need X on Y"."""
    first = items[0]
    if first.text in ("nobody", "no"):
        flags["neg"] = not flags.get("neg", False)
    j = _skip_aux(items, 1 if first.text != "no" else 2, flags)
    wanted = items[j].verb if j < len(items) else None
    if wanted is not None and wanted.lemma in _WANT \
            and j + 1 < len(items) and items[j + 1].text != "to":
        # "i need the alarm clock on the desk", "i want the tv on": a wish about objects
        rest = with_as_and(items[j + 1:])
        found = _state_frames(rest, mentions, dict(flags, directive=True, terse=True))
        if not found:
            frame = _verb_frame([*items[:j + 1], *rest], j, flags, mentions)
            frame.report = False
            found = [frame]
        return found
    if not (j < len(items) and items[j].verb is not None):
        return []
    v = items[j].verb
    assert v is not None
    frame = _verb_frame(items, j, flags, mentions)
    before = {x.text for x in items[1:j]}
    if first.text in ("i", "we") and ((before & {"was", "were"} and before & {"going", "gonna"})
                                      or (flags.get("perfect") and not flags.get("modal"))):
        # "I was going to bake": what did not happen; "I've left my phone on the
        # bed": what was done
        frame.report = frame.past = True
    elif v.lemma in _WANT:
        frame.report = False
    elif not flags.get("modal") and v.form in ("ed", "ing", "s") and \
            clause.link not in ("if", "after", "before", "by"):
        frame.report = True
        frame.past = v.form == "ed"
    return [frame]


def _without_rejected_topic(items: list[Item]) -> list[Item]:
    """"Not the pen - the pencil goes in the drawer": a rejected alternative before the
    clause proper (a negated noun phrase and a comma or dash) is left out."""
    if len(items) < 3 or items[0].text != "not" or not np_start(items[1]):
        return items
    _, end = parse_np(items, 1)
    if end > 1 and end < len(items) - 1 and items[end].punct is not None:
        return items[end + 1:]
    return items


def _yes_no_question(items: list[Item]) -> Head | None:
    """"Is the laptop still open? Close it if so.": a yes/no question about a state asks
    nothing by itself; it names what a later pronoun refers to."""
    if len(items) < 3 or items[0].text not in ("is", "are") or not np_start(items[1]):
        return None
    head, end = parse_np(items, 1)
    if head is None or any(i.verb is not None and i.state is None for i in items[end:]):
        return None
    return head


def _why_question(items: list[Item]) -> list[Item]:
    """"Why is the fridge open?", "why are the lights still on": a question about a state
    is a complaint about it, read as the statement "the fridge is open"."""
    if len(items) < 3 or items[0].text != "why" or items[1].text not in ("is", "are"):
        return items
    _, end = parse_np(items, 2)
    if end == 2:
        return items
    return [*items[2:end], items[1], *items[end:]]


def _tool_on(clause: Clause, items: list[Item], mentions: list[Head],
             flags: dict[str, bool]) -> ParsedClause | None:
    """"use a knife on the bread": what the tool does, to what it is used on (not "use the
    knife on the counter", where the counter says which knife)."""
    if items[0].text not in ("use", "using") or items[0].noun is not None:
        return None
    head, k = parse_np(items, 1)
    n = len(items)
    # ("use everything": a word of no type names no tool)
    tool = TOOLS.get(head.noun.concept.types[0]) if head is not None and head.noun is not None \
        and head.noun.concept.types else None
    if head is None or tool is None or not (k + 1 < n and items[k].prep == "on" and np_start(items[k + 1])):
        return None
    target, _ = parse_np(items, k + 1)
    cat = load_catalogue()
    if target is None or target.noun is None or not any(
            t in cat.types and cat.type(t).has(tool.used_on) for t in target.noun.concept.types):
        return None
    head.role = "place"
    mentions.extend([head, target])
    frame = Frame(tool.act, "use", [Target(target)], text=" ".join(i.text for i in items))
    frame.instruments.append(head)
    return ParsedClause(clause, [frame], mentions, [])


def _things_they(items: list[Item]) -> bool:
    """Is "they" things, not people: in a state ("they're clean") or going somewhere
    ("they can go in a drawer", "they both belong on the shelf")?"""
    return _THEY_STATE.at(items) or (_BE_NEAR_START.at(items) and _THEY_PUT_AWAY.at(items)) or _THEY_GO.at(items)


def _use_to(clause: Clause, items: list[Item], mentions: list[Head],
            flags: dict[str, bool]) -> ParsedClause | None:
    """"use the stove to fry the egg", "using the microwave, heat the soup": the act of the
    rest of the clause, with the named appliance as its means."""
    if items[0].text not in ("use", "using") or items[0].noun is not None:
        return None
    head, k = parse_np(items, 1)
    n = len(items)
    k = skip_locative(items, k)     # "use the knife on the counter to slice the bread"
    while k < n and (items[k].text in ("to", "and", "for") or items[k].punct is not None):
        k += 1
    if head is None or k >= n or items[k].verb is None:
        return None
    head.role = "place"
    inner = parse_clause(Clause(items[k:], clause.link, clause.robot, clause.sentence,
                                clause.initial))
    for f in inner.frames:
        f.means = f.means or head
    inner.mentions.insert(0, head)
    return inner

#: readers of clause shapes tried before the grammar proper, in order: the first that
#: reads the clause decides
CLAUSE_READERS: tuple[Callable[[Clause, list[Item], list[Head], dict[str, bool]], ParsedClause | None], ...] = (
    _there_is, _tool_on, _means_only, _use_to,
)

