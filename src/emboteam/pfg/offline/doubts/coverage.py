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
from emboteam.pfg.offline.doubts.explained import explanation
from emboteam.pfg.offline.doubts.wants import asked_predicate
from emboteam.world.goals import Condition


def asked_mentions(ctx: DoubtContext) -> list[tuple[int, tuple[str, ...]]]:
    """(position, types) of the mentions the words ask something of: not a place, not
    negated, excluded, called off or a condition (:func:`.explained.explanation` by the
    words alone)."""
    return [(k, ts) for k, _, ts in ctx.mentions() if explanation(ctx, k, ts, goals=False) is None]


class Coverage:
    """``coverage(goals)``: the mentions the words ask something of whose thing is in a
    goal, plus the words asking a state a goal has (what the words ask is found once per
    instruction)."""

    def __init__(self, ctx: DoubtContext) -> None:
        self.mentions = [frozenset(ts) for _, ts in asked_mentions(ctx)]
        self.asked = [p for i in ctx.items if (p := asked_predicate(i)) is not None]

    def __call__(self, goals: Sequence[Condition]) -> int:
        types: set[str] = set()
        preds = set()
        for c in goals:
            types |= condition_types(c)
            preds.add(c.predicate)
        return sum(1 for ts in self.mentions if types & ts) + sum(1 for p in self.asked if p in preds)
