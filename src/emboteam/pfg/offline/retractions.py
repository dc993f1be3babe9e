"""Undo and redo across statements. An instruction is a sequence of statements (between
sentence breaks; a transcript's "[beep]" is one); one that opens with "undo" ("undo that as
well", "cancel that", "she changed her mind") removes the nearest earlier statement that
still asks for something, what it goes on to say stands; one that opens with "redo" says
the last undone statement again (the one naming what it names: "redo the microwave one").
A cue before a colon ("Undo it: the watch goes back ...") or inside a sentence ("can you
undo that") asks to undo what someone else did: nothing is called back. Done on the tagged
items before the slot rules of :mod:`.corrections`; the words are ``words.json``,
``retractions``."""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.tagger import Item

_W = word_tables("retractions")
_UNDO, _REDO, _TAILS = _W.phrases("undo"), _W.phrases("redo"), _W.phrases("tails")
_OPENERS, _ONES = _W.phrases("openers"), _W.set("ones")
_CHANGED, _SUBJECT = _W.phrases("changed_mind"), _W.set("subject_words")
#: at most this many words of a subject before "changed her mind" ("the quest giver")
_SUBJECT_REACH = 5
_CALL_OFF, _NOT, _THAT, _MEANT = (_W.phrases(n) for n in ("call_off", "not", "that", "meant"))
_PAST, _NARRATORS = _W.set("past"), _W.set("narrators")
_SENTENCE = frozenset(".!?;")


def _phrase(items: Sequence[Item], k: int, phrases: Sequence[tuple[str, ...]]) -> int:
    first = items[k].text if 0 <= k < len(items) else None
    for p in phrases:
        # the first word first: most phrases start with another word
        if not p or ((k < 0 or p[0] == first) and tuple(x.text for x in items[k:k + len(p)]) == p):
            return len(p)
    return 0


def _skip(items: Sequence[Item], j: int, hi: int, phrases: Sequence[tuple[str, ...]]) -> int:
    """Past punctuation and ``phrases``."""
    while j < hi and (items[j].punct is not None or _phrase(items, j, phrases)):
        j += max(_phrase(items, j, phrases), 1)
    return j


def _statements(items: Sequence[Item]) -> list[tuple[int, int]]:
    """[start, end) of each statement; a statement's end includes its break."""
    out, start = [], 0
    for k, x in enumerate(items):
        if x.punct in _SENTENCE:
            out.append((start, k + 1))
            start = k + 1
    if start < len(items):
        out.append((start, len(items)))
    return out


def _asks(items: Sequence[Item]) -> bool:
    return any(x.verb is not None or x.noun is not None or x.state is not None for x in items)


def _narrative(items: Sequence[Item]) -> bool:
    """Whether a statement tells what someone did ("she moved the soap bottle", "it was on
    the toilet"): an undo after it asks to put things back, it calls back no request."""
    first = next((x for x in items if x.verb is not None or x.copula or x.text in _NARRATORS), None)
    return first is not None and (first.text in _PAST or first.text in _NARRATORS
                                  or (first.verb is not None and first.verb.form == "ed"))


def _cue(items: Sequence[Item], lo: int, hi: int) -> tuple[str, int, int] | None:
    """("undo" | "redo", where the cue starts, where what it says ends) when the statement
    [lo, hi) opens with a cue (after openers like "actually,"); None otherwise."""
    k = _skip(items, lo, hi, _OPENERS)
    for kind, phrases in (("undo", _UNDO), ("redo", _REDO)):
        n = _phrase(items, k, phrases)
        if n:
            return kind, k, k + n
    # "UPDATE: the quest giver changed her mind - ...": a change of mind after its subject
    for j in range(k, min(hi, k + _SUBJECT_REACH + 1)):
        n = _phrase(items, j, _CHANGED)
        if n:
            return "undo", k, j + n
        if items[j].verb is not None and items[j].text not in _SUBJECT:
            break        # a request of its own before it
    return None


def _tail_end(items: Sequence[Item], k: int, hi: int) -> int:
    """Past the words that only go with the cue: "as well", "command two", "four"."""
    while k < hi:
        n = _phrase(items, k, _TAILS) or int(items[k].number is not None and items[k].noun is None)
        if not n:
            return k
        k += n
    return k


def _named(items: Sequence[Item], k: int, hi: int) -> tuple[frozenset[str], int]:
    """The things a redo names ("the microwave one") and where that description ends."""
    j = k + int(k < hi and items[k].det)
    names: set[str] = set()
    while j < hi and (noun := items[j].noun) is not None:
        names |= {*noun.concept.types, noun.concept.name}
        j += 1
    if names and j < hi and items[j].text in _ONES:
        return frozenset(names), j + 1
    return frozenset(), k


def _called_off(items: Sequence[Item], k: int, hi: int) -> int:
    """Where what follows a redo goes on when it calls the redo off ("redo the microwave
    one - no wait, not that one, I mean shut the microwave"); ``k`` when it does not."""
    j = _skip(items, k, hi, _CALL_OFF)
    n = _phrase(items, j, _NOT) if j > k else 0
    m = _phrase(items, j + n, _THAT) if n else 0
    if not m:
        return k
    return _skip(items, j + n + m, hi, _MEANT)


def _mentions(items: Sequence[Item], names: frozenset[str]) -> bool:
    return any(x.noun is not None and names & {*x.noun.concept.types, x.noun.concept.name} for x in items)


def retract(items: list[Item]) -> list[Item]:
    """The items with every undone request taken out and every redone one said again."""
    spans = _statements(items)
    if not any(_cue(items, lo, hi) for lo, hi in spans):
        return items
    kept: list[list[Item]] = []      # the statements as they stand, in order
    live: list[bool] = []            # whether each still asks for something
    undone: list[list[Item]] = []
    for lo, hi in spans:
        found = _cue(items, lo, hi)
        kind, at, end = found or ("", hi, hi)
        # "Undo the tidying: ...": an act of someone else's undone, no request called back
        done = kind == "undo" and end == at + 1 and end < hi and items[end].det and items[end].pron is None
        end = _tail_end(items, end, hi)
        names, end = _named(items, end, hi) if kind == "redo" else (frozenset(), end)
        back = next((i for i in range(len(kept) - 1, -1, -1) if live[i]), None)
        if found is None or done or (end < hi and items[end].punct == ":") or (   # "Undo it: ..." announces
                kind == "undo" and (back is None or _narrative(kept[back]))):
            kept.append(list(items[lo:hi]))
            live.append(_asks(items[lo:hi]))
            continue
        said: list[Item] = []
        if kind == "undo":
            if back is not None:
                undone.append(kept[back])
                kept[back], live[back] = [], False
        elif _called_off(items, end, hi) > end:
            end = _called_off(items, end, hi)
        elif undone:
            pick = next((i for i in range(len(undone) - 1, -1, -1)
                         if not names or _mentions(undone[i], names)), len(undone) - 1)
            said = [x for x in undone.pop(pick) if x.punct not in _SENTENCE]
        rest = list(items[end:hi])
        kept.append([*items[lo:at], *said, *rest])
        live.append(_asks(said) or _asks(rest))
    return [x for statement in kept for x in statement]
