"""TF-IDF cosine similarity between short texts: which worked examples are closest to an
instruction.

Written by hand (30 lines) rather than with scikit-learn's ``TfidfVectorizer``: the
project does not otherwise depend on scikit-learn, and this is its textbook form
(smoothed idf ``ln((1 + n) / (1 + df)) + 1``, raw term counts, L2-normalised vectors,
words of letters and digits, lowercased), deterministic and fast for a few thousand texts.
"""

from __future__ import annotations

import math
import re
from collections import Counter
from collections.abc import Sequence

_WORD = re.compile(r"[a-z0-9]+")


def words(text: str) -> list[str]:
    return _WORD.findall(text.lower())


class TfIdfIndex:
    """The documents' TF-IDF vectors; :meth:`scores` gives a query's cosine with each."""

    def __init__(self, documents: Sequence[str]) -> None:
        counts = [Counter(words(d)) for d in documents]
        n = len(documents)
        df = Counter(w for c in counts for w in c)
        self.idf = {w: math.log((1 + n) / (1 + f)) + 1.0 for w, f in df.items()}
        self.vectors = [self._vector(c) for c in counts]

    def _vector(self, counts: Counter[str]) -> dict[str, float]:
        vec = {w: c * self.idf.get(w, 0.0) for w, c in counts.items()}
        norm = math.sqrt(sum(v * v for v in vec.values()))
        return {w: v / norm for w, v in vec.items()} if norm else {}

    def scores(self, query: str) -> list[float]:
        """Cosine similarity of ``query`` with every document, in document order (words
        no document has are ignored)."""
        q = self._vector(Counter(words(query)))
        return [sum(v * d.get(w, 0.0) for w, v in q.items()) for d in self.vectors]
