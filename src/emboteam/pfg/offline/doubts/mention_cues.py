"""Point of doubt: what a mention's own words ask of a thing the reading gave no goal.

One general mechanism instead of a phrase rule per sentence: every mention of a scene
thing that ends in no goal (and that nothing but a negation explains) is read in its own
stretch of words (its clause, cut at the neighbouring things that are not places) for

- a *keeping* cue ("stays", "remains", "leave X", "where it is", "is fine there"): the
  thing kept as it is, its start place or its start state read from the scene, or the
  state its stretch names ("the floor lamp stays on" -> on);
- a *state* word or participle ("the floor lamp glowing", "blinds down", "laptop: shut");
(a place it goes, "mug -> desk", "leave the phone on the bed", is :mod:`.destination`'s).

*Chatter* cues ("we used to have", "last time", "can't find") make the mention chatter
instead: :func:`chatter` is also one of :mod:`.explained`'s explanations. The cue words
are data (``mention_cues.json``, schema :class:`MentionCues` checked at load); the
alternative's prior is in ``priors.json`` (kind ``mention_cue``, one label per cue).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.context import type_props as _props
from emboteam.pfg.offline.doubts.counts import counted, implied, said_count, said_number
from emboteam.pfg.offline.doubts.destination import destination
from emboteam.pfg.offline.doubts.explained import CHATTER, NEGATED, explanation
from emboteam.pfg.offline.doubts.mention_words import (
    MentionCues,
    answers,
    load_mention_cues,
    segment,
    side,
    sided,
)
from emboteam.pfg.offline.doubts.place_roles import state_kept
from emboteam.pfg.offline.doubts.state_words import load_state_words
from emboteam.pfg.offline.doubts.wants import asked_predicate, one_object, placed
from emboteam.pfg.offline.tagger import Item
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.goals import Condition, Predicate

KIND = "mention_cue"
#: the predicates of one family: a thing keeps one place, one switch state, one open state
_FAMILIES = ({Predicate.inside}, {Predicate.switched_on, Predicate.switched_off}, {Predicate.open, Predicate.closed})
#: the property a predicate needs of the thing (a state word that cannot apply is no cue)
_OPPOSITE = {Predicate.switched_on: Predicate.switched_off, Predicate.switched_off: Predicate.switched_on,
             Predicate.open: Predicate.closed, Predicate.closed: Predicate.open}
_NEEDS = {Predicate.switched_on: "toggleable", Predicate.switched_off: "toggleable",
          Predicate.open: "openable", Predicate.closed: "openable"}


def _state_at(ctx: DoubtContext, j: int, end: int, data: MentionCues) -> Predicate | None:
    """The state the word at ``j`` asks; a word that may be a preposition or a particle
    ("on", "up") is one only with no place or preposition after it ("stays on the shelf",
    "ends up on the dresser")."""
    item = ctx.items[j]
    said = _STATES.get(item.text) if item.state is None else None     # the state lexicon's own words
    if said is None and item.state is None:
        return None
    if (said is not None or item.text in data.place_preps) and j + 1 < end:
        nxt = ctx.items[j + 1]
        if nxt.det or nxt.noun is not None or (nxt.prep is not None and said is not None):
            return None
    return said if said is not None else asked_predicate(item)


#: the words of the state lexicon (``state_words.json``) the tagger reads as no state
#: ("glowing", "unlit", "down"), certain ones of any device ("up", "down" of any lid too), as predicates
_STATES = {w.words[0]: {("switch", True): Predicate.switched_on, ("switch", False): Predicate.switched_off,
                        ("open", True): Predicate.open, ("open", False): Predicate.closed}[(w.family, w.polarity)]
           for w in load_state_words().words if w.certain and (not w.types or w.words[0] in ("up", "down"))}


def _described(ctx: DoubtContext, k: int, j: int, data: MentionCues) -> bool:
    """Whether the state at ``j`` is said of the thing as it is ("the phone, it's broken
    anyway"): after a copula, with no wish, rule or narrative that makes it an end state
    ("should be on", "is never on", "when I walk in the TV is on")."""
    between = ctx.items[k + 1:j]
    if not any(i.copula or i.text in data.copulas for i in between):
        return False
    return not (ctx.narrative or any(i.text in data.wishes for i in between))


def _fits(pred: Predicate | None, thing: str) -> bool:
    return pred is not None and pred is not Predicate.inside and _NEEDS.get(pred, "") in _props(thing) | {""}


def _state_before(ctx: DoubtContext, k: int, start: int, thing: str) -> Predicate | None:
    """A state said before the thing and outside its noun phrase ("put open the blinds",
    "lights off, the floor lamp too"); an adjective of the noun phrase ("the dirty
    clothes", "a hot cup") describes it and asks nothing."""
    j = k - 1
    while j >= max(start, k - 3) and (ctx.items[j].det or ctx.items[j].punct is not None):
        j -= 1
    if j < start or j == k - 1:
        return None
    pred = _state_at(ctx, j, k, load_mention_cues())
    return pred if _fits(pred, thing) else None


def _state(ctx: DoubtContext, k: int, start: int, end: int, thing: str, before: bool) -> Predicate | None:
    """The state the words after the thing name that it can take (up to a condition:
    "the knife, and once it is sliced ..."); a negated one ("never left burning") is its
    opposite, or none; else one said before it (:func:`_state_before`)."""
    data = load_mention_cues()
    for j in range(k + 1, end):
        item = ctx.items[j]
        if item.sub is not None or item.text in data.condition_words or (item.pron is not None and not item.det):
            return None      # a condition, or a state said of what a pronoun names ("press it down")
        pred = _state_at(ctx, j, end, data)
        if not _fits(pred, thing) or _described(ctx, k, j, data):
            continue
        if any(i.neg for i in ctx.items[max(k + 1, j - 3):j]):
            return _OPPOSITE.get(pred)     # type: ignore[arg-type]
        return pred
    return _state_before(ctx, k, start, thing) if before else None


def said_state(ctx: DoubtContext, k: int, end: int, thing: str) -> Condition | None:
    """The switch or open state a word after the thing (up to ``end``) asks of it, as a
    goal ("the candle that's hiding in the cupboard is out and burning on the counter"):
    one it can take, not under a negation, not a particle before a place ("ends up on")."""
    data = load_mention_cues()
    for j in range(k + 1, end):
        pred = _state_at(ctx, j, end, data)
        if pred in _NEEDS and _fits(pred, thing) and not any(i.neg for i in ctx.items[max(k + 1, j - 3):j]):
            return one_object(pred, thing)
    return None


def _kept_switch(ctx: DoubtContext, thing: str, is_on: bool, as_is: bool) -> Predicate:
    """The switch state a thing kept as it is ends in: its start state, unless the
    reading switches the rest of its group to that state ("lights off (desk lamp can
    stay)": an exception to the group, it stays as the person believes it is: the other)
    and its words do not name the start state itself (``as_is``: "the big lamp stays how
    it is" beside "the small lamp on": on, as it is)."""
    now = Predicate.switched_on if is_on else Predicate.switched_off
    if as_is:
        return now
    group = next((set(g) for g in load_mention_cues().groups if thing in g), set())
    if any(c.predicate is now and (ref_types(c.subject) & group) - {thing} for c in ctx.goals):
        return _OPPOSITE[now]
    return now


def kept(ctx: DoubtContext, thing: str, state: Predicate | None, named: Mapping[str, int] | None = None,
         as_is: bool = False, count: int | None = None) -> tuple[Condition, ...]:
    """The thing as it is: its start place (a thing that is picked up; of several, the one
    in the receptacle named nearest to it, ``named``: type -> distance, "the toilet paper
    in the bin is fine"; ``count`` of them where they share it, "the two vases stay") and
    the state its words name ("the candle stays and gets lit"), else its start switch or
    open state."""
    near = named or {}
    objs = sorted(ctx.state.of_type(thing), key=lambda o: near.get(ctx.state.obj(o.parent).type, 99)
                  if o.parent is not None else 99)
    if not objs:
        return ()
    o, props = objs[0], _props(thing)
    out = [one_object(state, thing)] if state is not None else []
    if "pickupable" in props and o.parent is not None:
        where = ctx.state.obj(o.parent).type
        same = [x for x in objs[: count or 1] if x.parent is not None and ctx.state.obj(x.parent).type == where]
        out.append(counted(placed(thing, where), len(same)))
    elif state is None and "toggleable" in props:
        out.append(one_object(_kept_switch(ctx, thing, o.is_on, as_is), thing))
    elif state is None and "openable" in props:
        out.append(one_object(Predicate.open if o.is_open else Predicate.closed, thing))
    return tuple(out)


def _proposal(ctx: DoubtContext, k: int, thing: str, negated: bool) -> tuple[str, tuple[Condition, ...]] | None:
    """(label, goals) the mention's cues ask for, or None."""
    data = load_mention_cues()
    start, end = segment(ctx, k)
    keep = side(ctx, k, start, end, data.keep)
    # type -> how near it is named (after the thing first: "the toilet paper in the bin")
    named: dict[str, int] = {}
    for m in range(start, end):
        for t in ctx.named_types(ctx.items[m], verbs_too=True)[:1]:
            named[t] = min(named.get(t, 99), m - k if m > k else 20 + k - m)
    # a thing kept as it is takes only a state said after it ("the lamp stays on"), not
    # the state of the clause before ("lights off, the desk lamp can stay")
    state = _state(ctx, k, start, end, thing, before=keep is None)
    as_is = sided(ctx, k, start, end, data.as_is)
    count = said_count(ctx, k, thing)
    if keep == "after":
        goals = kept(ctx, thing, state, named, as_is, count)
        if state is not None and state_kept(ctx, k, end, data.keep):      # "the laptop stays shut": not its place
            goals = tuple(g for g in goals if g.predicate is not Predicate.inside)
        return ("keep", goals) if goals else None
    if keep == "before":      # "leave the lamp on", "leave the phone on the bed": a place named is where it goes
        goals = kept(ctx, thing, state, named, as_is, count)
        if there := destination(ctx, k, thing, end):
            goals = (*(g for g in goals if g.predicate is not Predicate.inside),
                     counted(placed(thing, there[0]), said_number(ctx, k)))
        return ("leave", goals) if goals else None
    if negated:
        return None      # "not the lamp on": only a keeping cue speaks past a negation
    # a place it goes is its window's (:mod:`.window`, through the unexplained mention)
    return None if state is None else ("state", (one_object(state, thing),))


def _choice(ctx: DoubtContext, thing: str, label: str, goals: tuple[Condition, ...]) -> Choice | None:
    """The alternative a mention's cues give, or None when the reading has it already.
    A state or a place its words ask is for a thing with no goal; a thing kept as it is
    may have goals of other kinds ("the candle stays and gets lit"), and a place the
    reading moves it to is dropped ("the soap stays by the sink": by the sink is where it
    is, not where it goes)."""
    if label not in ("keep", "leave"):
        return None if thing in ctx.goal_types() else Choice(label, _how(thing, goals), add=goals)
    mine = [c for c in ctx.goals if thing in ref_types(c.subject)]
    add = tuple(g for g in goals if not implied(g, mine))
    families = [f for f in _FAMILIES if any(g.predicate in f for g in add)]
    clash = tuple(c for c in mine if any(c.predicate in f for f in families))
    if not add or any(c.predicate is not Predicate.inside or label != "keep" for c in clash):
        return None
    if clash:
        return Choice("keep_moved", _how(thing, add), drop=clash, add=add)
    return Choice(label, _how(thing, add), add=add)


def _how(thing: str, goals: Sequence[Condition]) -> str:
    return f"{type_name(thing)}: " + "; ".join(clause(c) for c in goals)


def _mentions(ctx: DoubtContext) -> list[tuple[int, Item, tuple[str, ...]]]:
    """The context's mentions, and a word that may be a verb after a determiner ("leave
    the light as it is": the light)."""
    memo = answers(ctx)
    if "mentions" in memo:
        return memo["mentions"]    # type: ignore[return-value]
    found = {k for k, _, _ in ctx.mentions()}
    more = [(k, i, types) for k, i in enumerate(ctx.items)
            if k not in found and k > 0 and ctx.items[k - 1].det and i.verb is not None
            and (types := ctx.named_types(i, verbs_too=True))]
    memo["mentions"] = sorted([*ctx.mentions(), *more], key=lambda m: m[0])
    return memo["mentions"]    # type: ignore[return-value]


def _chatter_doubt(ctx: DoubtContext, k: int, item: Item, thing: str) -> Doubt | None:
    """A thing named only in chatter ("we used to have a laptop") that the reading gave
    goals: those goals dropped is the alternative."""
    if any(m != k and thing in ts and explanation(ctx, m, ts, goals=False) != CHATTER for m, _, ts in _mentions(ctx)):
        return None      # named again outside the chatter
    goals = tuple(c for c in ctx.goals if thing in ref_types(c.subject))
    if not goals:
        return None
    return Doubt(KIND, item.text, (Choice(AS_READ, f"{item.text!r}: as read"),
                                   Choice("chatter", f"{item.text!r} is chatter: no goal", drop=goals)))


def doubts(ctx: DoubtContext) -> list[Doubt]:
    out: list[Doubt] = []
    seen: set[str] = set()
    for k, item, types in _mentions(ctx):
        why = explanation(ctx, k, types, goals=False)
        if types[0] in seen or why not in (None, NEGATED, CHATTER):
            continue
        if why == CHATTER:
            found = _chatter_doubt(ctx, k, item, types[0])
            if found is not None:
                seen.add(types[0])
                out.append(found)
            continue
        made = _proposal(ctx, k, types[0], negated=why == NEGATED)
        choice = None if made is None else _choice(ctx, types[0], *made)
        if choice is None:
            continue
        seen.add(types[0])
        out.append(Doubt(KIND, item.text, (Choice(AS_READ, f"{item.text!r}: as read"), choice)))
    return out
