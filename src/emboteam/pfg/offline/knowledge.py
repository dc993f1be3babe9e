"""The reader's knowledge as data: the lexicon, the idioms and the word tables of the
offline parser live in JSON files under ``data/`` (docs/teach_a_phrasing.md). The code
interprets them; the data knows the language, as spaCy's Matcher patterns do.

Each file is validated against a pydantic schema when it is first loaded (once per
process, cached): a malformed entry is a :class:`KnowledgeDataError` that names the file
and the entry, never a half-loaded table or a wrong reading later.
"""

from __future__ import annotations

import json
import re
from functools import cache
from pathlib import Path
from typing import Any, TypeVar

from pydantic import BaseModel, ConfigDict, ValidationError, model_validator

from emboteam.errors import EmboTeamError
from emboteam.pfg.offline.regex_filter import needle_groups
from emboteam.world.catalogue import load_catalogue

#: where the knowledge files are (package data)
DATA_DIR = Path(__file__).with_name("data")

M = TypeVar("M", bound=BaseModel)


class KnowledgeDataError(EmboTeamError):
    """A knowledge file of the offline parser is malformed: ``file``, the ``entry`` at fault
    (its path in the file, e.g. ``nouns -> 'settee'``) and what is wrong with it."""

    def __init__(self, file: str, entry: str, problem: str) -> None:
        self.file, self.entry, self.problem = file, entry, problem
        super().__init__(f"{file}: {entry}: {problem}")


class Strict(BaseModel):
    """Every table is closed: a misspelt field or table name is an error, not ignored."""

    model_config = ConfigDict(extra="forbid", frozen=True)


class Rewrite(Strict):
    """A regular expression on normalised text and what it is rewritten to (``\\1`` refers
    to a group), with the phrasing it is for."""

    pattern: str
    replace: str
    why: str = ""

    @model_validator(mode="after")
    def _compiles(self) -> Rewrite:
        try:
            compiled = re.compile(self.pattern)
        except re.error as exc:
            raise ValueError(f"pattern {self.pattern!r} is no regular expression: {exc}") from None
        for ref in re.findall(r"\\(\d+)|\\g<(\d+)>", self.replace):
            group = int(ref[0] or ref[1])
            if group > compiled.groups:
                raise ValueError(f"replacement {self.replace!r} refers to group {group}; "
                                 f"the pattern has {compiled.groups}")
        return self

    def compiled(self) -> tuple[re.Pattern[str], str]:
        return re.compile(self.pattern), self.replace


#: a compiled rewrite: the pattern, its replacement, the groups of strings a match contains
#: one of each of (:func:`.regex_filter.needle_groups`) and whether they are lower-case
#: strings of a case-blind pattern (tested on the lower-cased ASCII text)
CompiledRewrite = tuple[re.Pattern[str], str, tuple[frozenset[str], ...], bool]


def compile_rewrites(rules: tuple[Rewrite, ...]) -> tuple[CompiledRewrite, ...]:
    return tuple((pattern, repl, needle_groups(pattern), bool(pattern.flags & re.IGNORECASE))
                 for pattern, repl in (rule.compiled() for rule in rules))


def apply_rewrites(rules: tuple[CompiledRewrite, ...], text: str) -> str:
    """Each rule in order, every match rewritten (``re.sub``); a rule that misses a string
    of one of its needle groups cannot match and is skipped (:mod:`.regex_filter`)."""
    lower: str | None = None    # the text lower-cased, for the case-blind rules' groups
    for pattern, repl, groups, blind in rules:
        if groups and (not blind or text.isascii()):
            probe = text
            if blind:
                probe = lower = text.lower() if lower is None else lower
            missing = False
            for group in groups:    # loops, not a call or any(): this runs per rule
                for needle in group:
                    if needle in probe:
                        break
                else:
                    missing = True
                    break
            if missing:
                continue
        changed = pattern.sub(repl, text)
        if changed != text:
            text, lower = changed, None
    return text


def _gist(node: Any) -> str:
    """What an entry of a list says, to find it by: its pattern, its first words or why it is."""
    shown = node.get("pattern") or node.get("words") or node.get("why") if isinstance(node, dict) else None
    if isinstance(shown, list):
        return f" ({', '.join(map(str, shown[:3]))}{', ...' if len(shown) > 3 else ''})"
    return f" ({str(shown)[:60]!r})" if shown else ""


def _entry(raw: Any, loc: tuple[int | str, ...]) -> str:
    """``nouns -> 'settee'``, ``phrasings[3] ('\\bput the lid ...')``: where in the file."""
    parts: list[str] = []
    node = raw
    for key in loc:
        try:
            node = node[key]
        except (KeyError, IndexError, TypeError):
            node = None
        if isinstance(key, int) and parts:
            parts[-1] += f"[{key}]{_gist(node)}"
        else:
            parts.append(repr(key) if parts else str(key))
    return " -> ".join(parts)


def load(name: str, schema: type[M]) -> M:
    """The file ``data/NAME`` read as ``schema``; cached, so each file is read once."""
    return _load(name, schema)   # type: ignore[return-value]


@cache
def _load(name: str, schema: type[BaseModel]) -> BaseModel:
    return read(DATA_DIR / name, schema)


def read(path: Path, schema: type[M]) -> M:
    """The knowledge file at ``path`` read as ``schema`` (uncached: :func:`load` caches)."""
    try:
        raw = json.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise KnowledgeDataError(path.name, "(file)", f"cannot be read: {exc.strerror}") from None
    except json.JSONDecodeError as exc:
        raise KnowledgeDataError(path.name, f"line {exc.lineno} column {exc.colno}", f"not JSON: {exc.msg}") from None
    return validate(path.name, raw, schema)


def validate(name: str, raw: Any, schema: type[M]) -> M:
    """``raw`` (the parsed JSON of the file ``name``) as ``schema``, or the first problem as a
    :class:`KnowledgeDataError` naming the entry."""
    try:
        return schema.model_validate(raw)
    except ValidationError as exc:
        first = exc.errors()[0]
        loc = tuple(k for k in first["loc"] if not (isinstance(k, str) and k.startswith("function-")))
        message = str(first["msg"]).removeprefix("Value error, ")
        if not loc and ": " in message:     # a check across tables says where itself
            entry, message = message.split(": ", 1)
            raise KnowledgeDataError(name, entry, message) from None
        raise KnowledgeDataError(name, _entry(raw, loc) or "(top level)", message) from None


def known_types(types: list[str]) -> list[str]:
    """A field validator for the object types a knowledge file names: each one AI2-THOR has."""
    unknown = [t for t in types if t not in load_catalogue().types]
    if unknown:
        raise ValueError(f"unknown object type {unknown[0]!r}")
    return types


class WordsFile(Strict):
    """``data/words.json``: the word lists each module of the parser compares tokens with,
    by module and table (a set of words, an ordered list, or phrases of several words)."""

    about: str = ""
    tables: dict[str, dict[str, tuple[str, ...]]]

    @model_validator(mode="after")
    def _words(self) -> WordsFile:
        for module, tables in self.tables.items():
            for table, words in tables.items():
                bad = [w for w in words if not w or w != w.lower().strip() or "  " in w]
                if bad:
                    raise ValueError(f"tables -> {module!r} -> {table!r}: {bad[0]!r} is not a "
                                     "lower-case word or phrase (the parser's tokens are lower-case)")
        return self


class WordTables:
    """The word tables of one module; a table the module asks for and the file lacks is a
    :class:`KnowledgeDataError` at import."""

    FILE = "words.json"

    def __init__(self, module: str) -> None:
        self.module = module
        self.tables = load(self.FILE, WordsFile).tables.get(module, {})

    def _get(self, name: str) -> tuple[str, ...]:
        if name not in self.tables:
            raise KnowledgeDataError(self.FILE, f"tables -> {self.module!r} -> {name!r}",
                                     f"missing: the module {self.module} needs it")
        return self.tables[name]

    def set(self, name: str) -> frozenset[str]:
        return frozenset(self._get(name))

    def seq(self, name: str) -> tuple[str, ...]:
        return self._get(name)

    def phrases(self, name: str) -> tuple[tuple[str, ...], ...]:
        """Phrases of several words, each as its words: ``"one of you"`` -> ``("one", "of", "you")``."""
        return tuple(tuple(p.split()) for p in self._get(name))


def word_tables(module: str) -> WordTables:
    return WordTables(module)
