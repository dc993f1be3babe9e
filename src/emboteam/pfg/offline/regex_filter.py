"""The words a regular expression cannot match without: a cheap test that skips a rewrite.

Normalisation runs some 250 rewrites (``data/text.json``, ``data/idioms.json``) over every
instruction, and most of them find nothing: a ``re.sub`` that finds nothing still costs
its scan, a ``str in str`` test costs a tenth of it. :func:`needles` reads a pattern's
parse tree (the standard library's own parser) for strings one of which every match
must contain; a rewrite whose needles are all absent from the text cannot change it, so
skipping it changes no reading. Kept by hand: no library derives required literals from
Python's regular expressions.
"""

from __future__ import annotations

import re
from typing import Any

try:    # Python 3.11+
    from re import _parser as _sre  # type: ignore[attr-defined]
except ImportError:     # pragma: no cover - Python 3.10
    import sre_parse as _sre

_C = vars(_sre)     # the parser's opcodes (imported into it from its constants module)
_LITERAL, _SUBPATTERN, _BRANCH, _IN = _C["LITERAL"], _C["SUBPATTERN"], _C["BRANCH"], _C["IN"]
_REPEATS = tuple(_C[n] for n in ("MAX_REPEAT", "MIN_REPEAT", "POSSESSIVE_REPEAT") if n in _C)
_ATOMIC = _C.get("ATOMIC_GROUP")

Needles = frozenset[str] | None


def needles(pattern: re.Pattern[str]) -> Needles:
    """Strings one of which every match of ``pattern`` contains; None when the pattern
    promises none (it may match an empty string, or ignores case)."""
    if pattern.flags & re.IGNORECASE:
        return None
    try:
        return _sequence(list(_sre.parse(pattern.pattern, pattern.flags)))
    except Exception:     # a construct this reader does not know: no promise, no skipping
        return None


def _better(a: Needles, b: Needles) -> Needles:
    """The more selective of two constraints: the longer shortest needle, then fewer."""
    if a is None or b is None:
        return a if b is None else b
    return max(a, b, key=lambda s: (min(map(len, s)), -len(s)))


def _sequence(items: list[tuple[Any, Any]]) -> Needles:
    """Every element of a sequence must match: the best constraint of any of them, a run
    of consecutive literal characters counting as one string."""
    best: Needles = None
    run = ""
    for op, av in items:
        if op is _LITERAL:
            run += chr(av)
            continue
        if run:
            best, run = _better(best, frozenset({run})), ""
        best = _better(best, _element(op, av))
    return _better(best, frozenset({run})) if run else best


def _element(op: Any, av: Any) -> Needles:
    if op is _SUBPATTERN:
        _, add_flags, _, sub = av
        return None if add_flags & re.IGNORECASE else _sequence(list(sub))
    if op is _ATOMIC:
        return _sequence(list(av))
    if op in _REPEATS:
        low, _, sub = av
        return _sequence(list(sub)) if low >= 1 else None
    if op is _BRANCH:
        parts = [_sequence(list(b)) for b in av[1]]
        return None if any(p is None for p in parts) else frozenset().union(*parts)  # type: ignore[arg-type]
    if op is _IN and av and all(o is _LITERAL for o, _ in av):
        return frozenset(chr(c) for _, c in av)
    return None
