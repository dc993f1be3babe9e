"""How many of a thing a mention names, for the doubts that give it a goal of their own.

A number said before the noun ("the two vases", "both loo rolls", "the 3 CDs") is how many
the person means; a bare plural ("bats are kept on my bedside table") means every one the
scene has. The goal a keep or a window proposes carries that count, so "the two cushions
stay on the bed" keeps both cushions there, not one. One helper, shared by
:mod:`.mention_cues` and :mod:`.unexplained`, so that both count the same way.
"""

from __future__ import annotations

from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.world.goals import Condition

#: how far before the noun a number may stand ("both of the loo rolls", "the two big vases")
_REACH = 4


def said_number(ctx: DoubtContext, k: int) -> int | None:
    """The number said before the mention at ``k`` in its noun phrase, or None: only
    determiners, numbers, "of" and adjectives may stand between ("both of the rolls")."""
    for j in range(k - 1, max(-1, k - 1 - _REACH), -1):
        item = ctx.items[j]
        if isinstance(item.number, int) and item.number > 0:
            return item.number
        if item.quant == "both":
            return 2
        if item.det or item.text == "of" or (item.noun is None and item.verb is None and item.prep is None
                                              and item.punct is None and not item.neg and item.pron is None
                                              and item.conj is None and item.state is None):
            continue
        return None
    return None


def said_count(ctx: DoubtContext, k: int, thing: str, plural_all: bool = True) -> int | None:
    """How many the mention names: its number, else (``plural_all``) every one the scene
    has for a plural noun, else None."""
    said = said_number(ctx, k)
    if said is not None:
        return said
    noun = ctx.items[k].noun
    if plural_all and noun is not None and noun.plural:
        return len(list(ctx.state.of_type(thing)))
    return None


def counted(goal: Condition, said: int | None) -> Condition:
    """``goal`` over ``said`` objects of its type (an object named by id stays one)."""
    return goal.model_copy(update={"count": said}) if said is not None and said > 1 and goal.subject.id is None \
        else goal


def implied(goal: Condition, by: list[Condition] | tuple[Condition, ...]) -> bool:
    """Whether a goal of ``by`` already asks ``goal``: the same state or place of the same
    kind of thing, for at least as many ("inside(2 of Pillow, Bed)" asks "inside(Pillow, Bed)")."""
    return any(c.predicate is goal.predicate and ref_types(c.subject) == ref_types(goal.subject)
               and str(c.receptacle) == str(goal.receptacle) and c.liquid == goal.liquid
               and c.count >= goal.count for c in by)
