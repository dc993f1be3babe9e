"""Two opposed requests where the words say which one stands: the later one.

"Turn the floor lamp off - sorry, I mean leave it on", "if the coffee machine is off, it
ought to be on", "hang it on the holder ... so put it in the toilet instead": the reader
finds a state and its opposite asked at once (:class:`.ContradictoryInstruction`), but a
self-correction or a condition between them says the later request settles it. Then the
earlier request's opposed condition is dropped (the reading is marked unsure with a note)
instead of raising; with no such cue ("open and close the fridge") the error stands. The
cues are data (``rule_words.json``, ``contradiction``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from emboteam.pfg.offline.clauses import Clause
from emboteam.pfg.offline.consistency import ContradictoryInstruction
from emboteam.pfg.offline.doubts.rule_words import load_rule_words
from emboteam.pfg.offline.semantics import Draft
from emboteam.pfg.offline.tagger import Item

#: at most this many contradictions are settled in one instruction (then the error stands)
_MOST = 3


def _clause_of(drafts: dict[int, list[Draft]], draft: Draft) -> int | None:
    return next((ci for ci, ds in drafts.items() if any(d is draft for d in ds)), None)


def _cued(clauses: Sequence[Clause], ci: int, cj: int, said: Sequence[Item], cues: set[str]) -> bool:
    """Whether a cue stands in the two clauses or between them, or is their link ("if"),
    or (self-corrections are taken out of the clauses) was said in the instruction."""
    return any(i.text in cues for c in clauses[ci:cj + 1] for i in c.items) or \
        any(c.link in cues for c in clauses[ci:cj + 1]) or any(i.text in cues for i in said)


def settle(clauses: Sequence[Clause], drafts: dict[int, list[Draft]],
           check: Callable[[Sequence[Clause], dict[int, list[Draft]]], None],
           said: Sequence[Item] = ()) -> list[tuple[str, str]]:
    """Run ``check`` (the reader's consistency check); each contradiction a cue settles
    drops the earlier request's opposed condition. Returns (span, why) notes; raises the
    contradiction no cue settles. ``said``: the instruction's words as said."""
    cues = set(load_rule_words().contradiction.cues)
    notes: list[tuple[str, str]] = []
    for _ in range(_MOST + 1):
        try:
            check(clauses, drafts)
            return notes
        except ContradictoryInstruction as exc:
            first, second, a = exc.first, exc.second, exc.a
            ci, cj = _clause_of(drafts, first), _clause_of(drafts, second)
            if ci is None or cj is None or len(notes) >= _MOST or not _cued(clauses, ci, cj, said, cues):
                raise
            first.conditions.remove(a)
            if not first.conditions:
                drafts[ci] = [d for d in drafts[ci] if d is not first]
                if not drafts[ci]:
                    del drafts[ci]
            notes.append((first.description, f"a later request settles it ({second.description!r}): "
                                              "the earlier one is dropped"))
    return notes
