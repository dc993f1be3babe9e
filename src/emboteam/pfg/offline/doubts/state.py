"""Point of doubt: which state a verb, participle or idiom asks for ("warm the bread":
hot or cooked; "do the dishes": clean or in the sink; "open the laptop": open or on).

The confusable pairs and their priors are data (``priors.json``, ``state_swaps``); a swap
the object cannot take is left to the candidate check.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.sentences import clause
from emboteam.world.goals import Condition, ObjectRef, Predicate

KIND = "state"


def _alternative(c: Condition, target: str) -> Condition:
    """``target`` is a predicate name, or ``inside:Type`` (the place that gives the state)."""
    if target.startswith("inside:"):
        return Condition(predicate=Predicate.inside, subject=c.subject, count=c.count,
                         receptacle=ObjectRef(types=(target.split(":", 1)[1],)))
    pred = Predicate(target)
    return Condition(predicate=pred, subject=c.subject, count=c.count,
                     liquid="water" if pred is Predicate.filled else None)


def doubts(ctx: DoubtContext, swaps: Mapping[str, Sequence[str]]) -> list[Doubt]:
    out = []
    for c in ctx.goals:
        key = c.predicate.value if c.predicate is not Predicate.inside else f"inside:{c.receptacle}"
        targets = swaps.get(key, ())
        if not targets:
            continue
        choices = [Choice(AS_READ, clause(c))]
        for target in targets:
            alt = _alternative(c, target)
            choices.append(Choice(f"{key}->{target}", clause(alt), drop=(c,), add=(alt,)))
        out.append(Doubt(KIND, str(c), tuple(choices)))
    return out
