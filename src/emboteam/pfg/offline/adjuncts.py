"""Time adjuncts: "tonight", "before lunch", "at some point this afternoon", "by tomorrow
morning", "all day" say *when*, never *what*: the robots act now, and the goal is the
same. They are taken out of the word sequence before clauses are found, so that a time
word is never read as an object ("put the apple in the fridge tonight") and a
subordinator before a meal ("before lunch and the tomato in the microwave") does not
open a clause that swallows the next conjunct.

A time adjunct is a run of time words (:data:`TIME_POINTS`, a closed word class, not a
list of sentences) with the words that introduce and modify it: a preposition or
subordinator ("before", "by", "at", "until"), determiners and time modifiers ("this",
"next", "some", "every"). Durations ("for two minutes") are kept: they say how long an
appliance runs.
"""

from __future__ import annotations

from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.patterns import pattern_tables
from emboteam.pfg.offline.tagger import Item

_W = word_tables("adjuncts")
#: nouns and adverbs that name a point or stretch of time (not a duration unit)
TIME_POINTS = _W.set("time_points")
#: "... on any more"; a word that introduces a time adjunct ("on" only before a day:
#: "leave the light on all night" keeps its particle)
_NO_LONGER, _INTRODUCED = (pattern_tables("adjuncts").pattern(name) for name in ("no_longer", "introduced"))
#: words that modify a time noun ("this afternoon", "next week", "all day", "at some point")
_MODIFIERS = _W.set("modifiers")
#: "at some point", "at any time": a vague point in time
_VAGUE_POINTS = _W.set("vague_points")


def _time_run(items: list[Item], k: int) -> int:
    """The index after the time words (with their modifiers) starting at ``k``; ``k`` if
    none start there."""
    m = k
    while m < len(items) and items[m].text in _MODIFIERS and items[m].noun is None:
        m += 1
    end = m
    while end < len(items) and items[end].noun is None and (
            items[end].text in TIME_POINTS
            or (items[end].text in _VAGUE_POINTS and end > k
                and items[end - 1].text in ("some", "any", "this", "next", "every"))   # "this time"
            or (items[end].text == "end" and end > k and items[end - 1].text == "the"      # "at the end"
                and not (end + 1 < len(items) and items[end + 1].text == "of"))):
        end += 1
    return end if end > m else k


def _ends_sentence(items: list[Item], k: int, end: int) -> bool:
    """"open a drawer and shut it afterwards": a lone sequence word that ends its sentence
    orders its clause (:func:`.clauses.segment`), it says no time."""
    if end != k + 1 or items[k].seq is None:
        return False
    rest = next((j for j in range(end, len(items)) if items[j].punct in (".", "!", "?", ";")), len(items))
    return not any(i.is_content() for i in items[end:rest])


def drop_time_adjuncts(items: list[Item]) -> list[Item]:
    """The items without their time adjuncts (see the module docstring)."""
    out: list[Item] = []
    k = 0
    while k < len(items):
        no_longer = _NO_LONGER.end(items, k)
        if no_longer is not None:
            k = no_longer
            continue
        start = k + 1 if _INTRODUCED.at(items, k) else k
        end = _time_run(items, start)
        if end > start and (end >= len(items) or items[end].text != "of") and not _ends_sentence(items, k, end):
            k = end        # "the morning of ..." aside: the whole adjunct goes
            continue
        out.append(items[k])
        k += 1
    return out
