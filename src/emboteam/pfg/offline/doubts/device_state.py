"""Point of doubt: which end state a device is asked to be in, read from its own words.

The words after a device's name say its state ("the lamp you put it off", "the blinds stay
down", "the candle stays unlit", "the big light of" heard for off), flipped by a negation
("is never left on"), carried to the next device ("the telly is off and so is the desk
lamp"), or said to be as it is now ("the telly is off, same as now"); a purpose implies one
("watching the news": the TV on). A switch word of a thing that only opens, or an open word
of a thing that only switches, is read in the other family ("close the light" = off,
"open the water" = on). The words are data (``state_words.json``); this module is the
composition. Where the words settle a state the reading lacks or reads the other way, the
alternative gives it, priced by its label (how the state was said) in ``priors.json``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.context import type_props as _props
from emboteam.pfg.offline.doubts.rule_words import find, load_rule_words, sentence_bounds, starts_at
from emboteam.pfg.offline.doubts.state_words import (
    StateWords,
    load_state_words,
    purpose_phrases,
    state_word_index,
)
from emboteam.pfg.offline.doubts.wants import one_object
from emboteam.pfg.offline.lexicon import Act
from emboteam.pfg.offline.tagger import Item
from emboteam.pfg.sentences import clause
from emboteam.world.goals import Predicate

KIND = "device_state"
P = Predicate
_PRED = {("switch", True): P.switched_on, ("switch", False): P.switched_off,
         ("open", True): P.open, ("open", False): P.closed}
_PROP = {"switch": "toggleable", "open": "openable"}
_OTHER = {"switch": "open", "open": "switch"}
_ACTS: dict[Act, tuple[str, bool]] = {Act.SWITCH_ON: ("switch", True), Act.SWITCH_OFF: ("switch", False),
         Act.OPEN: ("open", True), Act.CLOSE: ("open", False)}


@dataclass(frozen=True)
class Said:
    """A state the words give a device: its family, polarity and how it was said."""

    family: str
    polarity: bool
    label: str
    #: said by a verb ("close it"): a later act on the device settles it
    act: bool = False


def _family(type_: str, family: str) -> str | None:
    """The family a state word of ``family`` names for ``type_``: its own, or, for an open
    word of a thing that only switches, the switch (a calque: "close the light", "open
    the water"; a switch word never opens: "the kettle on" is on the stove)."""
    props = _props(type_)
    if _PROP[family] in props:
        return family
    return "switch" if family == "open" and type_ in load_state_words().calque_types else None


def _governs_another(items: Sequence[Item], j: int, words: StateWords) -> bool:
    """Whether the word at ``j`` takes a noun phrase of its own ("off the bed", "close
    the box"): then it says nothing of the device before it ("that one" is the device)."""
    if j + 1 >= len(items):
        return False
    nxt = items[j + 1]
    if nxt.text in ("that", "this") and j + 2 < len(items) and items[j + 2].text == "one":
        return False
    if items[j].verb is None and nxt.pron is not None:
        return True             # "off it", "on them": a preposition
    if items[j].verb is not None and nxt.text in state_word_index() and j + 2 < len(items):
        nxt = items[j + 2]      # "shut off the light": a verb and its particle
    return nxt.text in words.before_object or (nxt.noun is not None and nxt.pron is None)


def _word_state(items: Sequence[Item], j: int, words: StateWords, type_: str) -> Said | None:
    """The state the word at ``j`` says of a device of ``type_``, if any."""
    item = items[j]
    index = state_word_index()
    # a state word the tagger spelt into another ("unlit" -> "unit")
    entry = index.get(item.corrected_from or "") or index.get(item.text)
    if entry is not None and j > 0 and items[j - 1].text in words.particle_of:
        return None     # "hang on", "get on with it"
    if entry is not None and (not entry.types or type_ in entry.types):
        family, polarity = str(entry.family), entry.polarity
        label = "said" if entry.certain else "heard"
    elif item.verb is not None and item.verb.sense.act in _ACTS:
        (family, polarity), label = _ACTS[item.verb.sense.act], "said"
    else:
        return None
    if _governs_another(items, j, words):
        return None
    if entry is not None and not entry.certain and j + 1 < len(items) and items[j + 1].punct is None \
            and items[j + 1].text not in words.heard_end:
        return None     # "for a couple of minutes": "of" heard for "off" only at a clause's end
    fam = _family(type_, family)
    return Said(fam, polarity, label, act=entry is None or item.verb is not None) if fam is not None else None


def _modifier(ctx: DoubtContext, m: int, lo: int, words: StateWords) -> bool:
    """Whether the thing named at ``m`` only says which device ("the lamp on the desk"):
    a preposition of ``modifier_preps`` just before it (a determiner between; not "in
    the safe": a destination)."""
    k = m - 1
    if k >= lo and ctx.items[k].det:
        k -= 1
    return k >= lo and ctx.items[k].text in words.modifier_preps


def _own_words(ctx: DoubtContext, k: int, type_: str, words: StateWords, named: set[int]) -> Said | None:
    """The state said after the device named at ``k`` in its sentence: before the next
    thing named (a place that says which device does not count) or a stop word."""
    start, end = sentence_bounds(ctx.items, k)
    if end < len(ctx.items) and ctx.items[end].punct == "?":
        return None     # "is the light on?": a question
    corrections = set(load_rule_words().correction.cues)
    if end + 1 < len(ctx.items) and ctx.items[end + 1].text in corrections:
        _, end = sentence_bounds(ctx.items, end + 1)    # "open it. Wait no, keep it shut": it goes on
    lo, _ = ctx.clause_bounds(k)
    # "don't leave the toaster on": a negated verb before the device in its clause (not
    # "not the desk lamps": an exclusion)
    flipped = any(i.neg and any(v.verb is not None for v in ctx.items[n + 1:k])
                  for n, i in enumerate(ctx.items[max(lo, k - 4):k], start=max(lo, k - 4)))
    verb_seen = False
    # "if the door is open, it must be closed": the first state is the condition's
    condition = any(i.text in words.conditions for i in ctx.items[max(start, k - 4):k])
    if any(i.text in words.roles or i.text in words.stop for i in ctx.items[max(start, k - 3):k]):
        return None     # a role ("whoever opens drawers"), a complaint ("somebody left the fridge open")
    found: Said | None = None
    corrected = False       # a self-correction since the state found ("off - sorry, I mean leave it on")
    keepers = set(load_rule_words().stays.keepers) - {"but", "not", "except", "where"}
    kept = False
    for j in range(k + 1, end):
        if j > k + words.reach and not (found is not None and found.act):
            break       # past the reach only acts on "it" go on ("open it, put them in, then shut it")
        item = ctx.items[j]
        if (j in named or _names_thing(ctx, j)) and (verb_seen or not _modifier(ctx, j, k + 1, words)) and (
                _is_device(ctx, j) or not (_place(ctx, j, k + 1) or (found is not None and found.act))):
            return found    # the next thing's words (past a place, or a thing between acts on "it", it goes on)
        if item.liquid is not None and j > k + 1 and ctx.items[j - 1].det:
            return found    # "..., and the water of the sink you open it": the water's words
        if (item.conj is not None or item.sub is not None) and not _acts_on_it(ctx, k, j) and not (
                found is not None and (found.act or (j + 1 < end and ctx.items[j + 1].text in state_word_index()))):
            return found    # "when the kids shower, and close it after": another clause's act
        if item.text in words.stop and not flipped and not corrected:
            # "the light is on again": a complaint; "shut it again": the act stands
            return None if found is not None and found.label == "copula" else found
        if (item.neg and not (found is not None and item.text in corrections)) or any(
                starts_at(ctx.items, j, f) for f in words.flip):
            flipped = True      # (the "no" of "open it - no, keep it shut" takes back, it does not negate)
        condition = condition or item.text in words.conditions
        kept = kept or item.text in keepers
        corrected = corrected or (found is not None and item.text in corrections)
        said = _word_state(ctx.items, j, words, type_)
        if said is not None and condition:
            if _present(ctx, type_, said.family) == (said.polarity == flipped):
                return None     # "if the lamp's on, off with it" while it is off: not this branch
            condition, flipped, said = False, False, None
        if said is not None:
            label = said.label
            described = any(i.text in words.describing for i in ctx.items[max(start, k - 3):k])
            if label == "said" and not kept and (described or any(
                    i.text in words.copulas for i in ctx.items[max(k + 1, j - 2):j])):
                # "the TV is on": a description (a complaint) unless wanted or told as a narrative
                wished = ctx.narrative or any(i.text in words.wishes for i in ctx.items[k + 1:j])
                label = "said" if wished else "copula"
            elif kept and label == "said":
                label = "kept"
            if found is not None and found.label != "copula" and not corrected and not (
                    found.family == said.family and (_later(ctx.items, j, end, words) or (found.act and said.act))):
                return found    # "the tap is running, turn it off": the request after the description;
                # "open it, put them in, then shut it": the last act
            found = Said(said.family, said.polarity != flipped, label, said.act)
        verb_seen = verb_seen or item.verb is not None
    return found


def _acts_on_it(ctx: DoubtContext, k: int, j: int) -> bool:
    """Whether "and" at ``j`` joins an act on the device named at ``k`` ("put it in the
    toaster and switch it on"): a verb and a pronoun after it, a determiner before the device."""
    items = ctx.items
    return (items[j].conj is not None and k > 0 and items[k - 1].det and j + 2 < len(items)
            and items[j + 1].verb is not None and items[j + 2].pron is not None)


def _place(ctx: DoubtContext, m: int, lo: int) -> bool:
    """Whether the thing at ``m`` is a place ("on the desk"): a preposition before it."""
    k = m - 1
    if k >= lo and ctx.items[k].det:
        k -= 1
    return k >= lo and ctx.items[k].prep is not None


def _is_device(ctx: DoubtContext, j: int) -> bool:
    types = ctx.named_types(ctx.items[j], verbs_too=True) or next(
        (ts for m, _, ts in ctx.mentions() if m == j), ())
    return any(_props(t) & {"toggleable", "openable"} for t in types)


def _names_thing(ctx: DoubtContext, j: int) -> bool:
    """Whether a word that may be a verb names a thing here ("lights off"; not "light
    it", "light the candle")."""
    item = ctx.items[j]
    if item.verb is None or not ctx.named_types(item, verbs_too=True):
        return False
    nxt = ctx.items[j + 1] if j + 1 < len(ctx.items) else None
    return nxt is None or not (nxt.pron is not None or nxt.det or nxt.text in ("that", "this"))


def _later(items: Sequence[Item], j: int, end: int, words: StateWords) -> bool:
    """Whether the state at ``j`` is said to come after another ("shut after")."""
    return any(i.text in words.later for i in items[max(0, j - 2):min(end, j + 2)])


def _asked_before(ctx: DoubtContext, k: int) -> bool:
    """Whether a verb of switching or opening stands right before the device ("kill the light")."""
    j = k - 2 if k >= 2 and ctx.items[k - 1].det else k - 1
    verb = ctx.items[j].verb if j >= 0 else None
    return verb is not None and verb.sense.act in _ACTS


def _present(ctx: DoubtContext, type_: str, family: str) -> bool | None:
    objs = list(ctx.state.of_type(type_))
    if not objs:
        return None
    return bool(objs[0].is_on) if family == "switch" else bool(objs[0].is_open)


def _device(ctx: DoubtContext, types: Sequence[str], own: frozenset[str]) -> str | None:
    """The device a name means: of its types with a switch or a lid and not named by a
    name of their own elsewhere ("the big lamp" beside "the desk lamp"), the one the
    reading already gives a state (else the first)."""
    devices = [t for t in types if _props(t) & {"toggleable", "openable"}]
    if len(devices) > 1:
        devices = [t for t in devices if t not in own] or devices
    if not devices:
        return None
    stated = {t for c in ctx.goals if c.predicate in _PRED.values() for t in ref_types(c.subject)}
    return next((t for t in devices if t in stated), devices[0])


def _purpose(ctx: DoubtContext, words: StateWords, k: int | None, type_: str | None,
             complaints: bool = False) -> tuple[str, Said] | None:
    """A purpose that implies the state of the device named at ``k`` (``near``) or of the
    scene's device of its types (only the complaints with ``complaints``)."""
    phrases, by_words = purpose_phrases()
    for at, after in find(ctx.items, 0, len(ctx.items), phrases):
        p = by_words[tuple(i.text for i in ctx.items[at:after])]
        if complaints and not p.complaint:
            continue
        start, end = sentence_bounds(ctx.items, at)
        flipped = any(i.neg for i in ctx.items[max(start, at - 3):at])
        if p.near:
            if k is None or type_ is None or type_ not in p.types or not start <= k < end:
                continue
            thing: str | None = type_
        else:
            thing = next((t for t in p.types if t in ctx.scene_types), None)
            if thing is None or (type_ is not None and thing != type_):
                continue
        fam = _family(thing, p.family) if thing is not None else None
        if thing is not None and fam is not None:
            return thing, Said(fam, p.polarity != flipped, "complaint" if p.complaint else "purpose")
    return None


def _doubt(ctx: DoubtContext, span: str, type_: str, said: Said) -> Doubt | None:
    pred = _PRED[(said.family, said.polarity)]
    family = {_PRED[(said.family, True)], _PRED[(said.family, False)]}
    clash = tuple(c for c in ctx.goals if c.predicate in family and ref_types(c.subject) == {type_})
    if any(c.predicate is pred for c in clash):
        return None
    # the count the reading gave ("both taps") stays
    want = one_object(pred, type_).model_copy(update={"count": clash[0].count if clash else 1})
    read = "; ".join(clause(c) for c in clash) or "no goal"
    return Doubt(KIND, span, (Choice(AS_READ, read), Choice(said.label, clause(want), drop=clash, add=(want,))))


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_state_words()
    # a name that may be a verb names the device where no object follows ("the microwave is running")
    nouned = [(k, i, ctx.named_types(i, verbs_too=True)) for k, i in enumerate(ctx.items)
              if k > 0 and ctx.items[k - 1].det and _names_thing(ctx, k)]
    mentions = sorted([*ctx.mentions(), *nouned], key=lambda m: m[0])
    named = {m for m, _, _ in mentions}
    own = frozenset(ts[0] for _, _, ts in mentions if len(ts) == 1)
    last: dict[str, tuple[str, Said]] = {}     # the later words settle a device's state
    before: Said | None = None
    for k, item, types in mentions:
        type_ = _device(ctx, types, own)
        if type_ is None:
            continue
        complaint = _purpose(ctx, words, k, type_, complaints=True)
        said = complaint[1] if complaint else _own_words(ctx, k, type_, words, named)
        if said is None and before is not None and any(
                starts_at(ctx.items, j, c) and j + len(c) in (k, k - 1) for c in words.carry
                for j in range(max(0, k - 4), k)):
            fam = _family(type_, before.family)
            said = Said(fam, before.polarity, "carried") if fam is not None else None
        if find(ctx.items, k, min(len(ctx.items), k + words.reach + 4), words.present):
            now = _present(ctx, type_, said.family if said else "switch")
            if now is not None and (said is None or said.polarity == now):
                said = Said(said.family if said else "switch", now, "present")
        if said is None and type_ in last and _asked_before(ctx, k):
            del last[type_]     # "the light's on ... kill the light": the later request, as read
            continue
        if said is None:
            purpose = _purpose(ctx, words, k, type_)
            said = purpose[1] if purpose else None
        if said is None:
            continue
        before = said
        last[type_] = (item.text, said)
    far = _purpose(ctx, words, None, None)
    if far is not None and far[0] not in last:
        last[far[0]] = ("purpose", far[1])
    return [d for type_, (span, said) in last.items() if (d := _doubt(ctx, span, type_, said)) is not None]


__all__ = ["KIND", "Said", "doubts"]
