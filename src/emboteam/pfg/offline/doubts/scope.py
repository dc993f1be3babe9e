"""Point of doubt: the scope of a negation or an exclusion.

A goal on a thing named right after "not", "except", "without", "leave" ... may be the
thing the person excluded: drop it. (Self-corrections are :mod:`..corrections`: one
mechanism reads their slot and offers the other readings.)
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.explained import EXCLUDERS


def doubts(ctx: DoubtContext) -> list[Doubt]:
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
