"""Point of doubt: an unexplained mention, a thing of the scene the instruction names
that ends in no goal and that nothing explains (:mod:`.explained`).

It is the most common silent loss (a clause after a misheard conjunction, an item joined
by "+", a participle in a verbless list, a split or misspelled name). Its alternatives:
leave it (chatter, as read), or give it the end state its neighbours ask for: the goal
before it or after it carried over ("the apple in the fridge, the egg too"), a state word
or verb of its own stretch ("the mug washed"), a place named after it ("bowl + plate in
the sink"), or, when none of these says it, the goals the scene allows for the thing
by what it affords (:mod:`.affordances`: the switch or open state it is not in, a place
named near it).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts import affordances
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.counts import counted, said_count
from emboteam.pfg.offline.doubts.destination import (
    destination,
    head_place,
    load_destination_cues,
    place_before,
    present,
    same_place,
    window,
)
from emboteam.pfg.offline.doubts.explained import CORRECTIONS, NEGATED, explanation
from emboteam.pfg.offline.doubts.mention_cues import said_state
from emboteam.pfg.offline.doubts.rule_words import find, load_rule_words
from emboteam.pfg.offline.doubts.wants import asked_predicate, one_object, placed, with_subject
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.catalogue import load_catalogue
from emboteam.world.checker import check_condition
from emboteam.world.goals import Condition, Predicate

KIND = "unexplained_mention"
#: the labels of the goals a window gives (priors.json, kind unexplained_mention)
PLACE, KEEP = "window_place", "window_keep"
#: the label of the goal an additive word carries over ("same for the cloth", "the soap
#: bottle too")
CARRY_SAID = "carry_said"
#: the additive words ("too", "as well", "same for": rule_words.json's contents lists; "same
#: deal", "incl": destination_cues.json's carry_over), one list for the life of the process
#: (:func:`.rule_words.find` indexes a list by its id)
_ADDITIVE = [*load_rule_words().contents.stay_too, *load_rule_words().contents.also_stays,
             *load_destination_cues().carry_over]


def unexplained_spans(ctx: DoubtContext, unless: frozenset[str] = frozenset()) -> list[tuple[int, str, tuple[str, ...]]]:
    """(position, words, scene types) of each mention nothing explains (explanations in
    ``unless`` do not count), one per thing."""
    out: list[tuple[int, str, tuple[str, ...]]] = []
    seen: set[str] = set()
    for k, item, types in ctx.mentions():
        if types[0] in seen or explanation(ctx, k, types) not in (None, *unless):
            continue
        seen.add(types[0])
        out.append((k, item.text, types))
    return out


def _neighbour_goals(ctx: DoubtContext, k: int) -> tuple[Condition | None, Condition | None]:
    """The goal conditions whose objects are named last before ``k`` and first after."""
    placed_at = [(pos, c) for c in ctx.goals if (pos := ctx.position_of(c)) is not None]
    before = [(pos, c) for pos, c in placed_at if pos < k]
    after = [(pos, c) for pos, c in placed_at if pos > k]
    return (max(before, key=lambda x: x[0])[1] if before else None,
            min(after, key=lambda x: x[0])[1] if after else None)


def _own_words(ctx: DoubtContext, k: int, thing: str) -> list[Condition]:
    """Goals the words of the mention's own stretch ask of it: a state word or verb (a
    place is its window's: :func:`window_goal`)."""
    start, end = ctx.clause_bounds(k)
    return [one_object(pred, thing) for item in ctx.items[start:end]
            if (pred := asked_predicate(item)) is not None and pred is not Predicate.inside]


def carried(ctx: DoubtContext, k: int, thing: str) -> Condition | None:
    """The goal an additive word in the mention's own verbless stretch carries over to it
    ("the spray out of sight in a drawer. Same for the cloth.", "the cloth into the
    cabinet, the soap bottle too"), or None: for a thing that can be moved, the nearest
    place before the stretch a towards cue leads to and it can go in (not where it is);
    for another, the nearest goal before it of a predicate other than a place."""
    start, end = ctx.clause_bounds(k)
    cues = find(ctx.items, start, end, _ADDITIVE)
    cued = {j for b, e in cues for j in range(b, e)}
    if not cues or any(i.verb is not None or i.state is not None or i.copula
                       for j, i in enumerate(ctx.items[start:end], start) if j not in cued):
        return None
    cat = load_catalogue()
    if "pickupable" not in cat.type(thing).properties:
        before = sorted(((pos, c) for c in ctx.goals if (pos := ctx.position_of(c)) is not None and pos < start
                         and c.predicate is not Predicate.inside), key=lambda x: -x[0])
        return with_subject(before[0][1], thing) if before else None
    place = place_before(ctx, start, thing)
    return placed(thing, place[0]) if place else None


def window_goal(ctx: DoubtContext, k: int, thing: str) -> tuple[str, tuple[Condition, ...]] | None:
    """(label, goals) the window of the mention at ``k`` gives the thing, or None: its
    place (kept, or where it goes), and a state its words ask beside it ("out and
    burning on the counter")."""
    if "pickupable" not in load_catalogue().type(thing).properties:
        return None
    data = load_destination_cues()
    lo, hi = window(ctx, k, thing)
    if any(i.text in CORRECTIONS and i.text != "no" for i in ctx.items[lo:hi]) or find(ctx.items, lo, hi, data.described):
        return None      # "in the drawer - sorry, the box": the correction rules' (corrections.py)
    said = said_count(ctx, k, thing)
    keeps = find(ctx.items, lo, min(hi, k + 1 + data.keep_reach), data.keep)
    # a place it is sent to before the keep cue is where it goes, the keep a later thing's
    # ("keys + card -> a drawer. shut it after, all of em stay shut")
    sent = destination(ctx, k, thing, keeps[0][0]) if keeps else ()
    if keeps and not sent:
        here = sorted(present(ctx, thing))
        return (KEEP, (counted(placed(thing, here[0]), said),)) if len(here) == 1 else None
    dest = sent or destination(ctx, k, thing, hi) or head_place(ctx, k, thing) or same_place(ctx, k, lo, hi, thing)
    if not dest:
        return None
    state = said_state(ctx, k, hi, thing) or _changed(ctx, lo, hi, thing)
    pieces = load_catalogue().slice_product(thing) if state is not None and state.predicate is Predicate.sliced else None
    goal = counted(placed(pieces[0] if pieces else thing, dest[0]), said)     # "the apple cut up on a plate"
    return PLACE, (goal,) if state is None else (state, goal)


#: what a verb of the window may ask beside the place ("is heating in the microwave",
#: "cut up on a plate"); switch and open states come from :func:`.mention_cues.said_state`
_CHANGES = (Predicate.hot, Predicate.cold, Predicate.sliced, Predicate.cooked, Predicate.clean)


def _changed(ctx: DoubtContext, lo: int, hi: int, thing: str) -> Condition | None:
    pred = next((p for i in ctx.items[lo:hi] if (p := asked_predicate(i)) in _CHANGES), None)
    return None if pred is None else one_object(pred, thing)


def doubts(ctx: DoubtContext, unless: frozenset[str] = frozenset()) -> list[Doubt]:
    out = []
    for k, words, types in unexplained_spans(ctx, unless):
        thing = types[0]
        # the first of its unexplained mentions whose window says where it goes ("my brother
        # borrows the bats ... bats are kept on my bedside table")
        named = [(m, explanation(ctx, m, ts, goals=False)) for m, _, ts in ctx.mentions() if ts[0] == thing]
        again = (m for m, why in named if m >= k and why in (None, *unless))
        strong = None if any(why == NEGATED for _, why in named) else next(      # "..., oh wait, not the CD"
            (w for m in again if (w := window_goal(ctx, m, thing)) is not None), None)
        if strong is not None:     # its own window says where it goes: only that, or leaving it
            out.append(Doubt(KIND, words, (Choice(AS_READ, f"{words!r} asks nothing (chatter)"),
                                           Choice(strong[0], f"{type_name(thing)}: " + "; ".join(
                                               clause(c) for c in strong[1]), add=strong[1]))))
            continue
        proposals: list[tuple[str, Condition]] = [("own_words", c) for c in _own_words(ctx, k, thing)]
        if (said := carried(ctx, k, thing)) is not None:
            proposals.insert(0, (CARRY_SAID, said))
        prev, nxt = _neighbour_goals(ctx, k)
        for label, c in (("carry_previous", prev), ("carry_next", nxt)):
            if c is not None:
                proposals.append((label, with_subject(c, thing)))
        proposals += affordances.proposals(ctx, k, thing)
        choices = [Choice(AS_READ, f"{words!r} asks nothing (chatter)")]
        # a place where it is already asks nothing ("the remote's all the way over on the desk")
        seen = {str(c) for _, c in proposals if c.predicate is Predicate.inside and check_condition(c, ctx.state).holds}
        for label, c in proposals:
            if str(c) not in seen:
                seen.add(str(c))
                choices.append(Choice(label, f"{type_name(thing)}: {clause(c)}", add=(c,)))
        out.append(Doubt(KIND, words, tuple(choices)))
    return out
