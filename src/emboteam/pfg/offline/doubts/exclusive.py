"""Point of doubt: an exclusive purpose, "only the floor lamp on", "the telly is the one
and only light", "candles are the only light allowed", "dark apart from the screen",
"by candlelight".

The words name one light or screen to keep on and, by "only", "nothing else", "every
other", "apart from", say that the rest is off. The alternatives: that thing on and every
other light of the room off, or every other light and screen off. Goals the reader gave
those devices' switches are replaced. The cues and the device types are data
(``rule_words.json``, ``exclusive``).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.rule_words import Exclusive, find, load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.wants import one_object
from emboteam.pfg.offline.lexicon import Act
from emboteam.pfg.sentences import type_name
from emboteam.world.goals import Condition, Predicate

KIND = "exclusive"
_SWITCHES = (Predicate.switched_on, Predicate.switched_off)


def _devices(ctx: DoubtContext, lo: int, hi: int, words: Exclusive) -> list[tuple[int, str]]:
    """(position, type) of the lights and screens named between ``lo`` and ``hi`` (the
    word "light" itself names no one device)."""
    kinds = set(words.lights) | set(words.screens)
    return [(m, next(t for t in ts if t in kinds)) for m, item, ts in ctx.mentions()
            if lo <= m < hi and set(ts) & kinds
            and (item.noun is None or item.noun.concept.kind not in ("lights", "lamps"))]


def _kept(ctx: DoubtContext, start: int, end: int, cue: tuple[int, int], kept: str,
          words: Exclusive) -> str | None:
    at, after = cue
    inside = _devices(ctx, at, after, words)
    if kept == "inside":
        return inside[0][1] if inside else None
    later = _devices(ctx, after, min(end, after + 3), words)
    earlier = _devices(ctx, max(start, at - words.reach), at, words)
    if kept in ("after", "either") and later:
        return later[0][1]
    if kept in ("before", "either") and earlier:
        return earlier[-1][1]
    return None


def _proposal(ctx: DoubtContext, keep: str, off: list[str]) -> tuple[Condition, ...]:
    return (one_object(Predicate.switched_on, keep), *(one_object(Predicate.switched_off, t) for t in off))


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_rule_words().exclusive
    for cue in find(ctx.items, 0, len(ctx.items), [c.words for c in words.cues]):
        rule = next(c for c in words.cues if ctx.items[cue[0]:cue[1]] and
                    [i.text for i in ctx.items[cue[0]:cue[1]]] == c.words)
        start, end = sentence_bounds(ctx.items, cue[0])
        # a restrictive word ("turn off only ...", not a state said after a copula: "the telly
        # is off, ... the lamp is the only light on") or a verb switching off in the sentence
        if any((i.text in words.restrictive and not (n > 0 and ctx.items[n - 1].copula))
               or (i.verb is not None and i.verb.sense.act is Act.SWITCH_OFF)
               for n, i in enumerate(ctx.items[start:cue[0]], start=start)):
            continue    # "don't turn off the desk lamp, only the floor lamp"
        if rule.kept == "after" and any((i.verb is not None and i.verb.sense.act in words.excepted_from)
                                        or i.text in words.excepted_from_words for i in ctx.items[start:cue[0]]):
            continue    # "everything goes in the drawers except the candle": an exception to a move
        if any(i.text in rule.not_after for i in ctx.items[max(start, cue[0] - words.reach):cue[0]]):
            continue    # "leave the candle alone": hands off it
        keep = _kept(ctx, start, end, cue, rule.kept, words)
        if keep is None or not ctx.scene.of_type(keep):
            continue
        lights = [t for t in words.lights if t != keep and ctx.scene.of_type(t)]
        screens = [t for t in words.screens if t != keep and ctx.scene.of_type(t)]
        devices = {keep, *lights, *screens}
        drop = tuple(c for c in ctx.goals if c.predicate in _SWITCHES and ref_types(c.subject) & devices)
        choices = [Choice(AS_READ, "the lights as read")]
        for label, off in (("others_off", lights), ("screens_off_too", lights + screens)):
            add = _proposal(ctx, keep, off)
            if off and not set(add) <= set(ctx.goals):
                choices.append(Choice(label, f"only the {type_name(keep)} on: "
                                      + ", ".join(type_name(t) for t in off) + " off",
                                      drop=tuple(c for c in drop if c not in add), add=add))
        if len(choices) > 1:
            return [Doubt(KIND, " ".join(i.text for i in ctx.items[cue[0]:cue[1]]), tuple(choices))]
    return []
