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


def needle_groups(pattern: re.Pattern[str]) -> tuple[frozenset[str], ...]:
    """Every constraint a match of ``pattern`` meets, the most selective first: a match
    contains one string of each group. :func:`needles` keeps the one best constraint; a
    rule whose best needle is common ("the") is still skipped when another of its parts
    ("toilet") is absent. Case-blind patterns give lower-case groups, for a lower-cased
    ASCII text (none when a needle is not ASCII); () when the pattern promises nothing."""
    try:
        found = _all(list(_sre.parse(pattern.pattern, pattern.flags)))
    except Exception:     # a construct this reader does not know: no promise, no skipping
        return ()
    if pattern.flags & re.IGNORECASE:
        if not all(n.isascii() for group in found for n in group):
            return ()
        found = [frozenset(n.lower() for n in group) for group in found]
    # stable: ties keep the pattern's order (no set order, which varies by process)
    ranked = sorted(dict.fromkeys(found), key=lambda s: (-min(map(len, s)), len(s)))
    return tuple(ranked[:_MAX_GROUPS])


#: the groups kept per rule: the tests stop at the first group a text misses, so a few more
#: cost little; a dozen would
_MAX_GROUPS = 5


def _all(items: list[tuple[Any, Any]]) -> list[frozenset[str]]:
    """The constraints of a sequence one by one: each literal run, each required part's own
    constraints, a branch's union (:func:`_element`)."""
    out: list[frozenset[str]] = []
    run = ""
    for op, av in items:
        if op is _LITERAL:
            run += chr(av)
            continue
        if run:
            out.append(frozenset({run}))
            run = ""
        if op is _SUBPATTERN and not av[1] & re.IGNORECASE:
            out.extend(_all(list(av[3])))
        elif op is _ATOMIC:
            out.extend(_all(list(av)))
        elif op in _REPEATS and av[0] >= 1:
            out.extend(_all(list(av[2])))
        elif (found := _element(op, av)) is not None:
            out.append(found)
    if run:
        out.append(frozenset({run}))
    return [g for g in out if g and all(g)]

