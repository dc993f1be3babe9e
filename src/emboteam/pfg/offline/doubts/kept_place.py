"""Point of doubt: a thing the reading acts on but gives no place ("close the laptop, but
it stays on the dresser", "light the candle and leave it in the bath", "the candle: lit,
on the counter too").

The reader reads the act (closed, lit, sliced) and drops the place said beside it, so a
reading that must name every place of the things it touches loses it ("a keep beside an
act"). For each mention of such a thing (one it can pick up, whose words the scene does
not explain away) the alternative adds its place, by the evidence of its own words:

- ``sent``: a place its window sends it to (:func:`.destination.destination`);
- ``kept``: a keep cue after it ("stays", "left where it is", ``kept_place.json`` and
  ``mention_cues.json``'s keep cues): where it stands now (the one named, if several);
- ``named_place``: where it stands now, named right after it ("the candle in the bath,
  light it"): the weakest;
- ``kept_not_held``: a thing the reading carries (held) that a keep cue keeps ("the keys
  are up there, leave them"): put down where it is instead.

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
from emboteam.pfg.offline.doubts.explained import explanation
from emboteam.pfg.offline.doubts.mention_words import load_mention_cues, segment, side
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


def _proposal(ctx: DoubtContext, k: int, thing: str, carried: bool) -> tuple[str, str] | None:
    """(label, place type) the mention's words give, or None; a thing the reading
    carries (``carried``) only by a keep cue (where it goes is :mod:`.destination`'s)."""
    start, end = segment(ctx, k)
    dest = () if carried else destination(ctx, k, thing, end)
    if dest:
        return "sent", dest[0]
    data = load_kept_place()
    hi = min(end, k + 1 + data.reach)
    if find(ctx.items, k + 1, hi, data.keep_after) or side(ctx, k, start, end, load_mention_cues().keep) == "after":
        here = _here(ctx, thing, start, end)
        return ("kept", here) if here is not None else None
    here = None if carried else _named_after(ctx, k, thing)
    return ("named_place", here) if here is not None else None


def _stated(cued: Sequence[Doubt]) -> set[str]:
    """The words of the mentions a word doubt gives a state but no place."""
    return {d.span for d in cued if not any(c.predicate in _PLACES for ch in d.choices for c in ch.add)}


def doubts(ctx: DoubtContext, cued: Sequence[Doubt] = ()) -> list[Doubt]:
    """One doubt per thing acted on with no place (``cued``: the word doubts of
    :mod:`.device_state` and :mod:`.mention_cues`; a thing they give only a state counts)."""
    said = _stated(cued)
    out: list[Doubt] = []
    seen: set[str] = set()
    acted = {t for c in ctx.goals if c.predicate is not Predicate.inside for t in ref_types(c.subject)}
    for k, item, types in ctx.mentions():
        thing = types[0]
        if thing in seen or "pickupable" not in _props(thing):
            continue
        if thing not in acted and item.text not in said:
            continue      # no act read nor said (an unexplained mention's place is :mod:`.unexplained`'s)
        has_place, held, count = _acted(ctx, thing)
        if has_place or explanation(ctx, k, types, goals=False) is not None:
            continue
        made = _proposal(ctx, k, thing, carried=bool(held))
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
