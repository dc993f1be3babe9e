"""Coverage: how much of what the instruction names a reading accounts for.

The ranker's one general feature beside the priors: a reading that gives a goal to more
of the instruction's mentions of scene things, and asks the states its verbs and state
words ask for, explains more of the words, and the words were said for a reason. The
count is over positions, so a thing named twice counts twice; its weight against the
priors is ``coverage_weight`` in ``priors.json`` (fitted on development rounds by
``benchmarks/fit_reading_priors.py``).
"""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.pfg.offline.doubts.context import DoubtContext, condition_types
from emboteam.pfg.offline.doubts.wants import asked_predicate
from emboteam.world.goals import Condition


def coverage(ctx: DoubtContext, goals: Sequence[Condition]) -> int:
    """Mentions of scene things whose thing is in a goal, plus words asking a state a goal
    has."""
    types: set[str] = set()
    preds = set()
    for c in goals:
        types |= condition_types(c)
        preds.add(c.predicate)
    named = sum(1 for _, _, ts in ctx.mentions() if types & set(ts))
    asked = sum(1 for i in ctx.items if (p := asked_predicate(i)) is not None and p in preds)
    return named + asked
