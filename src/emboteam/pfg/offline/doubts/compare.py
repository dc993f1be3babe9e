"""Point of doubt: a thing singled out by comparison ("the heavier of the two sports
things on the floor goes on the bed", "from the two bottles on the counter, the bigger
goes in the drawer", "the bigger one on the desk (not the laptop) - switch it on").

The reader reads no object in such a phrase (its head is "one", "things" or nothing), so
the request is dropped or lands on a neighbour. The scene decides: the pool is the
scene's objects of the types named with the comparative (after it, or after "of the
two") or, when those name no type, the things standing where the phrase says ("on the
floor"), less the things it excludes ("not the laptop"); the comparative picks the one of
greatest or least mass (AI2-THOR gives no sizes: mass stands for size too). What is asked
of it is the destination or the state its clause says ("goes up on the bed", "switch it
on"); the others of the pool stay where they are when a keeping word follows ("the small
one stays"). The alternatives: the one the scene picks, then each other one of the pool.
The words are data (``rule_words.json``, ``compare``).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types, type_props
from emboteam.pfg.offline.doubts.destination import destination
from emboteam.pfg.offline.doubts.rule_words import find, load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.wants import asked_predicate, one_object, placed
from emboteam.pfg.sentences import clause
from emboteam.world.goals import Condition, Predicate
from emboteam.world.state import ObjectState

KIND = "compare"

#: what a thing must afford for the goal asked of it (a placement: be picked up)
_NEEDS = {Predicate.inside: "pickupable", Predicate.switched_on: "toggleable", Predicate.switched_off: "toggleable",
          Predicate.open: "openable", Predicate.closed: "openable", Predicate.sliced: "sliceable"}


def _pool_types(ctx: DoubtContext, k: int, hi: int) -> tuple[set[str], int]:
    """The types named with the comparative at ``k`` (right after it, past "one", or
    after "of / from the two" in its sentence) and where that name ends."""
    words = load_rule_words().compare
    lo = sentence_bounds(ctx.items, k)[0]
    for start, end in find(ctx.items, lo, hi, words.pool_cues):
        if start >= k + 3 or end < k - 8:
            continue
        types: set[str] = set()
        last = end - 1
        for m, _, ts in ctx.mentions():      # the list after it: "of the pan and the pot"
            between = ctx.items[last + 1:m]
            if m >= end and ((not types and m <= end + 2) or (types and all(
                    i.det or i.conj or i.punct == "," for i in between))):
                types, last = types | set(ts), m
        return types, last if types else end
    j = k + 1 + (k + 1 < len(ctx.items) and ctx.items[k + 1].text in words.heads)
    head = set(ctx.named_types(ctx.items[j], verbs_too=True)) if j < len(ctx.items) else set()
    return head, j if head else k


def _pool(ctx: DoubtContext, k: int, hi: int) -> list[ObjectState]:
    """The scene's objects the comparison is among (see the module's docstring)."""
    words = load_rule_words().compare
    types, at = _pool_types(ctx, k, hi)
    here: set[str] = set()
    for m, _, ts in ctx.mentions():     # "on the floor" right after the name
        if at < m <= at + 4 and any(i.prep is not None for i in ctx.items[at + 1:m]):
            here = set(ts)
            break
    not_these = {t for s, e in find(ctx.items, k, hi, words.excluders)
                 for m, _, ts in ctx.mentions() if e <= m <= e + 2 for t in ts}
    objs = [o for o in ctx.state.objects.values() if not o.gone and o.type not in not_these and o.mass > 0
            and (o.type in types if types else bool(here))]
    there = [o for o in objs if o.parent is not None and ctx.state.obj(o.parent).type in here]
    # a place after a name that leaves too few is where they go, not where they are
    return there if len(there) > 1 or not types else objs


def _asked(ctx: DoubtContext, k: int, hi: int, thing: str) -> Condition | None:
    """What the clause asks of the thing picked: a destination, else a state."""
    dest = destination(ctx, k, thing, hi)
    if dest:
        return placed(thing, dest[0])
    preds = [p for i in ctx.items[k + 1:hi] if (p := asked_predicate(i)) is not None]
    return one_object(preds[0], thing) if preds and preds[0] is not Predicate.held else None


def _doubt(ctx: DoubtContext, k: int, most: bool) -> Doubt | None:
    words = load_rule_words().compare
    hi = sentence_bounds(ctx.items, k)[1]
    stop = next((j for j in range(k + 1, hi) if ctx.items[j].punct in words.clause_ends), hi)
    objs = _pool(ctx, k, hi)
    # the ones the clause's goal fits ("switch it on": the things that switch), by mass
    asked = {o.id: goal for o in objs if (goal := _asked(ctx, k, stop, o.type)) is not None
             and _NEEDS.get(goal.predicate, "") in {"", *o.properties, *type_props(o.type)}}
    ranked = sorted((o for o in objs if o.id in asked), key=lambda o: o.mass, reverse=most)
    if len(objs) < 2 or not ranked or len({o.type for o in ranked}) < len(ranked) or \
            (len(ranked) > 1 and ranked[0].mass == ranked[1].mass):
        return None     # nothing to compare, several of a type (a goal by type cannot single one out), a tie
    pool = {o.type for o in objs}
    # "the bigger goes in a cupboard; the small one stays": the clause after a semicolon
    then = sentence_bounds(ctx.items, stop + 1)[1] if stop < len(ctx.items) and ctx.items[stop].punct == ";" else hi
    kept = bool(find(ctx.items, stop, then, [[w] for w in words.keepers]))
    choices = [Choice(AS_READ, "as read")]
    for one in ranked:
        goal = asked[one.id]
        add = [goal, *(placed(o.type, ctx.state.obj(o.parent).type) for o in ranked
                       if kept and o is not one and o.parent is not None)]
        # the reader's goals for the pool, or for what it read the phrase as ("the biggest of
        # the things ...": everything, each thing no word names sent the same way)
        drop = tuple(c for c in ctx.goals if c.predicate is goal.predicate and c not in add and (
            ref_types(c.subject) & pool or (c.receptacle == goal.receptacle and ctx.position_of(c) is None)))
        choices.append(Choice("scene_picks" if one is ranked[0] else "another", "; ".join(clause(c) for c in add),
                              drop=drop, add=tuple(c for c in add if c not in ctx.goals)))
    return Doubt(KIND, ctx.items[k].text, tuple(c for c in choices if c.as_read or c.add or c.drop))


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_rule_words().compare
    out = []
    for k, item in enumerate(ctx.items):
        most = item.text in words.more
        if (most or item.text in words.less) and k > 0 and ctx.items[k - 1].det:
            d = _doubt(ctx, k, most)
            if d is not None and len(d.choices) > 1:
                out.append(d)
    return out
