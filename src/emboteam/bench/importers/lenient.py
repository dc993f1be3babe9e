"""A tolerant reader for one-record-per-line task files that are *almost* JSON.

SMART-LLM's test files hold Python literals (``None``), records with a missing ``]`` in
the middle or missing closing brackets at the end, trailing commas and unterminated
strings. No JSON, JSON5 or YAML parser accepts all of these, so a record is repaired at
the token level (bracket balancing, literal normalisation) and then read with
:func:`ast.literal_eval`, which evaluates literals only and never runs code. Every repair
is reported, so an importer can say what it changed.
"""

from __future__ import annotations

import ast
import json
import re
from typing import Any

from emboteam.errors import EmboTeamError


class RecordSyntaxError(EmboTeamError):
    """A line that no repair turns into a literal."""


_TOKEN = re.compile(r"""
    (?P<str>"(?:[^"\\\n]|\\.)*"|'(?:[^'\\\n]|\\.)*')
  | (?P<open_str>["'].*)
  | (?P<punct>[{}\[\],:])
  | (?P<ws>\s+)
  | (?P<atom>[^\s{}\[\],:"']+)
""", re.VERBOSE)

_CLOSER = {"{": "}", "[": "]"}
_LITERALS = {"null": "None", "none": "None", "true": "True", "false": "False"}
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_PUNCT = frozenset("{}[],:")


def _tokens(text: str) -> tuple[list[str], list[str]]:
    out: list[str] = []
    repairs: list[str] = []
    for m in _TOKEN.finditer(text):
        kind, value = m.lastgroup, m.group()
        if kind == "ws":
            continue
        if kind == "open_str":
            value = value.rstrip()
            quote = value[0]
            # an unterminated string runs to the end of the line: close it there
            repairs.append(f"closed an unterminated string {value[:20]!r}")
            out.append(value + quote)
            break
        if kind == "atom":
            low = value.lower()
            if low in _LITERALS:
                if value != _LITERALS[low]:
                    repairs.append(f"read {value} as {_LITERALS[low]}")
                value = _LITERALS[low]
            elif _WORD.fullmatch(value):
                repairs.append(f"quoted the bare word {value!r}")
                value = repr(value)
            # anything else (``open(``, ``+``) is left for literal_eval to reject
        if out and out[-1] not in _PUNCT and value not in _PUNCT:
            raise RecordSyntaxError(f"two values without a separator: {out[-1]} {value}")
        out.append(value)
    return out, repairs


def repair(text: str) -> tuple[str, list[str]]:
    """The record's text with brackets balanced and literals normalised, and the repairs."""
    tokens, repairs = _tokens(text.strip())
    while tokens and tokens[-1] == ",":
        tokens.pop()
        repairs.append("dropped a trailing comma after the record")
    out: list[str] = []
    stack: list[str] = []
    for tok in tokens:
        if tok in _CLOSER:
            stack.append(tok)
        elif tok in ("}", "]"):
            if tok not in (_CLOSER[s] for s in stack):
                repairs.append(f"dropped an unmatched {tok!r}")
                continue
            while _CLOSER[stack[-1]] != tok:
                out.append(_CLOSER[stack.pop()])
                repairs.append(f"inserted a missing {out[-1]!r}")
            stack.pop()
        elif tok == ":" and stack and stack[-1] == "[" and out and out[-1][0] in "\"'":
            # a key inside a list: the list was never closed ("[{..}, "trans": 0")
            key = out.pop()
            comma = out.pop() if out and out[-1] == "," else None
            out.append("]")
            stack.pop()
            repairs.append(f"inserted a missing ']' before key {key}")
            if comma:
                out.append(comma)
            out.append(key)
        out.append(tok)
    while stack:
        out.append(_CLOSER[stack.pop()])
        repairs.append(f"inserted a missing {out[-1]!r} at the end")
    return " ".join(out), repairs


def read_record(text: str) -> tuple[Any, list[str]]:
    """Parse one record leniently: (value, repairs). Raises :class:`RecordSyntaxError`.

    Strict JSON is tried first: a valid line needs no repair, and only the JSON reader
    gets its escapes right (``\\/`` is ``/`` in JSON, a backslash and a slash to
    :func:`ast.literal_eval`)."""
    try:
        return json.loads(text), []
    except (ValueError, RecursionError):  # JSONDecodeError is a ValueError
        pass
    try:
        fixed, repairs = repair(text)
    except RecordSyntaxError as exc:
        raise RecordSyntaxError(f"not a record: {exc}") from None
    try:
        return ast.literal_eval(fixed), repairs
    except (ValueError, SyntaxError, MemoryError, RecursionError) as exc:
        raise RecordSyntaxError(f"not a record even after repair ({type(exc).__name__}: {exc})") from None
