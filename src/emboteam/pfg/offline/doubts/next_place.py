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
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.rule_words import NextPlace, find, load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.catalogue import load_catalogue

KIND = "next_place"


def _is(type_: str, prop: str) -> bool:
    return prop in load_catalogue().type(type_).properties


def next_destination(ctx: DoubtContext, k: int, thing: str, words: NextPlace) -> str | None:
    """The first receptacle after position ``k`` in its sentence that a destination cue
    leads to and no negation since ``k`` rules out."""
    start, end = sentence_bounds(ctx.items, k)
    if any(i.text in load_rule_words().correction_object.cues for i in ctx.items[start:end]):
        return None     # a self-correction's places are the correction rules' (scope.py)
    end = min(end, k + words.reach)
    clause_start, _ = ctx.clause_bounds(k)
    since = k + 1     # a negation rules out the first place after it
    cues = {e: ctx.items[b].text for b, e in find(ctx.items, k + 1, end, words.destination_cues)}
    for m, item, types in ctx.mentions():
        if not k < m < end or types[0] == thing or not _is(types[0], "receptacle") or item.noun is None:
            continue
        lead = [cues[j] for j in range(max(k + 1, m - 2), m + 1) if j in cues]
        if not lead:
            continue
        if any(i.neg for i in ctx.items[since:m]):
            since = m + 1
            continue    # "plates don't live on the coffee table - their home is the shelf"
        # the first place after the thing: where it is ("lying on", "the CD in the drawer,
        # put it ..."), or where it goes (a verb before the place, or a direction)
        located = any(i.text in words.locatives for i in ctx.items[max(k + 1, m - 3):m])
        verb = any(i.verb is not None or i.copula for i in ctx.items[clause_start:m] if i is not ctx.items[k])
        return types[0] if not located and (lead[0] in words.directional or verb) else None
    return None


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_rule_words().next_place
    out: list[Doubt] = []
    seen: set[str] = set()
    for k, item, types in ctx.mentions():
        thing = types[0]
        if thing in seen or not _is(thing, "pickupable"):
            continue
        seen.add(thing)
        mine = tuple(c for c in ctx.goals if c.predicate.value in words.replaces and thing in ref_types(c.subject)
                     and c.subject.id is None)
        if not mine:
            continue
        dest = next_destination(ctx, k, thing, words)
        if dest is None:
            continue
        alt = placed(thing, dest)
        if alt in ctx.goals:
            continue
        out.append(Doubt(KIND, item.text, (Choice(AS_READ, "; ".join(clause(c) for c in mine)),
                                           Choice("next_place", f"{type_name(thing)}: {clause(alt)}",
                                                  drop=mine, add=(alt,)))))
    return out
