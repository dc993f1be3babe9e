"""Contradictions: an instruction that asks, in one breath, for a state and its opposite
of one object ("open and close the fridge", "turn the TV on and off").

Only acts of one step (coordinated by "and", not sequenced by "then", "after that",
"first ... finally") can contradict each other: "turn off the light, then turn it back
on" and "open the fridge, then take out the apple, then close it" are sequences whose end
state is the last one. A means to an end (the running microwave of "cook the potato in
the microwave") is no request, and an act between the two ("open the fridge, take out
the apple and close it") gives the first state a purpose.
Otherwise neither end state can be the one meant, and the parser names both readings
instead of silently keeping the last.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

from emboteam.pfg.offline.clauses import Clause
from emboteam.pfg.offline.decompose import refs_overlap, steps
from emboteam.pfg.offline.errors import OfflineParseError
from emboteam.pfg.offline.semantics import Draft
from emboteam.world.goals import Condition, ObjectRef, Predicate

P = Predicate
#: state predicates that exclude each other (moves are not here: an object may be carried
#: from one place to another on purpose)
_EXCLUSIVE = frozenset({
    frozenset({P.switched_on, P.switched_off}), frozenset({P.open, P.closed}),
    frozenset({P.clean, P.dirty}),
})


class ContradictoryInstruction(OfflineParseError):
    """The instruction asks for a state and its opposite of the same object; ``readings``
    are the two conflicting requests, in the order written."""

    def __init__(self, first: Draft, second: Draft, a: Condition, b: Condition) -> None:
        self.readings = (first.description, second.description)
        self.first, self.second, self.a, self.b = first, second, a, b
        super().__init__(
            f"the instruction asks both to {first.description!r} ({a}) and to "
            f"{second.description!r} ({b}) at once: say which end state you want",
            phrase=f"{first.description} / {second.description}")


def opposed(a: Condition, b: Condition) -> bool:
    """Whether two conditions ask opposite states of one object (they cannot both hold at the end)."""
    return frozenset({a.predicate, b.predicate}) in _EXCLUSIVE and refs_overlap(a.subject, b.subject)


def check_consistent(clauses: Sequence[Clause], drafts: dict[int, list[Draft]]) -> None:
    """Raise :class:`ContradictoryInstruction` for the first two requests of one step and
    one sentence, next to each other, that ask for opposite states of one object (an act between them,
    "open the fridge, take out the apple and close it", gives the first state a purpose)."""
    for group in steps(clauses):
        step = [(clauses[ci].sentence, d) for ci in sorted(group) for d in drafts.get(ci, [])
                if not d.intermediate]
        for (s1, first), (s2, second) in itertools.pairwise(step):
            if s1 != s2:
                continue       # "the lamp is off. Turn it on.": a new sentence, a new request
            for a, b in itertools.product(first.conditions, second.conditions):
                if opposed(a, b):
                    raise ContradictoryInstruction(first, second, a, b)


def check_placements(clauses: Sequence[Clause],
                     superseded: Sequence[tuple[int, Draft, int, Draft]]) -> list[tuple[str, str]]:
    """One object placed in two places (draft_passes.drop_superseded_placements kept the
    later one): an error naming both when they are asked at once ("put the apple in the
    fridge and put the apple in the sink"), else the later one wins and this returns a
    note (span, reason) saying so ("put it in the sink, then in the fridge")."""
    order = {ci: k for k, group in enumerate(steps(clauses)) for ci in group}
    notes = []
    for ci, first, cj, second in superseded:
        if ci == cj or not (_asks_to_place(clauses[ci]) and _asks_to_place(clauses[cj])):
            # one clause's list read twice ("pillow and paper up - pillow on the sofa"), or
            # where the object is now ("the candle fell in the bin, put it on the counter",
            # "the wine bottle on the table - can it go in the fridge?"): a reading, no request
            continue
        if order.get(ci) == order.get(cj) and clauses[ci].sentence == clauses[cj].sentence:
            a = next(c for c in first.conditions if c.predicate is P.inside)
            b = next(c for c in second.conditions if c.predicate is P.inside)
            raise ContradictoryInstruction(first, second, a, b)
        notes.append((first.description, f"a later step places it elsewhere ({second.description!r}): "
                                         "the later place is kept"))
    return notes


#: verbs that open a request to place something: only two such requests can contradict
#: (a small list on purpose: what else reads as a placement is mostly where a thing is now)
_PLACING = frozenset({"put", "place", "set", "move", "leave", "stick", "pop", "stand", "lay", "hang", "store"})
_OPENERS = frozenset({"and", "then", "also", "please", "now", "so", "but"})


def _asks_to_place(clause: Clause) -> bool:
    """Does the clause open with a placing verb ("put the apple in the sink")?"""
    words = [w for w in clause.text.lower().split() if w.isalpha()]
    while words and words[0] in _OPENERS:
        words.pop(0)
    return bool(words) and words[0] in _PLACING


def narrow_contrasts(drafts: dict[int, list[Draft]]) -> None:
    """"Switch on the tall lamp and turn off the little one on the desk": when one of two
    opposed requests names an instance and the other a choice of kinds that includes it, the
    choice is the other kinds, not a contradiction."""
    all_drafts = [d for ds in drafts.values() for d in ds]
    for a_draft, b_draft in itertools.permutations(all_drafts, 2):
        for k, b in enumerate(b_draft.conditions):
            for a in a_draft.conditions:
                if not opposed(a, b) or a.subject.id is None or b.subject.id is not None:
                    continue
                kind = a.subject.id.split("_")[0]
                rest = tuple(t for t in b.subject.types if t != kind)
                if rest and len(rest) < len(b.subject.types):
                    b_draft.conditions[k] = b.model_copy(update={"subject": ObjectRef(types=rest)})


def narrow_choices(drafts: dict[int, list[Draft]]) -> None:
    """"Switch off the reading lamp and the floor light": a choice of kinds (a reading lamp
    is a desk or a floor lamp) next to a request of the same kind about one of them named
    alone is the other kinds (else one floor lamp would do for both)."""
    all_drafts = [d for ds in drafts.values() for d in ds]
    for a_draft, b_draft in itertools.permutations(all_drafts, 2):
        for k, b in enumerate(b_draft.conditions):
            for a in a_draft.conditions:
                if a.predicate is not b.predicate or a.receptacle != b.receptacle or a.subject.id is not None \
                        or b.subject.id is not None or len(a.subject.types) != 1 or len(b.subject.types) < 2 \
                        or b.count != 1:     # "both lamps are on: turn off the desk lamp and ..." stays
                    continue
                rest = tuple(t for t in b.subject.types if t not in a.subject.types)
                if rest and len(rest) < len(b.subject.types):
                    b_draft.conditions[k] = b.model_copy(update={"subject": ObjectRef(types=rest)})
