"""Point of doubt: a thing joins the others of its kind ("the roll on the floor joins the
other one, wherever that ends up", "the lone CD joins the other two", "back in a drawer
with the other one").

The place is not said: it is where the other instances of the thing's type are at the end.
The type is the word after "other" when it names one ("the other CDs"), else the thing
named last before the cue that the scene has several of. The one that joins is the
instance whose place is named before the cue ("the roll on the floor"), else the one lying
apart from all the others. The others end where a goal of the reading sends them, or, when
the reading moves every other thing that lies with them to one place ("clear the counter
into the cabinets"), there; else they stay where they are. The alternative places all of
them there, counted, in place of the reading's goals for the type. The words are data
(``joins.json``, schema :class:`JoinWords` checked at load).
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

from pydantic import BaseModel, ConfigDict

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types, type_props
from emboteam.pfg.offline.doubts.rule_words import sentence_bounds
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.offline.knowledge import read
from emboteam.pfg.sentences import clause
from emboteam.world.goals import Condition, Predicate
from emboteam.world.state import ObjectState

KIND = "joins"
JOINS_FILE = Path(__file__).with_name("joins.json")


class JoinWords(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    about: str
    #: words that join a thing to others: a verb ("joins") or a preposition of company ("with")
    joining: list[str]
    #: the words for the others ("the other one", "the others")
    others: list[str]
    #: at most this many words between the joining word and the others word
    reach: int


@cache
def load_join_words(path: Path = JOINS_FILE) -> JoinWords:
    return read(path, JoinWords)


def _several(ctx: DoubtContext, types: tuple[str, ...]) -> str | None:
    """A thing one carries that the scene has several of (not "a drawer with the other")."""
    return next((t for t in types if "pickupable" in type_props(t) and len(list(ctx.state.of_type(t))) > 1), None)


def _type_at(ctx: DoubtContext, k: int, lo: int) -> tuple[str, int] | None:
    """The type the others at ``k`` are of and where the joining thing is named (in an
    earlier sentence when its own names none: "three CDs ...; the lone one joins ...")."""
    if k + 1 < len(ctx.items) and (after := _several(ctx, ctx.named_types(ctx.items[k + 1], verbs_too=True))):
        before = [m for m, _, types in ctx.mentions() if lo <= m < k and after in types]
        return (after, before[-1]) if before else None
    named = [(t, m) for m, _, types in ctx.mentions() if m < k and (t := _several(ctx, types))]
    return named[-1] if named else None


def _parent(ctx: DoubtContext, o: ObjectState) -> str:
    return ctx.state.obj(str(o.parent)).type


def _sent(ctx: DoubtContext, type_: str) -> set[str]:
    """The places the reading sends the type to."""
    return {t for c in ctx.goals if c.predicate is Predicate.inside and type_ in ref_types(c.subject)
            and c.receptacle is not None for t in ref_types(c.receptacle)}


def _attached(ctx: DoubtContext, m: int, p: int) -> bool:
    """Whether the place at ``p`` is said of the thing at ``m`` ("the roll on the floor")."""
    return m < p <= m + 3 and all(i.prep is not None or i.det for i in ctx.items[m + 1:p])


def _the_one(ctx: DoubtContext, type_: str, objs: list[ObjectState], m: int, k: int) -> ObjectState | None:
    """The one that joins: the place said of it ("the roll on the floor"), else a place
    named before the cue that the reading does not send it to ("back in a drawer with the
    other one" is where it goes), else the only one not at such a place, else the one lying
    apart."""
    sent = _sent(ctx, type_)
    lo, _ = sentence_bounds(ctx.items, k)
    places = [(p, set(types) if _attached(ctx, m, p) else set(types) - sent)
              for p, _, types in ctx.mentions() if max(lo, m) < p < k]
    for _, types in sorted(places, key=lambda x: not _attached(ctx, m, x[0])):
        hit = [o for o in objs if _parent(ctx, o) in types]
        if len(hit) == 1:
            return hit[0]
    away = [o for o in objs if _parent(ctx, o) not in sent]
    if sent and len(away) == 1:
        return away[0]
    apart = [o for o in objs if sum(_parent(ctx, p) == _parent(ctx, o) for p in objs) == 1]
    return apart[0] if len(apart) == 1 else None


def _end_place(ctx: DoubtContext, type_: str, one: ObjectState, others: list[ObjectState]) -> str | None:
    """Where the others are at the end: a place the reading sends the type (not where the
    one lies: the reader's "on the floor" is where it is), else where the reading sends
    everything lying with them, else where they are."""
    starts = {_parent(ctx, o) for o in others}
    if len(starts) != 1:
        return None
    start = next(iter(starts))
    sent = _sent(ctx, type_) - {start, _parent(ctx, one)}
    if len(sent) == 1:
        return next(iter(sent))
    mates = {o.type for p in ctx.state.of_type(start) for o in ctx.state.children(p.id)} - {type_}
    swept = {t for c in ctx.goals if c.predicate is Predicate.inside and c.receptacle is not None
             and ref_types(c.subject) & mates for t in ref_types(c.receptacle)}
    moved = sum(1 for c in ctx.goals if c.predicate is Predicate.inside and ref_types(c.subject) & mates)
    return next(iter(swept)) if len(swept) == 1 and moved > 1 else start


def _doubt(ctx: DoubtContext, j: int, k: int) -> Doubt | None:
    lo, _ = sentence_bounds(ctx.items, j)
    found = _type_at(ctx, k, lo)
    if found is None:
        return None
    type_, m = found
    objs = [o for o in ctx.state.of_type(type_) if o.parent is not None]
    mine = tuple(c for c in ctx.goals if c.predicate is Predicate.inside and type_ in ref_types(c.subject))
    said = {t for p, _, types in ctx.mentions() if _attached(ctx, m, p) for t in types}
    joined = _joined(ctx, tuple(c for c in mine if c.receptacle and not ref_types(c.receptacle) & said), objs)
    if joined is not None:
        # the place is said ("-> the side table, with the other one"): the ones there count too
        return _choices(ctx, m, mine, joined)
    one = _the_one(ctx, type_, objs, m, j)
    if one is None:
        return None
    others = [o for o in objs if o.id != one.id]
    place = _end_place(ctx, type_, one, others)
    if place is None:
        return None
    alt = placed(type_, place)
    return _choices(ctx, m, mine, alt.model_copy(update={"count": len(objs)}) if len(objs) > 1 else alt)


def _joined(ctx: DoubtContext, mine: tuple[Condition, ...], objs: list[ObjectState]) -> Condition | None:
    """The reading's goal that sends the type where others of it lie now, counting them."""
    for c in mine:
        if c.receptacle is None:
            continue
        to = ref_types(c.receptacle)
        there = [o for o in objs if _parent(ctx, o) in to]
        if there:
            sent = sum(g.count for g in mine if g.receptacle is not None and ref_types(g.receptacle) == to)
            return placed(next(iter(ref_types(c.subject) & {o.type for o in objs})), next(iter(to))).model_copy(
                update={"count": min(len(objs), sent + len(there))})
    return None


def _choices(ctx: DoubtContext, m: int, mine: tuple[Condition, ...], alt: Condition) -> Doubt | None:
    if mine == (alt,):
        return None
    return Doubt(KIND, ctx.items[m].text, (Choice(AS_READ, "; ".join(clause(c) for c in mine) or "as read"),
                                           Choice("with_the_others", clause(alt), drop=mine, add=(alt,))))


def doubts(ctx: DoubtContext) -> list[Doubt]:
    """Every "joins the other one(s)" of the instruction."""
    words = load_join_words()
    out: list[Doubt] = []
    for j, item in enumerate(ctx.items):
        if item.text not in words.joining:
            continue
        k = next((x for x in range(j + 1, min(len(ctx.items), j + 2 + words.reach))
                  if ctx.items[x].text in words.others), None)
        if k is not None and (d := _doubt(ctx, j, k)) is not None and all(d.span != o.span for o in out):
            out.append(d)
    return out
