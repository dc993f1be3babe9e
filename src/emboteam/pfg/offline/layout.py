"""The layout of a typed list, made into running text before the surface rules
(:mod:`.surface`): a markdown table's rows, and items nested under a heading.

A table row is its cells in a line; a cell under a column whose header names a place
("where", ``surface.json`` -> ``layout``) is where the row's thing goes ("→ cabinet"),
unless it says so in its own words ("stays on the counter"). Things listed, indented,
under a heading that ends in a colon ("into the box:" over "the card", "the keys") are the
heading's: they join its line, so the heading's destination or verb is theirs (items that
say what to do in their own words keep their lines). Struck-out
words are a rewrite of ``surface.json`` (``~~drawer~~ garbage can``: corrected away).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass

from emboteam.pfg.offline.knowledge import Strict


class Layout(Strict):
    """``surface.json`` -> ``layout``: what opens a list item, the headers of a place column."""

    bullet: str
    place_columns: tuple[str, ...]


_ROW = re.compile(r"^[ \t]*\|(.*)\|[ \t]*$")
_RULE = re.compile(r"^[\s|:-]+$")


@dataclass(frozen=True)
class Words:
    """What the lexicon says of a list's words: whether a cell says what to do in its own
    words (a verb or a state first), whether an item only names things, whether a heading
    is a place ("into the box")."""

    clause: Callable[[str], bool]
    bare: Callable[[str], bool]
    place: Callable[[str], bool]


def read_layout(text: str, layout: Layout, words: Words) -> str:
    """The text with its tables and nested lists as running lines."""
    if "\n" not in text:
        return text
    return "\n".join(_nested(_tables(text.split("\n"), layout, words.clause), re.compile(layout.bullet), words))


def _tables(lines: list[str], layout: Layout, clause: Callable[[str], bool]) -> list[str]:
    out: list[str] = []
    places: set[int] = set()
    header = True
    for line in lines:
        row = _ROW.match(line)
        if row is None:
            out.append(line)
            header = True
            continue
        cells = [c.strip() for c in row.group(1).split("|")]
        if _RULE.match(row.group(1)):
            continue
        if header:      # the first row of a table names its columns
            places = {i for i, c in enumerate(cells) if c.lower().strip("* ") in layout.place_columns}
            header = False
            continue
        said = [f"→ {c}" if i in places and c and not clause(c) else c for i, c in enumerate(cells)]
        out.append(" ".join(c for c in said if c))
    return out


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip(" \t"))


def _nested(lines: list[str], bullet: re.Pattern[str], words: Words) -> list[str]:
    """Things indented under a heading that ends in a colon joined to its line: after a
    heading that is a verb or a label ("put away the apple", "fridge: the apple"), before
    one that is a place ("the card and the keys into the box")."""
    out: list[str] = []
    k = 0
    while k < len(lines):
        line = lines[k]
        k += 1
        block: list[str] = []
        while line.rstrip().endswith(":") and k < len(lines) and lines[k].strip() and _indent(lines[k]) > _indent(line):
            block.append(lines[k])
            k += 1
        inner = _nested(block, bullet, words)
        kids = [bullet.sub("", x).strip() for x in inner]
        if not kids or not all(words.bare(x) for x in kids):
            out += [line, *inner]
            continue
        said = ", ".join(kids[:-1]) + " and " + kids[-1] if len(kids) > 1 else kids[0]
        head = bullet.sub("", line).strip()
        if words.place(head):
            out.append(f"{line[: len(line) - len(bullet.sub('', line))]}{said} {head[:-1]}")
        else:      # "put away: the apple" is "put away the apple"; "fridge: the apple" stays a label
            out.append(f"{line.rstrip()[:-1] if words.clause(head) else line.rstrip()} {said}")
    return out
