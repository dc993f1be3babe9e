"""Point of doubt: what a mention's own words ask of a thing the reading gave no goal.

One general mechanism instead of a phrase rule per sentence: every mention of a scene
thing that ends in no goal (and that nothing but a negation explains) is read in its own
stretch of words (its clause, cut at the neighbouring things that are not places) for

- a *keeping* cue ("stays", "remains", "leave X", "where it is", "is fine there"): the
  thing kept as it is, its start place or its start state read from the scene, or the
  state its stretch names ("the floor lamp stays on" -> on);
- a *state* word or participle ("the floor lamp glowing", "blinds down", "laptop: shut");
- a *direction* to a receptacle named after it ("mug -> desk", "kettle 2 the stove").

*Chatter* cues ("we used to have", "last time", "can't find") make the mention chatter
instead: :func:`chatter` is also one of :mod:`.explained`'s explanations. The cue words
are data (``mention_cues.json``, schema :class:`MentionCues` checked at load); the
alternative's prior is in ``priors.json`` (kind ``mention_cue``, one label per cue).
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache
from pathlib import Path
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.rule_words import Words, find, starts_at
from emboteam.pfg.offline.doubts.wants import asked_predicate, one_object, placed
from emboteam.pfg.offline.knowledge import read
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Condition, Predicate

KIND = "mention_cue"
MENTION_CUES_FILE = Path(__file__).with_name("mention_cues.json")
#: the predicates of one family: a thing keeps one place, one switch state, one open state
_FAMILIES = ({Predicate.inside}, {Predicate.switched_on, Predicate.switched_off}, {Predicate.open, Predicate.closed})
#: the property a predicate needs of the thing (a state word that cannot apply is no cue)
_NEEDS = {Predicate.switched_on: "toggleable", Predicate.switched_off: "toggleable",
          Predicate.open: "openable", Predicate.closed: "openable"}


class _Closed(BaseModel):
    model_config = ConfigDict(extra="forbid")


class SidedCue(_Closed):
    words: Words = Field(min_length=1)
    #: where the cue stands from the thing: "the lamp stays" (after), "leave the lamp" (before)
    side: Literal["before", "after", "either"]


class MentionCues(_Closed):
    about: str = ""
    keep: list[SidedCue]
    #: participles and words the tagger reads as no state -> the predicate they ask
    states: dict[str, Predicate]
    #: words that are a state only with no place after them ("stays on" / "stays on the shelf")
    place_preps: list[str]
    directions: list[Words]
    chatter: list[SidedCue]
    chatter_reach: int = Field(4, ge=1, le=12)


@cache
def load_mention_cues(path: Path = MENTION_CUES_FILE) -> MentionCues:
    """The cue file, checked by its schema (a malformed entry is a
    :class:`~emboteam.pfg.offline.knowledge.KnowledgeDataError` naming file and entry)."""
    return read(path, MentionCues)


def _props(type_: str) -> frozenset[str]:
    return frozenset(load_catalogue().type(type_).properties)


def _is_place(ctx: DoubtContext, m: int) -> bool:
    from emboteam.pfg.offline.doubts.explained import after_preposition

    return after_preposition(ctx, m, ctx.clause_bounds(m)[0])


def segment(ctx: DoubtContext, k: int) -> tuple[int, int]:
    """[start, end) of the mention's own words: its clause, cut at the nearest mentions
    of other things that are not places (a place belongs to the stretch of its thing)."""
    start, end = ctx.clause_bounds(k)
    thing = set(ctx.named_types(ctx.items[k], verbs_too=True))
    for m, _, types in ctx.mentions():
        if m == k or not start <= m < end or set(types) & thing or _is_place(ctx, m):
            continue
        if m < k:
            start = m + 1
        else:
            end = m
            break
    return start, end


def _found(ctx: DoubtContext, lo: int, hi: int, words: Words) -> list[int]:
    """Where the words start between ``lo`` and ``hi`` (the whole phrase inside)."""
    return [s for s in range(lo, hi - len(words) + 1) if starts_at(ctx.items, s, words)]


def _sided(ctx: DoubtContext, k: int, lo: int, hi: int, cues: Sequence[SidedCue]) -> bool:
    """Whether a cue stands on its side of ``k`` within [lo, hi), not right after a negation."""
    for cue in cues:
        starts = []
        if cue.side in ("before", "either"):
            starts += _found(ctx, lo, k, cue.words)
        if cue.side in ("after", "either"):
            starts += _found(ctx, k + 1, hi, cue.words)
        if any(not any(i.neg for i in ctx.items[max(lo, s - 2):s]) for s in starts):
            return True
    return False


def chatter(ctx: DoubtContext, k: int) -> bool:
    """Whether a chatter cue frames the mention ("we used to have a magazine rack")."""
    data = load_mention_cues()
    start, end = segment(ctx, k)
    return _sided(ctx, k, max(start, k - data.chatter_reach), min(end, k + 1 + data.chatter_reach), data.chatter)


def _state_at(ctx: DoubtContext, j: int, end: int, data: MentionCues) -> Predicate | None:
    item = ctx.items[j]
    if item.text in data.states:
        return data.states[item.text]
    if item.state is None:
        return None
    if item.text in data.place_preps and j + 1 < end:
        nxt = ctx.items[j + 1]
        if nxt.det or nxt.noun is not None:
            return None      # "stays on the shelf": a place, not a state
    return asked_predicate(item)


def _state(ctx: DoubtContext, k: int, start: int, end: int, thing: str) -> Predicate | None:
    """The state the stretch names that the thing can take, nearest after it first."""
    data = load_mention_cues()
    props = _props(thing)
    for j in [*range(k + 1, end), *range(k - 1, start - 1, -1)]:
        pred = _state_at(ctx, j, end, data)
        if pred is not None and _NEEDS.get(pred, "") in props | {""} and pred is not Predicate.inside:
            return pred
    return None


def _destination(ctx: DoubtContext, k: int, end: int, thing: str) -> str | None:
    """The receptacle a direction after the thing leads to ("mug -> desk")."""
    for s, e in find(ctx.items, k + 1, end, load_mention_cues().directions):   # a list of the loaded file
        place = next((ts[0] for m, _, ts in ctx.mentions() if e <= m < min(end, e + 3)), None)
        if place is not None and place != thing and "receptacle" in _props(place):
            return place
    return None


def kept(ctx: DoubtContext, thing: str, state: Predicate | None) -> Condition | None:
    """The thing as it is: the state its words name, else its start place (a thing that
    is picked up), else its start switch or open state."""
    if state is not None:
        return one_object(state, thing)
    objs = list(ctx.state.of_type(thing))
    if not objs:
        return None
    o, props = objs[0], _props(thing)
    if "pickupable" in props and o.parent is not None:
        return placed(thing, ctx.state.obj(o.parent).type)
    if "toggleable" in props:
        return one_object(Predicate.switched_on if o.is_on else Predicate.switched_off, thing)
    if "openable" in props:
        return one_object(Predicate.open if o.is_open else Predicate.closed, thing)
    return None


def _proposal(ctx: DoubtContext, k: int, thing: str, negated: bool) -> tuple[str, tuple[Condition, ...]] | None:
    """(label, goals) the mention's cues ask for, or None."""
    data = load_mention_cues()
    start, end = segment(ctx, k)
    state = _state(ctx, k, start, end, thing)
    if _sided(ctx, k, start, end, data.keep):
        keep = kept(ctx, thing, state)
        return ("keep", (keep,)) if keep is not None else None
    if negated:
        return None      # "not the lamp on": only a keeping cue speaks past a negation
    dest = _destination(ctx, k, end, thing)
    goals = tuple(c for c in (one_object(state, thing) if state is not None else None,
                              placed(thing, dest) if dest is not None else None) if c is not None)
    label = "_".join(n for n, c in (("state", state), ("place", dest)) if c is not None)
    return (label, goals) if goals else None


def _has_family(ctx: DoubtContext, thing: str, goals: Sequence[Condition]) -> bool:
    """Whether the reading already gives the thing a goal of a family the proposal has."""
    preds = {c.predicate for c in goals}
    return any(thing in ref_types(c.subject) and any(c.predicate in f and preds & f for f in _FAMILIES)
               for c in ctx.goals)


def doubts(ctx: DoubtContext) -> list[Doubt]:
    from emboteam.pfg.offline.doubts.explained import NEGATED, explanation

    out: list[Doubt] = []
    seen: set[str] = set()
    for k, item, types in ctx.mentions():
        why = explanation(ctx, k, types, goals=False)
        if types[0] in seen or why not in (None, NEGATED):
            continue
        made = _proposal(ctx, k, types[0], negated=why == NEGATED)
        if made is None or _has_family(ctx, types[0], made[1]):
            continue
        seen.add(types[0])
        label, goals = made
        how = "; ".join(clause(c) for c in goals)
        out.append(Doubt(KIND, item.text, (Choice(AS_READ, f"{item.text!r}: no goal"),
                                           Choice(label, f"{type_name(types[0])}: {how}", add=goals))))
    return out
