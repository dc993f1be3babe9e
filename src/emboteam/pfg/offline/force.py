"""A clause's force: the request behind a sentence that is no plain imperative ("I'm not
not wanting the lamp off", "I wouldn't dream of leaving it open", "not anywhere but the
box", "is there any chance X might ...", "X was off ... all that again", "House rules: the
lid is closed at night"), rewritten to its plain phrasing so the grammar reads the state
asked for, not its opposite. One mechanism, its words data (``data/force.json``): the
cancelling of negation pairs runs to a fixed point (their count composes), then the
rewrites; the cues of a repeat and of a rule are scoped by sentence.
"""

from __future__ import annotations

import re
from functools import cache

from pydantic import model_validator

from emboteam.pfg.offline.knowledge import Rewrite, Strict, load
from emboteam.pfg.offline.morphology import verb_lemma
from emboteam.pfg.offline.regex_filter import needles

_PIECE = re.compile(r"\{([a-z_]+)\}")
#: where a sentence (a repeat cue's scope) ends in normalised text
_SENTENCE = re.compile(r"(?<= [.;!?]) ")


class ForceRule(Strict):
    """A rewrite written with named pieces; group ``base`` holds an -ing verb, written as its
    base form ("dream of leaving" -> "leave")."""

    pattern: str
    replace: str
    base: int | None = None
    why: str = ""


#: the rewrite tables, in the order they apply
RULES = ("cancel", "only", "litotes", "request", "states")
#: the cue tables: over their sentence, every sentence before, every one after; rule headers
CUES = ("repeat_cues", "repeat_all_cues", "restore_headers", "rule_headers")


class ForceFile(Strict):
    """``data/force.json``: named ``pieces``; double negations (``cancel``, each rule removes a
    pair), ``only``, ``litotes``, ``request`` (questions and hedges), ``states`` (kept and described states); the cues of a past
    arrangement to repeat and the forms they make wished ("was" -> "should be"); rule headers
    and what a described state after one becomes."""

    about: str = ""
    pieces: dict[str, str]
    cancel: tuple[ForceRule, ...]
    only: tuple[ForceRule, ...]
    litotes: tuple[ForceRule, ...]
    request: tuple[ForceRule, ...]
    #: a described or kept state said plainly: code forms, "X is on, leave it", sarcasm's correction
    states: tuple[ForceRule, ...] = ()
    repeat_cues: tuple[str, ...]
    repeat_all_cues: tuple[str, ...]
    restore_headers: tuple[str, ...]
    wished_forms: dict[str, str]
    present_forms: dict[str, str]
    rule_headers: tuple[str, ...]
    rule_states: ForceRule

    def expand(self, pattern: str) -> str:
        return _PIECE.sub(lambda m: self.pieces[m.group(1)], pattern)

    @model_validator(mode="after")
    def _compiles(self) -> ForceFile:
        rules = [(f"{t}[{k}]", r) for t in RULES for k, r in enumerate(getattr(self, t))]
        for where, rule in [*rules, ("rule_states", self.rule_states)]:
            unknown = [p for p in _PIECE.findall(rule.pattern) if p not in self.pieces]
            if unknown:
                raise ValueError(f"{where}: no piece {unknown[0]!r} (pieces: {', '.join(sorted(self.pieces))})")
            base = f"\\{rule.base}" if rule.base else ""
            try:
                Rewrite(pattern=self.expand(rule.pattern), replace=rule.replace + base)
            except ValueError as exc:
                raise ValueError(f"{where}: {exc}") from None
        for table in CUES:
            for k, cue in enumerate(getattr(self, table)):
                Rewrite(pattern=cue, replace="", why=f"{table}[{k}]")
        return self


_Compiled = tuple[re.Pattern[str], str, int | None, frozenset[str] | None]


@cache
def _tables() -> tuple[ForceFile, dict[str, tuple[_Compiled, ...]], dict[str, re.Pattern[str]],
                       tuple[re.Pattern[str], re.Pattern[str]]]:
    data = load("force.json", ForceFile)
    def comp(rule: ForceRule) -> _Compiled:
        pattern = re.compile(data.expand(rule.pattern))
        return pattern, rule.replace, rule.base, needles(pattern)    # skipped when no needle is in the text

    rules = {t: tuple(map(comp, getattr(data, t))) for t in RULES} | {"rule_states": (comp(data.rule_states),)}
    cues = {t: re.compile(" ?(?:" + "|".join(getattr(data, t)) + ")") for t in CUES}
    forms = sorted(map(re.escape, data.wished_forms), key=len, reverse=True)
    present = re.compile(r"\b(?:" + "|".join(map(re.escape, data.present_forms)) + r")\b")
    return data, rules, cues, (re.compile(r"\b(?:" + "|".join(forms) + r")\b"), present)


def warm_force() -> None:
    """Compile the force rules ahead of the first instruction (a fifth of a second, once)."""
    _tables()


def _sub(rule: _Compiled, text: str) -> str:
    pattern, repl, base, required = rule
    if required is not None and not any(n in text for n in required):
        return text

    def fill(m: re.Match[str]) -> str:
        groups = [m.group(0), *(g or "" for g in m.groups())]
        if base is not None:       # "leaving" -> "leave" (a verb the lexicon knows)
            groups[base] = (verb_lemma(groups[base]) or (groups[base],))[0]
        return re.sub(r"\\(\d+)", lambda r: groups[int(r.group(1))], repl)

    return pattern.sub(fill, text)


def _found(pattern: re.Pattern[str], text: str) -> bool:
    """Does ``pattern`` match in ``text``? Looked for only when one of its needles is there."""
    required = _needles(pattern)
    return (required is None or any(n in text for n in required)) and pattern.search(text) is not None


_needles = cache(needles)


def _repeat(text: str, data: ForceFile, cues: dict[str, re.Pattern[str]],
            forms: tuple[re.Pattern[str], re.Pattern[str]]) -> str:
    """A past arrangement told to be repeated: the described forms of the cue's sentence (of
    the one before, when the cue stands alone: "...; this time too"), and the past ones of
    every sentence before a "make it so" or after an "undo it", become the wished ones."""
    if not any(_found(cues[t], text) for t in CUES[:3]):
        return text
    parts = _SENTENCE.split(text)

    def wish(part: str, present: bool = False) -> str:
        part = forms[0].sub(lambda m: data.wished_forms[m.group(0)], part)
        return forms[1].sub(lambda m: data.present_forms[m.group(0)], part) if present else part

    for k, part in enumerate(parts):
        if cues["repeat_all_cues"].search(part):
            parts[:k], parts[k] = [wish(p) for p in parts[:k]], cues["repeat_all_cues"].sub("", part)
        elif cues["restore_headers"].search(part):
            parts[k + 1:] = [wish(p) for p in parts[k + 1:]]
        elif cues["repeat_cues"].search(part):
            rest = cues["repeat_cues"].sub("", part)
            if re.search(r"[a-z]", rest.replace("this time", "").replace("please", "")) or k == 0:
                parts[k] = wish(rest, present=True)
            else:
                parts[k - 1], parts[k] = wish(parts[k - 1], present=True), rest.strip(" .;!?")
    return " ".join(p for p in parts if p.strip())


def read_force(text: str) -> str:
    """The normalised instruction with each clause's force said plainly (module doc)."""
    data, rules, cues, forms = _tables()
    for _ in range(4):           # negations compose: each pass removes one pair
        before = text
        for rule in rules["cancel"]:
            text = _sub(rule, text)
        if text == before:
            break
    for table in RULES[1:]:
        for rule in rules[table]:
            text = _sub(rule, text)
    text = _repeat(text, data, cues, forms)
    header = cues["rule_headers"].search(text) if _found(cues["rule_headers"], text) else None
    if header is not None:
        # a rule holds from its header on, and over the header's own sentence ("cabinets
        # are shut in this house": said after what it rules)
        start = max(text.rfind(p, 0, header.start()) for p in ".!?;") + 1
        text = text[:start] + _sub(rules["rule_states"][0], text[start:])
    return re.sub(r"\s+", " ", text).strip()
