"""Point of doubt: the scope of a negation, an exclusion or a self-correction.

- a goal on a thing named right after "not", "except", "without", "leave" ... may be the
  thing the person excluded: drop it;
- after a self-correction ("in the fridge, no, on the counter", "actually", "I mean"),
  a place on either side may be the one meant: swap the place of a placement between them,
  and a state the reader gave the corrected place ("open(Fridge)") may be a misread
  placement there.
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.explained import CORRECTIONS, EXCLUDERS
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.goals import Condition, Predicate


def exclusion_doubts(ctx: DoubtContext) -> list[Doubt]:
    out = []
    for k, item, types in ctx.mentions():
        before = ctx.items[max(0, k - 3):k]
        if not any(i.neg or i.text in EXCLUDERS for i in before):
            continue
        hit = tuple(c for c in ctx.goals if ref_types(c.subject) & set(types))
        if hit and len(hit) < len(ctx.goals):
            out.append(Doubt("exclusion", item.text, (
                Choice(AS_READ, f"{item.text!r} is asked for"),
                Choice("drop_excluded", f"{item.text!r} is left out", drop=hit))))
    return out


def _places(ctx: DoubtContext, lo: int, hi: int) -> list[str]:
    return [types[0] for k, _, types in ctx.mentions() if lo <= k < hi]


def correction_doubts(ctx: DoubtContext) -> list[Doubt]:
    cue = next((k for k, i in enumerate(ctx.items) if i.text in CORRECTIONS and k > 0), None)
    if cue is None:
        return []
    before, after = _places(ctx, max(0, cue - 6), cue), _places(ctx, cue + 1, cue + 7)
    out = []
    for c in ctx.goals:
        if c.predicate is Predicate.inside and c.receptacle is not None:
            where = c.receptacle.types[0] if c.receptacle.types else ""
            others = [p for p in (after if where in before else before if where in after else [])
                      if p != where and p not in ref_types(c.subject)]
            for other in others[:2]:
                alt = placed(c.subject.types[0], other) if c.subject.types else None
                if alt is not None:
                    label = "take_correction" if where in before else "keep_first"
                    out.append(Doubt("correction", ctx.items[cue].text, (
                        Choice(AS_READ, clause(c)), Choice(label, clause(alt), drop=(c,), add=(alt,)))))
        elif c.predicate is not Predicate.inside and c.subject.types and c.subject.types[0] in after:
            moved = [g for g in ctx.goals if g.predicate is Predicate.inside and g.subject.types]
            if moved:
                g = moved[-1]
                alt = placed(g.subject.types[0], c.subject.types[0])
                out.append(Doubt("correction", ctx.items[cue].text, (
                    Choice(AS_READ, clause(c)),
                    Choice("state_was_place", f"{type_name(c.subject.types[0])} is the corrected place: "
                           f"{clause(alt)}", drop=(c, g), add=(alt,)))))
    return out


def doubts(ctx: DoubtContext) -> list[Doubt]:
    return exclusion_doubts(ctx) + correction_doubts(ctx)


__all__ = ["Condition", "doubts"]
