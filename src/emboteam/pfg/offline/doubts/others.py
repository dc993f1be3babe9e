"""Point of doubt: one of a kind moved, "the other ones" kept ("the statue on the table
goes in the box and the other ones stay where they are", "of the two rolls on the
toilet, one goes on the hanger and the other stays", "the spare stays on its shelf"; the kept one said first: "of the two rolls, one stays there
and the spare goes in the drawer").

"The other(s)", "the spare", "the rest" with a keeping word after it, in the same
stretch, names the instances of a type the scene has several of that the request did not
single out. The type is the word after "other" ("the other statues") or the thing named
last before it. The alternative moves exactly one instance as the reading's goal for the
type says (the one a place before the cue singles out, "the one on the table") and keeps
every other instance where it is now (its receptacle's type, counted); it replaces the
reading's goals for that type. The words are data (``rule_words.json``, ``others``).
"""

from __future__ import annotations

from collections import Counter

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.rule_words import load_rule_words
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.sentences import clause
from emboteam.world.goals import Condition, ObjectRef, Predicate
from emboteam.world.state import ObjectState

KIND = "others"


def _type_at(ctx: DoubtContext, k: int) -> str | None:
    """The type "the other ..." at ``k`` is about: the word after it, else the thing
    named last before it; a thing the scene has several of and the reading places."""
    placed_types = {t for c in ctx.goals if c.predicate is Predicate.inside for t in ref_types(c.subject)}

    def several(types: tuple[str, ...]) -> str | None:
        return next((t for t in types if t in placed_types and len(list(ctx.state.of_type(t))) > 1), None)
    if k + 1 < len(ctx.items) and (after := several(ctx.named_types(ctx.items[k + 1], verbs_too=True))):
        return after
    before = [t for m, _, types in ctx.mentions() if m < k and (t := several(types))]
    return before[-1] if before else None


def _the_one(ctx: DoubtContext, type_: str, k: int, objs: list[ObjectState]) -> ObjectState:
    """The instance singled out: the one whose place is named last before the cue ("the
    one on the table"), else the first."""
    parents = {o.id: ctx.state.obj(o.parent).type for o in objs if o.parent is not None}
    named = [ts for m, _, ts in ctx.mentions() if m < k and set(ts) & set(parents.values())]
    for types in reversed(named):
        hit = [o for o in objs if parents.get(o.id) in types]
        if len(hit) == 1:
            return hit[0]
    return objs[0]


def _place_after(ctx: DoubtContext, k: int) -> tuple[str, ...]:
    """The place named right after the phrase ("the one on the holder")."""
    words = load_rule_words().others
    for m, _, types in ctx.mentions():
        if k < m <= k + 3 and any(i.text in words.place_preps for i in ctx.items[k + 1:m]):
            return types
    return ()


def _doubt(ctx: DoubtContext, k: int) -> Doubt | None:
    type_ = _type_at(ctx, k)
    if type_ is None:
        return None
    moving = [c for c in ctx.goals if c.predicate is Predicate.inside and type_ in ref_types(c.subject)
              and c.receptacle is not None]
    objs = [o for o in ctx.state.of_type(type_) if o.parent is not None]
    if not moving or len(objs) < 2:
        return None
    # the goal that moves some away from where they all are ("one stays there and the spare
    # goes in the drawer": not the keep of the first clause)
    now = {ctx.state.obj(str(o.parent)).type for o in objs}
    move = next((c for c in moving if c.receptacle is not None and not ref_types(c.receptacle) & now), moving[0])
    dest = ref_types(move.receptacle) if move.receptacle is not None else frozenset()
    here = _place_after(ctx, k)
    staying = [o for o in objs if ctx.state.obj(str(o.parent)).type in here]
    if staying and len(staying) < len(objs):
        # "the one on the holder stays": the place after the phrase names the kept ones
        one = next(o for o in objs if o not in staying)
    else:
        one = _the_one(ctx, type_, k, [o for o in objs if ctx.state.obj(str(o.parent)).type not in dest] or objs)
    if one.parent is not None and ctx.state.obj(one.parent).type in dest:
        return None     # the goal read is where the one is already: not the move meant
    kept = Counter(ctx.state.obj(str(o.parent)).type for o in objs if o.id != one.id)
    if dest & set(kept):
        return None     # "the one already in a drawer is fine": the one joins the others, no other reading
    # by type: with every other instance kept where it is, only the one can move
    add: list[Condition] = [move.model_copy(update={"subject": ObjectRef(types=(type_,)), "count": 1})]
    add += [placed(type_, p).model_copy(update={"count": n}) if n > 1 else placed(type_, p) for p, n in kept.items()]
    if set(add) == set(moving):
        return None
    return Doubt(KIND, ctx.items[k].text, (Choice(AS_READ, "as read"),
                                           Choice("one_and_the_others", "; ".join(clause(c) for c in add),
                                                  drop=tuple(moving), add=tuple(add))))


def _kept(ctx: DoubtContext, k: int, keepers: list[str]) -> bool:
    """Whether what the phrase at ``k`` says of them is to stay: the first verb or keeping
    word after it is a keeping word ("the other ones stay", "the one on the holder stays";
    not "the one on the table goes in the box")."""
    _, end = ctx.clause_bounds(k)
    for item in ctx.items[k + 1:end]:
        if item.text in keepers:
            return True
        if item.verb is not None and item.noun is None:
            return False
    return False


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_rule_words().others
    out = []
    for k, item in enumerate(ctx.items):
        if item.text not in words.others or k == 0:
            continue
        # "the other stays", or a clause opened by the pro-form "one" ("of the two rolls, one
        # stays there"; not the numeral of "one vase can stay")
        if ctx.items[k - 1].text not in words.determiners and \
                not (item.text in words.openers and ctx.items[k - 1].punct is not None
                     and not (k + 1 < len(ctx.items) and ctx.named_types(ctx.items[k + 1]))):
            continue
        if not _kept(ctx, k, words.keepers):
            continue
        d = _doubt(ctx, k)
        if d is not None:
            out.append(d)
    return out
