"""The complete part of a JSON answer cut off at the token limit.

A weak model that loops (the same subtask again and again) runs into the completion
cap: its answer is cut mid-object and is not JSON. Rejecting it as "not JSON" would hide
the reason it is long; closing the JSON after the last complete element lets the usual
checks run on what was written ("s2 repeats s1", a condition copied from the example),
so the feedback names the fault. The closed prefix is only ever used for feedback: a
cut answer is never accepted.
"""

from __future__ import annotations

import json
from typing import Any

_CLOSE = {"{": "}", "[": "]"}


def complete_prefix(text: str) -> dict[str, Any] | None:
    """The longest prefix of ``text`` that ends with a complete element of the outermost
    container that has any (the subtasks array: a half-written subtask is dropped, not
    closed), closed with the brackets still open, parsed; None if there is none."""
    stack: list[str] = []
    cuts: list[tuple[int, str]] = []  # (end of a complete nested value, closing suffix)
    in_string = escaped = False
    start = text.find("{")
    if start < 0:
        return None
    for i in range(start, len(text)):
        ch = text[i]
        if in_string:
            if escaped:
                escaped = False
            elif ch == "\\":
                escaped = True
            elif ch == '"':
                in_string = False
            continue
        if ch == '"':
            in_string = True
        elif ch in _CLOSE:
            stack.append(ch)
        elif ch in "}]":
            if not stack or _CLOSE[stack[-1]] != ch:
                return None
            stack.pop()
            if not stack:  # the whole object is complete: not a cut answer
                return None
            cuts.append((i + 1, "".join(_CLOSE[b] for b in reversed(stack))))
    shallowest = min((len(suffix) for _, suffix in cuts), default=0)
    for end, suffix in reversed(cuts):
        if len(suffix) != shallowest:
            continue
        try:
            value = json.loads(text[start:end] + suffix)
        except ValueError:
            continue
        if isinstance(value, dict):
            return value
    return None
