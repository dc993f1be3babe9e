"""Point of doubt: a counted or plural thing said first, then taken up by a quantified
pronoun that gets the act ("The three vases of the shelves, all of them you put inside one
cupboard", "the pillows - both of them go on the armchair").

The pronoun ("all of them", "both of them", "them all") stands for the plural noun named
last before it, counted by the number before that noun (checked against the scene: no
more than it has) or, without one, every instance; the destination is where the words
after the pronoun send those things, in its sentence (:mod:`.destination`). The alternative places
those things there and replaces the reading's placements there of things its sentence
does not name (a pronoun read as an earlier thing). The words are data
(``rule_words.json``, ``resumed``).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.destination import destination
from emboteam.pfg.offline.doubts.rule_words import find, load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.sentences import clause
from emboteam.world.catalogue import load_catalogue

KIND = "resumed"


def _things(ctx: DoubtContext, start: int, k: int) -> tuple[str, int] | None:
    """The plural thing named last before ``k`` (in its sentence or the one before) and
    how many of it are meant."""
    plural = [(m, item, types) for m, item, types in ctx.mentions()
              if start <= m < k and item.noun is not None and item.noun.plural
              and load_catalogue().type(types[0]).has("pickupable")]
    if not plural:
        return None
    m, _, types = plural[-1]
    have = len(list(ctx.state.of_type(types[0])))
    said = next((i.number for i in ctx.items[max(0, m - 2):m] if i.number is not None), None)
    return types[0], min(said or have, have)


def doubts(ctx: DoubtContext) -> list[Doubt]:
    out = []
    for k, after in find(ctx.items, 0, len(ctx.items), load_rule_words().resumed.pronouns):
        start, end = sentence_bounds(ctx.items, k)
        prev = sentence_bounds(ctx.items, start - 2)[0] if start > 1 else start
        found = _things(ctx, prev, k)
        places = destination(ctx, after - 1, found[0], end) if found is not None else ()
        if found is None or not places:
            continue
        (type_, n), dest = found, places[0]
        goal = placed(type_, dest)
        goal = goal.model_copy(update={"count": n}) if n > 1 else goal
        named = {t for m, _, ts in ctx.mentions() if start <= m < end for t in ts}
        # the things' other placements (their place said before the pronoun is where they
        # are), and placements there of things the sentence does not name
        drop = tuple(c for c in ctx.goals if c.receptacle is not None and c != goal and (
            type_ in ref_types(c.subject) or (dest in ref_types(c.receptacle) and not ref_types(c.subject) & named)))
        if goal not in ctx.goals:
            out.append(Doubt(KIND, ctx.items[k].text, (Choice(AS_READ, "as read"),
                                                         Choice("the_things_before", clause(goal), drop=drop,
                                                                add=(goal,)))))
    return out
