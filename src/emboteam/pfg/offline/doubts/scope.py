"""Points of doubt of scope: what a negation, an exclusion or an undo reaches.

``exclusion``: a goal on a thing named right after "not", "except", "without", "leave" ...
may be the thing the person excluded: drop it. (Self-corrections are
:mod:`..corrections`: one mechanism reads their slot and offers the other readings.)

``undo``: "whoever moved my lettuce ... put it back", "the pillow went from the sofa to the
armchair - put it all back the way it was": where an undo is asked, a thing the reader
placed where it was moved *to* may go back to where it was moved *from* or lived (the
place after a source word in its own words: "from", "it lived on", "it was on"). The
words are data (``rule_words.json``, ``undo``); the reading as read stays a candidate.
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types, type_props
from emboteam.pfg.offline.doubts.destination import window
from emboteam.pfg.offline.doubts.explained import EXCLUDERS
from emboteam.pfg.offline.doubts.rule_words import find, load_rule_words
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.sentences import clause
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Condition, Predicate

UNDO = "undo"


def doubts(ctx: DoubtContext) -> list[Doubt]:
    return [*_exclusions(ctx), *_one_excepted(ctx), *_undone(ctx)]


def _exclusions(ctx: DoubtContext) -> list[Doubt]:
    out = []
    for k, item, types in ctx.mentions():
        before = ctx.items[max(0, k - 3):k]
        if not any(i.neg or i.text in EXCLUDERS for i in before):
            continue
        hit = tuple(c for c in ctx.goals if ref_types(c.subject) & set(types))
        if hit and len(hit) < len(ctx.goals):
            out.append(Doubt("exclusion", item.text, (
                Choice(AS_READ, f"{item.text!r} is asked for"),
                Choice("drop_quantified" if _quantified(ctx, k) else "drop_excluded",
                       f"{item.text!r} is left out", drop=hit))))
    return out


def _quantified(ctx: DoubtContext, k: int) -> bool:
    """Whether an excluder before the thing at ``k`` follows a quantifier of its clause
    ("every lamp but the little desk one", "all but the candle"): an exception to a
    whole, not a thing asked for after a contrast ("..., but the mug goes in the sink")."""
    at = next((j for j in range(k - 1, max(0, k - 4) - 1, -1) if ctx.items[j].text in EXCLUDERS), None)
    start = ctx.clause_bounds(at)[0] if at is not None else k
    return at is not None and any(i.quant is not None or i.text in load_rule_words().contents.quantifiers
                                  for i in ctx.items[max(start, at - 6):at])


def _one_excepted(ctx: DoubtContext) -> list[Doubt]:
    """"every lamp but the little desk one": "one" after an excluder stands for the
    quantified whole's noun, and the words before it say which of the whole's types is
    left out (a word of its type's name: the desk lamp)."""
    out = []
    for m, item, types in ctx.mentions():
        if len(types) < 2:
            continue
        near = ctx.items[m + 1:m + 6]
        e = m + 1 + next((n for n, i in enumerate(near) if i.text in EXCLUDERS or i.punct), len(near))
        if e >= len(ctx.items) or ctx.items[e].text not in EXCLUDERS or not _quantified(ctx, e + 1):
            continue
        pro_forms = load_rule_words().contents.pro_forms
        one = next((j for j in range(e + 1, min(len(ctx.items), e + 5)) if ctx.items[j].text in pro_forms), None)
        if one is None:
            continue
        said = {i.text for i in ctx.items[e + 1:one] if len(i.text) > 2}
        left = [t for t in types if any(w in t.lower() for w in said)]
        hit = tuple(c for c in ctx.goals if left and ref_types(c.subject) == {left[0]})
        if len(left) == 1 and hit and len(hit) < len(ctx.goals):
            out.append(Doubt("exclusion", " ".join(i.text for i in ctx.items[e:one + 1]), (
                Choice(AS_READ, f"{item.text!r} all asked for"),
                Choice("drop_quantified", f"the {left[0]} is left out", drop=hit))))
    return out


def _source(ctx: DoubtContext, k: int, thing: str, now: tuple[str, ...]) -> str | None:
    """The place the thing named at ``k`` came from or lived in, by its own words (a
    source word, then the place within ``lead`` words), when it is not where it goes now."""
    words, cat = load_rule_words().undo, load_catalogue()
    lo, hi = window(ctx, k, thing)
    for _, e in find(ctx.items, lo, hi, words.sources):
        for m in range(e, min(hi, e + words.lead)):
            types = ctx.named_types(ctx.items[m], verbs_too=ctx.items[m - 1].det)
            if types and types[0] != thing and "receptacle" in type_props(types[0]):
                ok = cat.can_place(thing, types[0]) and types[0] not in now
                return types[0] if ok else None
    return None


def _undone(ctx: DoubtContext) -> list[Doubt]:
    """``undo``: each placed thing's way back (module docs)."""
    if not find(ctx.items, 0, len(ctx.items), load_rule_words().undo.cues):
        return []
    out = []
    for c in ctx.goals:
        types = ref_types(c.subject)
        if c.predicate is not Predicate.inside or c.receptacle is None or len(types) != 1:
            continue
        thing = next(iter(types))
        if (k := ctx.position_of(c)) is None or (home := _source(ctx, k, thing, c.receptacle.types)) is None:
            continue
        back: Condition = placed(thing, home)
        out.append(Doubt(UNDO, str(c), (Choice(AS_READ, clause(c)),
                                         Choice("back_to_source", clause(back), drop=(c,), add=(back,)))))
    return out
