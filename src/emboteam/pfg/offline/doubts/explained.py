"""Why a mention of a scene thing that ends in no goal was not dropped: it is a place or
a landmark, a called-off or negated act, an excluded item, a condition or chatter (a chatter cue of
:mod:`.mention_cues`: "we used to have ...").

A mention none of these explain is an *unexplained mention* (:mod:`.unexplained`): the
reading may have dropped a requested end state.
"""

from __future__ import annotations

from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.context import type_props as _props
from emboteam.pfg.offline.doubts.mention_words import REACH as _REACH
from emboteam.pfg.offline.doubts.mention_words import after_preposition, answers, chatter
from emboteam.pfg.offline.doubts.rule_words import load_rule_words
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.roles import in_role

_W = word_tables("explained")     # data/words.json
#: words that put what follows out of the request: negation, exclusion, calling off
EXCLUDERS = _W.set("excluders")
#: words that make the rest of their clause a condition or a circumstance
CONDITIONS = _W.set("conditions")
#: words that start a self-correction ("in the fridge, no, on the counter"): ``rule_words.json``
CORRECTIONS = frozenset(load_rule_words().correction.cues)
#: words around a place that make it the scene of a chore, not a thing to act on ("tidy
#: the counter: ...", "the floor is covered in stuff")
CHORE_WORDS = _W.set("chore_words")
#: words of result that start a main clause, not a condition ("So the phone and the card
#: go up on a shelf")
RESULTS = _W.set("results")
#: words after "no" that make it no self-correction ("no longer lying about", "no more")
NOT_CORRECTING = _W.set("not_correcting")
#: the explanation of a mention the person negated or excluded
NEGATED = "negated or excluded"
#: the explanation of a mention that is a place or a landmark ("to the box", "next to the pot")
LANDMARK = "a place or landmark"
#: the explanation of a mention a chatter cue frames ("we used to have ...": :mod:`.mention_cues`)
CHATTER = "chatter"


def explanation(ctx: DoubtContext, k: int, types: tuple[str, ...], goals: bool = True) -> str | None:
    """Why the mention at ``k`` needs no goal of its own, or None when nothing explains
    it. A mention whose thing is in a goal is explained by that goal (unless ``goals`` is
    false: then only the words explain it)."""
    # asked of each mention by several rules: answered once per context (it is frozen)
    memo = answers(ctx)
    key = ("explanation", k, types, goals)
    if key not in memo:
        memo[key] = _explanation(ctx, k, types, goals)
    return memo[key]      # type: ignore[return-value]


def _explanation(ctx: DoubtContext, k: int, types: tuple[str, ...], goals: bool) -> str | None:
    item = ctx.items[k]
    if goals and set(types) & ctx.goal_types():
        return "in a goal"
    if goals and item.noun is not None and item.noun.concept.kind in ("lights", "lamps") and any(
            ref_types(c.subject) & {"LightSwitch", "DeskLamp", "FloorLamp"} for c in ctx.goals):
        return "in a goal"
    start, _ = ctx.clause_bounds(k)
    before = ctx.items[max(start, k - _REACH):k]
    if after_preposition(ctx, k, start):
        return LANDMARK
    if in_role(ctx.items, k):
        return "a team member's role"
    if any(i.text in CHORE_WORDS for i in ctx.items[max(start, k - _REACH):k + 1 + _REACH]) and \
            ctx.scene.of_type(types[0]) and "receptacle" in _props(types[0]):
        return "the place of a chore"
    if any(i.neg or i.text in EXCLUDERS for i in before):
        return NEGATED
    if any((i.text in CONDITIONS or i.sub is not None) and i.text not in RESULTS for i in ctx.items[start:k]):
        return "a condition"
    after = ctx.items[k + 1:k + 2 + 2 * _REACH]
    if any(i.text in CORRECTIONS and not (i.text == "no" and j + 1 < len(after) and after[j + 1].text in NOT_CORRECTING)
           for j, i in enumerate(after[:-1])):
        return "called off by a self-correction"
    if any(m.role in ("place", "dest") and set(types) & m.ref.types for m in ctx.history):
        return LANDMARK
    if chatter(ctx, k):
        return CHATTER
    return None
