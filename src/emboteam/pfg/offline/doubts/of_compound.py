"""Point of doubt: "N of the M" ("the drawer of the desk", "the slice of the apple", in
non-native English "the remote of the TV"): the act may be on N or on M.

When the reading acts on one of the two and the other is a thing of the scene, the
alternative moves the act to the other.
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.wants import with_subject
from emboteam.pfg.sentences import clause

KIND = "of_compound"


def doubts(ctx: DoubtContext) -> list[Doubt]:
    out = []
    mentions = {k: types for k, _, types in ctx.mentions()}
    for k, item in enumerate(ctx.items):
        if item.text != "of" or k == 0 or (k - 1) not in mentions:
            continue
        m = next((j for j in range(k + 1, min(k + 4, len(ctx.items))) if j in mentions), None)
        if m is None:
            continue
        first, second = mentions[k - 1][0], mentions[m][0]
        for c in ctx.goals:
            subject = ref_types(c.subject)
            other = second if first in subject else first if second in subject else None
            if other is None or other in subject:
                continue
            alt = with_subject(c, other)
            span = f"{ctx.items[k - 1].text} of the {ctx.items[m].text}"
            out.append(Doubt(KIND, span, (Choice(AS_READ, clause(c)),
                                          Choice("other_noun", clause(alt), drop=(c,), add=(alt,)))))
    return out
