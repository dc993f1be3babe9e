"""Household words of other languages said inside English ("the TV stays apagada", "und der
Fernseher stays aus", "la cortina de la ducha, ábrela"), read as their English words.

People who speak another language at home mix its words for things, states and simple
acts into English. ``data/foreign.json`` says what each is in English (general knowledge
of Spanish, German, French and Italian, not of any instruction): ``words`` are no English
words and are always read in English; ``joining`` words (articles, prepositions) are often
also English ("die", "la") or too short to trust, so they are read in English only before
a word read in English ("die Zeitung", "de la ducha"). Accents are folded first
(:func:`.text.fold_accents`), so the table is written without them.
"""

from __future__ import annotations

from functools import cache

from emboteam.pfg.offline.knowledge import Strict, load

#: the longest phrase of the table, in words ("s il vous plait")
_LONGEST = 4


class ForeignFile(Strict):
    """``data/foreign.json``."""

    about: str = ""
    words: dict[str, str]
    joining: dict[str, str]


@cache
def _data() -> ForeignFile:
    return load("foreign.json", ForeignFile)


@cache
def _firsts() -> frozenset[str]:
    """The first words of the table's words: most instructions have none."""
    return frozenset(k.split()[0] for k in _data().words)


def _at(words: list[str], k: int, table: dict[str, str]) -> tuple[str, int] | None:
    """The longest phrase of ``table`` starting at ``words[k]``: its English and length."""
    for n in range(min(_LONGEST, len(words) - k), 0, -1):
        key = " ".join(w.lower() for w in words[k:k + n])
        if key in table:
            return table[key], n
    return None


def translate(words: list[str]) -> list[str]:
    """The words with the table's words in English (same count: a phrase's first word
    takes its English, the rest become ""); the text's other words as they were."""
    data = _data()
    firsts = _firsts()
    if not any(w.lower() in firsts for w in words):
        return words
    out = list(words)
    english = [False] * len(words)
    k = 0
    while k < len(words):
        found = _at(words, k, data.words)
        if found is None:
            k += 1
            continue
        out[k], n = found
        for j in range(k + 1, k + n):
            out[j] = ""
        english[k:k + n] = [True] * n
        k += n
    # joining words: right to left, so that "de la ducha" joins through "la"
    for k in range(len(words) - 2, -1, -1):
        if not english[k] and english[k + 1] and words[k].lower() in data.joining:
            out[k], english[k] = data.joining[words[k].lower()], True
    return out


def warm_foreign() -> None:
    """Load the table and its search ahead of the first instruction."""
    _firsts()
