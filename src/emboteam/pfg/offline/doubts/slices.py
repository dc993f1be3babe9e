"""Point of doubt: the whole object or its slices ("put the bread in the toaster", "the
apple on the plate, cut up": the apple or the apple's slices).

Alternatives: the same condition on the pieces instead of the whole, or on the whole
instead of the pieces.
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.sentences import clause
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import ObjectRef, Predicate

KIND = "slices"

#: the predicates whose object can be a whole or its pieces (a slice's other states
#: already count for its whole)
_EITHER = frozenset({Predicate.inside, Predicate.held})


def _other_form(type_: str) -> str | None:
    """The pieces of a whole, or the whole of a piece (an egg's "piece" is a cracked egg:
    no slice, not asked for this way)."""
    if type_.startswith("Egg"):
        return None
    cat = load_catalogue()
    product = cat.slice_product(type_)
    if product is not None:
        return product[0]
    return cat.source_type(type_)


def doubts(ctx: DoubtContext) -> list[Doubt]:
    out = []
    for c in ctx.goals:
        if c.predicate not in _EITHER or c.subject.id is not None or len(c.subject.types) != 1:
            continue
        other = _other_form(c.subject.types[0])
        if other is None:
            continue
        alt = c.model_copy(update={"subject": ObjectRef(types=(other,))})
        label = "to_slices" if other.endswith("Sliced") else "to_whole"
        out.append(Doubt(KIND, str(c), (Choice(AS_READ, clause(c)),
                                        Choice(label, clause(alt), drop=(c,), add=(alt,)))))
    return out
