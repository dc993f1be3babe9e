"""Word forms: plural nouns to singular, inflected verbs to their lemma, and spelling
correction against the lexicon.

Written by hand on purpose: the vocabulary is closed (the lexicon), so a few suffix rules
checked against it are exact, where a general lemmatizer (spaCy, NLTK) would add a large
dependency and a model download for no gain. The edit distance is the 20-line
Damerau-Levenshtein recurrence; a fuzzy-matching package would be a new dependency for it.
"""

from __future__ import annotations

from collections.abc import Collection
from functools import cache, lru_cache

from emboteam.pfg.offline import lexicon as lx


@lru_cache(maxsize=8192)
def singular_candidates(word: str) -> tuple[str, ...]:
    """Possible singular forms of ``word``, most likely first (the word itself last);
    remembered per word (the tagger asks of every span of words)."""
    out: list[str] = []
    if word.endswith("ies") and len(word) > 4:
        out.append(word[:-3] + "y")
    if word.endswith("ves"):
        out += [word[:-3] + "f", word[:-3] + "fe"]
    if word.endswith("es"):
        out.append(word[:-2])
    if word.endswith("s") and not word.endswith("ss"):
        out.append(word[:-1])
    out.append(word)
    return tuple(out)


def singular(word: str, known: Collection[str]) -> tuple[str, bool]:
    """``(singular, was_plural)`` using the known noun words; unknown words pass through."""
    if word in known:
        return word, False
    for cand in singular_candidates(word)[:-1]:
        if cand in known:
            return cand, True
    return word, False


@cache
def verb_lemma(word: str) -> tuple[str, str] | None:
    """``(lemma, form)`` of an inflected verb of the lexicon, form in base/ing/ed/s;
    ``None`` when the word is no verb we know. Remembered per word (the lexicon is fixed
    at import, and the reader asks of every word several times per instruction)."""
    verbs = lx.VERBS
    if word in lx.IRREGULAR_VERBS:
        lemma = lx.IRREGULAR_VERBS[word]
        return lemma, "base" if lemma == word else "ed"
    if word in verbs:
        return word, "base"
    for suffix, form in (("ing", "ing"), ("ed", "ed"), ("es", "s"), ("s", "s"), ("d", "ed")):
        if not word.endswith(suffix) or len(word) <= len(suffix) + 1:
            continue
        stem = word[: -len(suffix)]
        cands = [stem, stem + "e"]
        if len(stem) > 2 and stem[-1] == stem[-2] and stem[-1] not in "aeiou" \
                and suffix in ("ing", "ed"):
            cands.append(stem[:-1])          # chopping -> chop (not good -> go)
        if stem.endswith("i"):
            cands.append(stem[:-1] + "y")     # fried -> fry
        if form == "ing" and stem.endswith("y"):
            cands.append(stem)                # frying -> fry
        for c in cands:
            if c in verbs or c in lx.IRREGULAR_VERBS.values():
                return c, form
    return None


def edit_distance(a: str, b: str, limit: int = 3) -> int:
    """Damerau-Levenshtein distance (adjacent transpositions count one), capped at
    ``limit + 1`` so far-apart words cost little."""
    if abs(len(a) - len(b)) > limit:
        return limit + 1
    prev2: list[int] = []
    prev = list(range(len(b) + 1))
    for i in range(1, len(a) + 1):
        cur = [i] + [0] * len(b)
        for j in range(1, len(b) + 1):
            cost = 0 if a[i - 1] == b[j - 1] else 1
            cur[j] = min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost)
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                cur[j] = min(cur[j], prev2[j - 2] + 1)
        if min(cur) > limit:
            return limit + 1
        prev2, prev = prev, cur
    return prev[-1]


def distance_within(a: str, b: str, k: int) -> int:
    """:func:`edit_distance` when it is at most ``k``, else ``k + 1``: only the band of
    cells within ``k`` of the diagonal is filled (a cell outside it already costs more than
    ``k``), which makes the many comparisons of a sound-alike search cheap."""
    n, m = len(a), len(b)
    over = k + 1
    if abs(n - m) > k:
        return over
    prev2: list[int] = []
    prev = [j if j <= k else over for j in range(m + 1)]
    for i in range(1, n + 1):
        cur = [over] * (m + 1)
        if i <= k:
            cur[0] = i
        lo, hi = max(1, i - k), min(m, i + k)
        for j in range(lo, hi + 1):
            v = min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1]))
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                v = min(v, prev2[j - 2] + 1)
            cur[j] = min(v, over)
        if min(cur[lo - 1:hi + 1]) > k:
            return over
        prev2, prev = prev, cur
    return prev[m]


def allowed_distance(word: str) -> int:
    """How many edits a typo of this length may have: none below 4 letters (pan/pen/pot
    are different things), one up to 6, two from 7."""
    if len(word) < 4:
        return 0
    return 1 if len(word) < 7 else 2


def _deletes(word: str, k: int) -> set[str]:
    """Every string made by deleting up to ``k`` letters."""
    out = {word}
    frontier = {word}
    for _ in range(k):
        frontier = {w[:i] + w[i + 1:] for w in frontier for i in range(len(w))}
        out |= frontier
    return out


@cache
def _delete_index(nouns_only: bool) -> dict[str, tuple[str, ...]]:
    """Symmetric-delete index (the SymSpell idea): two words within edit distance k share a
    string reachable by at most k deletions from each, so candidates are found by lookup
    instead of comparing the typo with every lexicon word."""
    out: dict[str, set[str]] = {}
    for t in lx.correction_targets(nouns_only):
        for d in _deletes(t, 2):
            out.setdefault(d, set()).add(t)
    return {d: tuple(sorted(ts)) for d, ts in out.items()}


def warm_spelling() -> None:
    """Build the spelling indexes and load the English word list ahead of the first typo."""
    _delete_index(False)
    _delete_index(True)
    is_english_word("the")


#: Zipf frequency (log10 of occurrences per billion words) from which a word is common
#: English: "losing" (4.9), "bake" (3.9) are words, "tomatoe" (1.4), "frigde" (0) typos
_COMMON_ZIPF = 3.0


def is_english_word(word: str) -> bool:
    """Is ``word`` a common English word (so not a typo to correct into a verb or a state)?
    wordfreq's English frequencies, not a hand-written list: "I keep losing my keys" must
    not become "closing"."""
    from wordfreq import zipf_frequency  # its word list loads on first use (~0.3 s)
    return zipf_frequency(word, "en") >= _COMMON_ZIPF


@cache
def correct(word: str, nouns_only: bool = False) -> str | None:
    """The lexicon word a typo most likely stands for, or ``None``.

    Only words unknown to the lexicon and to the list of common English words are
    corrected, only into content words (nouns, verbs, states), and only when one candidate
    is strictly closest (ties are ambiguous: no guess). After a determiner only nouns
    are candidates ("the bred" is bread, not brew).
    """
    if word in lx.vocabulary() or not word.isalpha():
        return None
    for suffix in ("ing", "ed"):
        # an inflected verb the lexicon lacks ("thinking") is no typo of a noun; a typo of
        # a known verb is corrected on its stem ("slcing" -> "slicing")
        if word.endswith(suffix) and len(word) >= len(suffix) + 3:
            stem = correct(word[: -len(suffix)])
            if stem is None and suffix == "ing":
                stem = correct(word[: -len(suffix)] + "e")
            if stem is not None and stem in lx.VERBS:
                return stem + suffix
            # otherwise only a one-letter slip of a word we know ("containg")
            return _closest(word, 1, nouns_only)
    doubled = word + word[-1]
    if len(word) >= 3 and doubled in lx.VERBS and not nouns_only:
        return doubled      # "kil the lights": a doubled last letter typed once
    limit = allowed_distance(word)
    if limit == 0:
        return None
    return _closest(word, limit, nouns_only)


#: function words whose letters people swap ("teh", "adn"): a transposition is read back
_SWAPPED_FUNCTION_WORDS = {"".join(sorted(w)): w for w in ("the", "and", "off", "out", "put", "into", "onto", "then")}


def unswap(word: str) -> str | None:
    """The function word a letter swap stands for ("teh" -> "the"), or ``None``."""
    fix = _SWAPPED_FUNCTION_WORDS.get("".join(sorted(word)))
    return fix if fix is not None and fix != word and sum(a != b for a, b in zip(fix, word, strict=True)) == 2 else None


def _closest(word: str, limit: int, nouns_only: bool) -> str | None:
    """The unique best correction within ``limit`` edits, or ``None``."""
    # rank by distance, then prefer a candidate with the same first letter (people rarely
    # mistype the first letter: "trun" is turn, not run), then a word the typo is the
    # start of (a dropped last letter: "plat" is plate, not plant), then the same length
    ranked: list[tuple[tuple[int, int, int, int], str]] = []
    index = _delete_index(nouns_only)
    nearby = {t for d in _deletes(word, limit) for t in index.get(d, ())}
    for target in sorted(nearby):
        d = edit_distance(word, target, limit)
        if d <= limit:
            # same length (a wrong or swapped letter) before a dropped letter before an
            # extra one: "bred" is bread, not bed
            length = 0 if len(target) == len(word) else 1 if len(target) > len(word) else 2
            key = (d, int(target[0] != word[0]), int(not target.startswith(word)), length)
            ranked.append((key, target))
    if not ranked:
        return None
    ranked.sort()
    if len(ranked) > 1 and ranked[0][0] == ranked[1][0]:
        return None
    return ranked[0][1]
