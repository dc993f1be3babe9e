"""Point of doubt: a thing one carries read as held or switched, where the words put it
somewhere ("the salt shaker needs hiding, cupboard": held; "phone charging on the desk":
switched off). Its alternative: the thing placed in a receptacle named as a destination
near it (:func:`.affordances.places_near`), in place of the state.

The priors (``priors.json``, kind ``placed_instead``) are small: the reading as read stays
first; this makes the placing reachable for the ranker and the local model.
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.affordances import load_affordances, places_near
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types, type_props
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.sentences import clause
from emboteam.world.goals import Predicate

KIND = "placed_instead"

#: the states a reader gives a carried thing when the words only move it: holding it,
#: its power (a phone "charging", "off")
_MOVED_AS = frozenset({Predicate.held, Predicate.switched_on, Predicate.switched_off})


def doubts(ctx: DoubtContext) -> list[Doubt]:
    place = load_affordances().place
    placed_types = {t for c in ctx.goals if c.predicate is Predicate.inside for t in ref_types(c.subject)}
    out = []
    for c in ctx.goals:
        types = ref_types(c.subject)
        if c.predicate not in _MOVED_AS or len(types) != 1 or types & placed_types:
            continue
        thing = next(iter(types))
        if place.property not in type_props(thing) or (k := ctx.position_of(c)) is None:
            continue
        alts = [placed(thing, p) for p in places_near(ctx, k, thing, place)[:place.most]]
        if alts:
            out.append(Doubt(KIND, str(c), (Choice(AS_READ, clause(c)), *(
                Choice("to_place", clause(a), drop=(c,), add=(a,)) for a in alts))))
    return out
