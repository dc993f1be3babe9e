"""Two opposed requests where the words say which one stands: the later one.

"Turn the floor lamp off - sorry, I mean leave it on", "if the coffee machine is off, it
ought to be on", "hang it on the holder ... so put it in the toilet instead": the reader
finds a state and its opposite asked at once (:class:`.ContradictoryInstruction`), but a
self-correction or a condition between them says the later request settles it. Then the
earlier request's opposed condition is dropped (the reading is marked unsure with a note)
instead of raising; with no such cue ("open and close the fridge") the error stands. The
cues are data (``rule_words.json``, ``contradiction``).

A settled contradiction is a choice, not a verdict: its other side ("the earlier request
stands") is a point of doubt of kind ``correction`` (label ``keep_first``, the priors of
a self-correction's other side), so it is a candidate next to the later request (the
reading as read: people correct themselves forward), the reading is unsure, and
``--clarify`` asks between them. The same holds for one object placed in two places in
one breath with a self-correction between ("the tomato too - no wait, not the tomato").

Where no cue stands between them ("open and close the fridge", "put the apple in the
fridge and put the apple in the sink"), the error stays: both requests were said with the
same weight and nothing says the person changed their mind, so taking either would be a
guess the words do not support; the error names both readings (exit 2) and the person
says which one.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.clauses import Clause
from emboteam.pfg.offline.consistency import ContradictoryInstruction, check_placements
from emboteam.pfg.offline.doubts.rule_words import load_rule_words
from emboteam.pfg.offline.semantics import Draft
from emboteam.pfg.offline.tagger import Item

#: at most this many contradictions are settled in one instruction (then the error stands)
_MOST = 3
#: cues of a condition, not a self-correction: "if the lamp is on, it should be off" says
#: what is, then what is wanted; the earlier side was never a request, so it is no candidate
_CONDITIONS = frozenset({"if", "unless", "when", "whenever"})


def _clause_of(drafts: dict[int, list[Draft]], draft: Draft) -> int | None:
    return next((ci for ci, ds in drafts.items() if any(d is draft for d in ds)), None)


def _cued(clauses: Sequence[Clause], ci: int, cj: int, said: Sequence[Item], cues: set[str],
          typed: frozenset[str] = frozenset()) -> bool:
    """Whether a cue stands in the two clauses or between them, or is their link ("if"),
    or (self-corrections are taken out of the clauses) was said in the instruction (its
    tagged words, or its ``typed`` words: the tagger drops a filler like "instead")."""
    return any(i.text in cues for c in clauses[ci:cj + 1] for i in c.items) or \
        any(c.link in cues for c in clauses[ci:cj + 1]) or any(i.text in cues for i in said) or bool(typed & cues)


def both_sides(exc: ContradictoryInstruction) -> Doubt:
    """The two sides of a settled contradiction: the later request stands (as read), or
    the earlier one (its condition instead of the later one's)."""
    first, second = exc.first.description, exc.second.description
    return Doubt("correction", f"{first} / {second}", (
        Choice(AS_READ, f"the later request stands ({second!r})"),
        Choice("keep_first", f"the earlier request stands ({first!r})", drop=(exc.b,), add=(exc.a,))))


def settle_placements(clauses: Sequence[Clause], superseded: Sequence[tuple[int, Draft, int, Draft]],
                      said: Sequence[Item], doubts: list[Doubt], typed: str = "") -> list[tuple[str, str]]:
    """:func:`.check_placements` (notes for a later place said later), except that one
    object placed twice in one breath with a self-correction between keeps the later
    place as read and the earlier as a candidate (appended to ``doubts``); with no cue the
    error stands (module docs: why)."""
    cues = set(load_rule_words().contradiction.cues) - _CONDITIONS
    notes: list[tuple[str, str]] = []
    for entry in superseded:
        try:
            notes += check_placements(clauses, [entry])
        except ContradictoryInstruction as exc:
            ci, cj = sorted((entry[0], entry[2]))
            if not _cued(clauses, ci, cj, said, cues, frozenset(re.findall(r"[a-z]+", typed.lower()))):
                raise
            doubts.append(both_sides(exc))
            notes.append((exc.first.description, f"a self-correction settles it ({exc.second.description!r}): "
                                                 "the later place is kept, the earlier is a candidate"))
    return notes


def settle(clauses: Sequence[Clause], drafts: dict[int, list[Draft]],
           check: Callable[[Sequence[Clause], dict[int, list[Draft]]], None],
           said: Sequence[Item] = (), doubts: list[Doubt] | None = None) -> list[tuple[str, str]]:
    """Run ``check`` (the reader's consistency check); each contradiction a cue settles
    drops the earlier request's opposed condition (its other side goes to ``doubts``).
    Returns (span, why) notes; raises the contradiction no cue settles (module docs:
    why). ``said``: the instruction's words as said."""
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
            if doubts is not None and _cued(clauses, ci, cj, said, cues - _CONDITIONS):
                doubts.append(both_sides(exc))
            if not first.conditions:
                drafts[ci] = [d for d in drafts[ci] if d is not first]
                if not drafts[ci]:
                    del drafts[ci]
            notes.append((first.description, f"a later request settles it ({second.description!r}): "
                                              "the earlier one is dropped"))
    return notes
