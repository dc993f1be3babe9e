"""Point of doubt: the destination a thing's own words give it.

"The remote lives on the sofa and the keys live in a drawer", "plates don't live on the
coffee table - their home is the shelf", "pen and pencil, go into a drawer": the place a
thing goes is usually the first destination named after it in its sentence (after a
placing preposition, not under a negation). When the reader gave the thing another place
(or held it, or switched it), the alternative places it there. The cues are data
(``rule_words.json``, ``next_place``).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.context import type_props as _props
from emboteam.pfg.offline.doubts.rule_words import NextPlace, find, load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.goals import Predicate

KIND = "next_place"


def destinations(ctx: DoubtContext, k: int, thing: str, words: NextPlace) -> tuple[str, ...]:
    """The scene types of the place a thing goes, by the words after it in its sentence
    (none when they say nothing sure): of the places a destination cue leads to before the
    next thing is named, after a verb of the thing's own ("the keys live in a drawer") or
    right after it in a direction ("mug -> desk"), a direction ("into") first, else the first; a place under a
    negation gives way to the next; where the thing is ("lying on", "there's a mug in the
    sink", "the CD in the drawer, put it ...") is no destination."""
    start, end = sentence_bounds(ctx.items, k)
    if ctx.corrected:
        return ()     # a self-correction's places are the correction rules' (scope.py)
    if find(ctx.items, max(start, k - 4), k, load_rule_words().contents.excluders):
        return ()     # "apart from the alarm clock": what is excluded goes nowhere
    end = min(end, k + words.reach)
    narrative = ctx.narrative
    since = ctx.clause_bounds(k)[0]     # a negation rules out the first place after it
    cues = {e: ctx.items[b].text for b, e in find(ctx.items, k + 1, end, words.destination_cues)}
    places: list[tuple[bool, tuple[str, ...]]] = []
    last = k    # the thing and those listed with it ("the card and the remote - go ...")
    for m, item, types in ctx.mentions():
        if not k < m < end or types[0] == thing or item.noun is None:
            continue
        lead = [cues[j] for j in range(max(k + 1, m - 2), m + 1) if j in cues]
        if not lead or "receptacle" not in _props(types[0]):
            if "pickupable" in _props(types[0]):
                if not all(i.det or i.conj or i.punct or i.number is not None for i in ctx.items[last + 1:m]):
                    break     # another thing, with places of its own
                last = m
            continue
        if any(i.neg for i in ctx.items[since:m]):
            since = m + 1
            continue    # "plates don't live on the coffee table - their home is the shelf"
        if any(i.text in words.locatives for i in ctx.items[max(k + 1, m - 3):m]):
            return ()
        # a verb says where it goes ("the keys live in a drawer"); a copula only in a
        # narrative ("by the time I'm back the roll is on its holder")
        # between the thing and the place: the thing is the subject of a verb of its own
        verb = any((i.verb is not None and not i.copula) or (narrative and i.copula)
                   for i in ctx.items[k + 1:m] if i.noun is None)
        directional = lead[0] in words.directional
        if not (verb or (directional and m - k <= 4)):
            return ()
        places.append((directional, types))
    if not places:
        return ()
    return next((ts for d, ts in places if d), places[0][1])


def next_destination(ctx: DoubtContext, k: int, thing: str, words: NextPlace) -> str | None:
    """The first type of :func:`destinations`, or None."""
    found = destinations(ctx, k, thing, words)
    return found[0] if found else None


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_rule_words().next_place
    out: list[Doubt] = []
    seen: set[str] = set()
    for k, item, types in ctx.mentions():
        thing = types[0]
        if thing in seen or "pickupable" not in _props(thing):
            continue
        seen.add(thing)
        # the thing itself (not its slices: "slice it, the slices on the plate"), by type
        mine = tuple(c for c in ctx.goals if c.predicate.value in words.replaces and c.subject.types == (thing,))
        if not mine:
            continue
        dest = destinations(ctx, k, thing, words)
        if not dest or any(c.receptacle is not None and set(c.receptacle.types) & set(dest) for c in mine):
            continue     # no place said, or the reader's is one the words may name ("holder")
        counted = max(c.count for c in mine if c.predicate is Predicate.inside) if any(
            c.predicate is Predicate.inside for c in mine) else 1
        alt = placed(thing, dest[0])
        alt = alt.model_copy(update={"count": counted}) if counted > 1 else alt
        out.append(Doubt(KIND, item.text, (Choice(AS_READ, "; ".join(clause(c) for c in mine)),
                                           Choice("next_place", f"{type_name(thing)}: {clause(alt)}",
                                                  drop=mine, add=(alt,)))))
    return out
