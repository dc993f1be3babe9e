"""Point of doubt: a thing whose words keep it where it is, though the reading gives it
no place: one rule for every keep of a thing that can be picked up.

- a keep beside an act: the reader reads the act (closed, lit) and drops the place said
  beside it ("close the laptop, but it stays on the dresser", "the laptop shut, not
  moved", "lit where it stands", "close it, but don't take it from the little table");
- a thing told as already in place ("the egg is already in there", "the mug's already
  sitting in it", "the pot that's already on the hob") or named as a landmark ("next to
  the pillow", "by the tissues on the night table"): its place is a condition too, and
  never an act on it.

The alternative adds its place, by the evidence of its own words (the cue words are data,
``kept_place.json`` and ``mention_cues.json``'s keep cues):

- ``sent``: a place its window sends it to (:func:`.destination.destination`);
- ``kept``: a keep cue after it ("stays", "left where it is", "not moved"): where it
  stands now (the one named, if several);
- ``already``: an already-word after it ("already", "currently"): where it stands now;
- ``landmark``: a landmark preposition before it ("next to", "beside", "by"): where it
  stands now;
- ``named_place``: where it stands now, named right after it ("the candle in the bath,
  light it"): the weakest;
- ``kept_not_held``: a thing the reading carries (held) that a keep cue keeps ("the keys
  are up there, leave them"): put down where it is instead.

The words of ``kept``, ``already`` and ``landmark`` say the thing stays, so their priors
put the kept place in the first reading; a place named only beside the thing does not.

A thing whose state only a word doubt proposes (:mod:`.device_state`, :mod:`.mention_cues`)
counts too (``said``). Priors: ``priors.json``, kind ``kept_place``.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache
from pathlib import Path

from pydantic import Field

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.context import type_props as _props
from emboteam.pfg.offline.doubts.destination import destination, present
from emboteam.pfg.offline.doubts.explained import LANDMARK, explanation
from emboteam.pfg.offline.doubts.mention_words import load_mention_cues, segment
from emboteam.pfg.offline.doubts.place_roles import keeps_state
from emboteam.pfg.offline.doubts.rule_words import Words, find
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.offline.knowledge import Strict, read
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.goals import Condition, Predicate

KIND = "kept_place"
KEPT_PLACE_FILE = Path(__file__).with_name("kept_place.json")
#: goals that say where a thing ends (or that it is carried)
_PLACES = (Predicate.inside, Predicate.held)


class KeptPlaceCues(Strict):
    about: str = ""
    keep_after: list[Words] = Field(min_length=1)
    place_preps: list[str] = Field(min_length=1)
    #: words after the thing that say it is in place now ("the egg is already in there")
    already: list[Words] = Field(min_length=1)
    #: words besides a preposition that, right after an already-word, name a place ("already there")
    already_before: list[str] = Field(min_length=1)
    #: the tagger's preposition relations that make the thing after them a landmark
    #: ("next to the pillow", "beside the pot", "by the tissues")
    landmark_preps: list[str] = Field(min_length=1)
    #: how many words after the thing a keep cue may stand
    reach: int = Field(8, ge=1, le=20)


@cache
def load_kept_place(path: Path = KEPT_PLACE_FILE) -> KeptPlaceCues:
    """The cue file, checked by its schema."""
    return read(path, KeptPlaceCues)


def _acted(ctx: DoubtContext, thing: str) -> tuple[bool, tuple[Condition, ...], int]:
    """Whether the reading places the thing (or its slices) already, its goals that
    only carry it (held), and the count its goals name."""
    mine = [c for c in ctx.goals if thing in ref_types(c.subject)]
    return (any(c.predicate is Predicate.inside for c in mine), tuple(c for c in mine if c.predicate is Predicate.held),
            max((c.count for c in mine), default=1))


def _here(ctx: DoubtContext, thing: str, lo: int, hi: int) -> str | None:
    """Where the thing stands now: its one receptacle type, or the one of several that
    its words name in [lo, hi)."""
    here = present(ctx, thing)
    if len(here) == 1:
        return next(iter(here))
    named = [t for item in ctx.items[lo:hi] for t in ctx.named_types(item)[:1] if t in here]
    return named[0] if named else None


def _named_after(ctx: DoubtContext, k: int, thing: str) -> str | None:
    """Its present place named right after it ("the candle in the bath"), else None."""
    preps = set(load_kept_place().place_preps)
    if k + 1 >= len(ctx.items) or ctx.items[k + 1].text not in preps:
        return None
    here = present(ctx, thing)
    for item in ctx.items[k + 2:k + 5]:
        types = ctx.named_types(item)
        if types:
            return next((t for t in types if t in here), None)
        if not (item.det or item.text in preps or item.text == "to"):
            return None
    return None


def _landmark(ctx: DoubtContext, k: int, start: int) -> bool:
    """Whether the mention at ``k`` is the object of a landmark preposition ("next to the
    pot", "by the two pillows"): one stands at most three determiners, numbers or
    describing words before it."""
    preps = set(load_kept_place().landmark_preps)
    for j in range(k - 1, max(start, k - 4) - 1, -1):
        item = ctx.items[j]
        if item.prep is not None:
            return item.prep in preps and item.noun is None
        if not (item.det or item.number is not None) and (item.noun or item.verb or item.punct or item.conj or item.state):
            return False
    return False


@cache
def _keep_cues() -> list[Words]:
    """This file's keep cues and ``mention_cues.json``'s said after the thing: one list
    for the process (:func:`.rule_words.find` indexes a list by its identity)."""
    return [*load_kept_place().keep_after, *(c.words for c in load_mention_cues().keep if c.side != "before")]


def _keep_cue(ctx: DoubtContext, lo: int, hi: int) -> bool:
    """Whether a keep cue of a place stands in [lo, hi) ("stays", "not moved", "do not take
    it from ..."): this file's or one of ``mention_cues.json``'s said after the thing, not
    right after a negation of its own ("it does not stay"), not keeping a state."""
    return any((ctx.items[s].neg or not any(i.neg for i in ctx.items[max(lo, s - 2):s])) and not keeps_state(ctx.items, e)
               for s, e in find(ctx.items, lo, hi, _keep_cues()))


def _already(ctx: DoubtContext, lo: int, hi: int) -> bool:
    """Whether an already-word in [lo, hi) says where the thing is now: a place follows it
    ("already in there", "already sitting in it"), not a state ("it's open already")."""
    after = set(load_kept_place().already_before)
    return any(any(i.prep is not None or i.text in after for i in ctx.items[e:e + 2])
               for _, e in find(ctx.items, lo, hi, load_kept_place().already))


def _proposal(ctx: DoubtContext, k: int, thing: str, carried: bool, acted: bool,
              landmark: bool) -> tuple[str, str] | None:
    """(label, place type) the mention's words give, or None; a thing the reading
    carries (``carried``) only by a keep cue (where it goes is :mod:`.destination`'s); a
    thing the reading does not act on (``acted`` false) only by an already-word or as a
    landmark (``landmark``: its mention's explanation; also a keep cue then)."""
    start, end = segment(ctx, k)
    dest = () if carried or not acted else destination(ctx, k, thing, end)
    if dest:
        return "sent", dest[0]
    data = load_kept_place()
    hi = min(end, k + 1 + data.reach)
    if _keep_cue(ctx, k + 1, hi) and (acted or landmark):
        label = "kept"      # (a keep of a thing with no act and no landmark is :mod:`.mention_cues`')
    elif _already(ctx, k + 1, hi):
        label = "already"
    elif not carried and _landmark(ctx, k, start):
        label = "landmark"
    else:
        here = None if carried or not acted else _named_after(ctx, k, thing)
        return ("named_place", here) if here is not None else None
    # a place its own words name that it is not in is the speaker's belief, not its place
    # ("the tomato's already in the fridge" with the tomato on the counter): no keep
    here_now = present(ctx, thing)
    for item in ctx.items[k + 1:end]:
        named = {t for t in ctx.named_types(item) if t != thing and "receptacle" in _props(t)}
        if named and not named & here_now:
            return None
    here = _here(ctx, thing, start, end)
    return (label, here) if here is not None else None


def _stated(cued: Sequence[Doubt]) -> set[str]:
    """The words of the mentions a word doubt gives a state but no place."""
    return {d.span for d in cued if not any(c.predicate in _PLACES for ch in d.choices for c in ch.add)}


def doubts(ctx: DoubtContext, cued: Sequence[Doubt] = ()) -> list[Doubt]:
    """One doubt per thing acted on with no place (``cued``: the word doubts of
    :mod:`.device_state` and :mod:`.mention_cues`; a thing they give only a state counts)."""
    said = _stated(cued)
    # a thing nothing acts on whose own words give it a place is settled by that doubt
    placed_by_words = {t for d in cued for ch in d.choices for c in ch.add if c.predicate in _PLACES
                       for t in ref_types(c.subject)}
    out: list[Doubt] = []
    seen: set[str] = set()
    acted = {t for c in ctx.goals if c.predicate is not Predicate.inside for t in ref_types(c.subject)}
    for k, item, types in ctx.mentions():
        thing = types[0]
        is_acted = thing in acted or item.text in said
        if thing in seen or "pickupable" not in _props(thing) or (not is_acted and thing in placed_by_words):
            continue
        has_place, held, count = _acted(ctx, thing)
        if has_place or explanation(ctx, k, types, goals=False) not in (None, LANDMARK):
            continue
        made = _proposal(ctx, k, thing, carried=bool(held), acted=is_acted,
                         landmark=explanation(ctx, k, types, goals=False) == LANDMARK)
        if made is None:
            continue
        seen.add(thing)
        label, place = made
        goal: Condition = placed(thing, place)
        goal = goal.model_copy(update={"count": count}) if count > 1 else goal
        # a thing read as carried that its words keep ("the keys are up there, leave
        # them") is put down where it is, not carried
        choice = Choice("kept_not_held", f"{type_name(thing)}: {clause(goal)}", drop=held, add=(goal,)) if held \
            else Choice(label, f"{type_name(thing)}: {clause(goal)}", add=(goal,))
        out.append(Doubt(KIND, item.text, (Choice(AS_READ, f"{item.text!r}: no place"), choice)))
    return out
