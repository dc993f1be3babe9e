"""Mentions the tagger could not read: a misheard, split or texted name ("the sync",
"the so far", "the to motto", "hang it on the hold her", "the desk lump").

A run of one or two words, at least one of them unread by the tagger (no noun, verb,
state, preposition ... reading), joined without spaces and rewritten to how it sounds
(``sound_alike.json``), that is within a small edit distance of a noun phrase of a scene
type (also rewritten) is a mention of that type. A single word that is common English
("far", "her") counts alone only when it sounds exactly like the thing ("sync"). The points of doubt
then treat it like any other mention (an unexplained one proposes its goals).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from functools import cache, lru_cache
from pathlib import Path

from pydantic import BaseModel

from emboteam.pfg.offline.knowledge import read
from emboteam.pfg.offline.lexicon import nouns
from emboteam.pfg.offline.morphology import distance_within, is_english_word
from emboteam.pfg.offline.tagger import Item

SOUND_FILE = Path(__file__).with_name("sound_alike.json")


class SoundAlike(BaseModel):
    about: str = ""
    rewrites: list[tuple[str, str]]
    max_join: int = 2
    distance: dict[str, int]


@cache
def load_sound_alike(path: Path = SOUND_FILE) -> SoundAlike:
    """The sound-alike rules file, checked by its schema at load (a malformed entry is a
    :class:`~emboteam.pfg.offline.knowledge.KnowledgeDataError` naming file and entry)."""
    return read(path, SoundAlike)


_NOT_LETTER, _DOUBLED = re.compile(r"[^a-z]"), re.compile(r"(.)\1+")


@lru_cache(maxsize=8192)
def sound(text: str) -> str:
    """The letters of ``text`` as they sound (rewrites applied, doubled letters single);
    remembered: the same words come back in every instruction."""
    out = _NOT_LETTER.sub("", text.lower())
    for a, b in load_sound_alike().rewrites:
        out = out.replace(a, b)
    return _DOUBLED.sub(r"\1", out)


def _limit(n: int) -> int:
    d = load_sound_alike().distance
    return d["below_5"] if n < 5 else d["below_8"] if n < 8 else d["longer"]


@cache
def _phrase_sounds() -> tuple[tuple[str, tuple[str, ...]], ...]:
    """(sound, types) of every noun phrase of the lexicon, in its order: the same for every
    scene, so worked out once rather than once per scene (it was most of a scene's first
    instruction's time)."""
    return tuple((sound(phrase), tuple(dict.fromkeys((*concept.types, *concept.fallback))))
                 for phrase, concept in nouns().items())


def warm_sound_alike() -> None:
    """Load the rules and work out every noun phrase's sound ahead of the first instruction."""
    _phrases_by_type()


@cache
def _phrases_by_type() -> dict[str, tuple[int, ...]]:
    """Type -> the positions in :func:`_phrase_sounds` of the phrases that name it."""
    out: dict[str, list[int]] = {}
    for k, (_, types) in enumerate(_phrase_sounds()):
        for t in types:
            out.setdefault(t, []).append(k)
    return {t: tuple(ks) for t, ks in out.items()}


@cache
def _sounds(scene_types: frozenset[str]) -> dict[str, tuple[tuple[str, tuple[str, ...]], ...]]:
    """(sound, scene types) of every noun phrase naming a type of the scene, by the sound's
    first letter (a misheard name keeps its first sound: the index keeps the reader
    within its time budget)."""
    out: dict[str, list[tuple[str, tuple[str, ...]]]] = {}
    phrases = _phrase_sounds()
    by_type = _phrases_by_type()    # only the phrases naming a type of the scene, in order
    for said, all_types in (phrases[k] for k in sorted({k for t in scene_types for k in by_type.get(t, ())})):
        types = tuple(t for t in all_types if t in scene_types)
        if types and len(said) >= 3:
            out.setdefault(said[0], []).append((said, types))
    return {k: tuple(v) for k, v in out.items()}


def _unread(item: Item) -> bool:
    return not (item.is_content() or item.prep or item.pron or item.det or item.punct or item.conj or item.seq
                or item.sub or item.quant or item.number is not None or item.neg or item.copula)


def heard(items: Sequence[Item], scene_types: frozenset[str]) -> list[tuple[int, tuple[str, ...]]]:
    """(position, scene types) of each run of words that sounds like a scene thing."""
    out: list[tuple[int, tuple[str, ...]]] = []
    taken: set[int] = set()
    for k, item in enumerate(items):
        if not _unread(item) or k in taken:
            continue
        runs = [(k - 1, k + 1), (k, k + 2), (k, k + 1)]    # with the word before, after, alone
        for lo, hi in runs:
            if lo < 0 or hi > len(items) or hi - lo > load_sound_alike().max_join or taken & set(range(lo, hi)):
                continue
            words = [i.text for i in items[lo:hi]]
            if any(items[j].det or items[j].punct for j in range(lo, hi)):
                continue
            # a common English word alone only when it sounds exactly like the thing ("sync")
            exact = hi - lo == 1 and is_english_word(words[0])
            said = sound("".join(words))
            match = _closest(said, scene_types, 0 if exact else None)
            if match is not None:
                out.append((k, match))
                taken |= set(range(lo, hi))
                break
    return out


@lru_cache(maxsize=8192)
def _closest(said: str, scene_types: frozenset[str], limit: int | None = None) -> tuple[str, ...] | None:
    """The scene types of the nearest phrase sound within ``limit`` edits (the length's own
    limit when None); remembered per sound and scene: most of a sound-alike search's time."""
    if len(said) < 3:
        return None
    limit = _limit(len(said)) if limit is None else limit
    if limit == 0:      # the sound itself, the first in order (no distance to work out)
        return next((types for s, types in _sounds(scene_types).get(said[0], ()) if s == said), None)
    best: tuple[int, tuple[str, ...]] | None = None
    for s, types in _sounds(scene_types).get(said[0], ()):
        if abs(len(s) - len(said)) > limit:
            continue
        d = distance_within(said, s, limit)
        if d <= limit and (best is None or d < best[0]):
            best = (d, types)
    return best[1] if best is not None else None
