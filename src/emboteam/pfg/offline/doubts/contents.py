"""Point of doubt: "everything on X except Y goes in Z", "empty the fridge onto the
counter, except the egg": an exclusion over a receptacle's contents.

The grammar reads "everything" only for switching off and closing; here the words give a
source (the receptacle after a quantifier or an emptying verb), a destination (a
receptacle after a placing preposition, or the bin for a throwing verb) and the excluded
things (after "except", "apart from", ...). The alternative moves every pickupable thing
that stands in the source now (the world state says which) to the destination, keeps
each excluded thing where it is and closes a source that is closed now; goals the reader
gave those things are replaced. The
words are data (``rule_words.json``, ``contents``).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.rule_words import Contents, find, load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.wants import one_object, placed
from emboteam.pfg.sentences import type_name
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Condition, Predicate

KIND = "contents"


def _is(type_: str, prop: str) -> bool:
    return prop in load_catalogue().type(type_).properties


def _trigger(ctx: DoubtContext, words: Contents) -> int | None:
    for k, item in enumerate(ctx.items):
        if item.text in words.quantifiers or item.text in words.emptying_verbs:
            return k
    return None


def _source(ctx: DoubtContext, k: int, end: int, words: Contents) -> tuple[int, str] | None:
    """The receptacle whose contents are meant: after a source preposition (or right after
    an emptying verb) within reach; "in there" is the receptacle named last before."""
    emptying = ctx.items[k].text in words.emptying_verbs
    for m, _, types in ctx.mentions():
        if k < m < min(end, k + words.reach):
            if not _is(types[0], "receptacle"):
                return None     # "all three vases on the counter": things, not contents
            lead = [i.text for i in ctx.items[max(k + 1, m - 2):m]]
            if emptying or any(w in words.source_preps for w in lead):
                return m, types[0]
    for j in range(k + 1, min(end, k + 3)):
        if ctx.items[j].text in words.pronoun_places and ctx.items[j - 1].text in words.source_preps:
            before = [(m, ts[0]) for m, _, ts in ctx.mentions() if m < k and _is(ts[0], "receptacle")]
            return before[-1] if before else None
    return None


def _excluded(ctx: DoubtContext, start: int, end: int, words: Contents) -> list[str]:
    """The things named after an excluder (a list: up to a verb, a clause mark or a
    sequence word; marks right after the excluder do not end it)."""
    out: list[str] = []
    for _, after in find(ctx.items, start, end, words.excluders):
        j, leading = after, True
        while j < end:
            item = ctx.items[j]
            if item.punct is not None and leading:
                j += 1
                continue
            if item.punct is not None or item.seq is not None or (item.verb is not None and item.noun is None):
                break
            leading = False
            types = ctx.named_types(item, verbs_too=True)     # "except the watch"
            if types and _is(types[0], "pickupable"):
                out.append(types[0])
            j += 1
    return out


def _destination(ctx: DoubtContext, src_at: int, end: int, source: str, excluded: list[str],
                 words: Contents) -> str | None:
    """The receptacle after the source that a placing preposition leads to, with only
    excluded things named between ("clear my desk: the mug goes on ..." is a list)."""
    for m, _, types in ctx.mentions():
        if not src_at < m < end or types[0] == source:
            continue
        if _is(types[0], "receptacle") and \
                any(i.text in words.destination_preps for i in ctx.items[max(src_at + 1, m - 2):m]):
            return types[0]
        if _is(types[0], "pickupable") and types[0] not in excluded:
            return None
    start, _ = sentence_bounds(ctx.items, src_at)
    if any(i.verb is not None and i.verb.sense.act.value in words.trash_acts for i in ctx.items[start:end]):
        return words.trash_place
    return None


def _contents(ctx: DoubtContext, source: str) -> list[str]:
    """The pickupable things standing in or on a receptacle of the type now, by type."""
    out = []
    for o in ctx.state.objects.values():
        if o.parent is not None and o.has("pickupable") and ctx.state.obj(o.parent).type == source:
            t = load_catalogue().source_type(o.type) or o.type
            out.append(t)
    return list(dict.fromkeys(out))


def _count(ctx: DoubtContext, type_: str, source: str) -> int:
    return sum(1 for o in ctx.state.of_type(type_) if o.parent is not None and ctx.state.obj(o.parent).type == source)


def _goal(type_: str, place: str, count: int) -> Condition:
    c = placed(type_, place)
    return c.model_copy(update={"count": count}) if count > 1 else c


def _closed_again(ctx: DoubtContext, source: str) -> list[Condition]:
    """A source that is closed now is closed again once emptied (the fridge, a cabinet:
    taking things out opens it; the person left it shut)."""
    objs = list(ctx.state.of_type(source))
    if objs and all(o.has("openable") and not o.is_open for o in objs):
        return [one_object(Predicate.closed, source)]
    return []


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_rule_words().contents
    k = _trigger(ctx, words)
    if k is None:
        return []
    _, end = sentence_bounds(ctx.items, k)
    found = _source(ctx, k, end, words)
    if found is None:
        return []
    src_at, source = found
    excluded = _excluded(ctx, k, end, words)
    dest = _destination(ctx, src_at, end, source, excluded, words)
    if dest is None:
        return []
    moved = [t for t in _contents(ctx, source) if t not in excluded and t != dest]
    kept = [t for t in dict.fromkeys(excluded) if _count(ctx, t, source)]
    if not moved:
        return []
    add = tuple([placed(t, dest) for t in moved] + [_goal(t, source, _count(ctx, t, source)) for t in kept]
                + _closed_again(ctx, source))
    touched = set(moved) | set(kept)
    drop = tuple(c for c in ctx.goals if ref_types(c.subject) & touched and c not in add)
    if set(add) <= set(ctx.goals):
        return []
    how = f"what is in/on the {type_name(source)} goes to the {type_name(dest)}" + (
        f", except {', '.join(type_name(t) for t in kept)}" if kept else "")
    return [Doubt(KIND, ctx.items[k].text, (Choice(AS_READ, "the things as read"),
                                            Choice("all_contents", how, drop=drop, add=add)))]

