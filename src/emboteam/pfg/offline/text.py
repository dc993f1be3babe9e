"""Normalisation and tokenisation: from what people type to a clean token stream.

Lower-cases, splits CamelCase type names (``CounterTop`` -> ``counter top``), expands
contractions (``don't`` -> ``do not``), turns arrows and ampersands into words and keeps
sentence punctuation as tokens, because clause boundaries depend on it. Kept by hand
(a few regular expressions): a tokenizer library would not know AI2-THOR's CamelCase
names, and the parser must stay dependency-free and fast.
"""

from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass

from emboteam.pfg.offline.idioms import rephrase, spoken
from emboteam.pfg.offline.knowledge import Rewrite, Strict, apply_rewrites, compile_rewrites, load

#: punctuation kept as tokens: they delimit sentences and clauses
PUNCT = frozenset(".,;:!?")


class TextFile(Strict):
    """``data/text.json``: the rewrites of normalisation, by stage."""

    about: str = ""
    replace: tuple[Rewrite, ...]
    contractions: tuple[Rewrite, ...]
    chat: tuple[Rewrite, ...]


_DATA = load("text.json", TextFile)
#: on the text as typed: quotes, arrows, dashes, bullets, brackets
_REPLACE = compile_rewrites(_DATA.replace)
#: after lower-casing: "won't" -> "will not", "the lamp's off" -> "the lamp is off"
_CONTRACTIONS = compile_rewrites(_DATA.contractions)
#: chat spellings, after the spoken variants of :mod:`~emboteam.pfg.offline.idioms`
_CHAT = compile_rewrites(_DATA.chat)


@dataclass(frozen=True, slots=True)
class Token:
    """One word, number or punctuation mark, lower-case."""

    text: str
    index: int


def split_camel(text: str) -> str:
    """``CounterTop`` -> ``Counter Top``, ``TVStand`` -> ``TV Stand``, ``robot2`` -> ``robot 2``."""
    for pattern in _CAMEL:
        text = pattern.sub(" ", text)
    return text


#: where split_camel puts a space: lower-upper, upper-Upperlower (not "CDs"), letter-digit
_CAMEL = tuple(map(re.compile, (r"(?<=[a-z])(?=[A-Z])", r"(?<=[A-Z])(?=[A-Z][a-rt-z]|[A-Z]s[a-z])",
                                r"(?<=[A-Za-z])(?=\d)|(?<=\d)(?=[A-Za-z])")))


_ARROW = r"\s*(?:->|=>|\u2192|\u27f6)\s*"


def _arrows(text: str) -> str:
    """An arrow between a thing and a place is "to" ("apple -> fridge"); a chain of arrows in
    one sentence is a sequence of steps ("kettle out -> fill it -> onto a burner")."""
    def chain(part: str) -> bool:
        middle = re.split(_ARROW, part)[1:-1]
        return any(not re.search(r"[,;&+]|\band\b", m) and len(m.split()) >= 3 for m in middle)

    return ".".join(re.sub(_ARROW, " , then ", part) if chain(part) else part for part in text.split("."))


#: a word broken off by a dash and a hedge ("crack- well, just put the egg in"): a
#: self-correction, read as "I mean" (offline/corrections.py)
_BROKEN_OFF = re.compile(r"\b([A-Za-z]+)-\s+(?:well|actually|er|erm|um|hmm),?\s+(?:just\s+)?")


#: a word broken off by a dash before a space ("into the b- in the box", "in the fri-" as
#: another speaker cuts in)
_CUT_WORD = re.compile(r"\b([A-Za-z]+)-(?=\s|$)")
#: how many words on the speaker may say the broken word in full
_CUT_REACH = 30


def _finish_cut_words(text: str) -> str:
    """A broken-off word as the word it began, when one of the next words starts with it
    ("the b- ... The BOX" -> "the box"): a false start says where the speaker was going.
    Without such a word it stays as typed."""
    def finish(m: re.Match[str]) -> str:
        stem = m.group(1).lower()
        later = re.findall(r"[A-Za-z]+", text[m.end():])[:_CUT_REACH]
        return next((w.lower() for w in later if len(w) > len(stem) and w.lower().startswith(stem)), m.group(0))
    return _CUT_WORD.sub(finish, text)


#: letters with no decomposition into a letter and its accent
_LIGATURES = str.maketrans({"ß": "ss", "æ": "ae", "œ": "oe", "ø": "o", "Æ": "Ae", "Œ": "Oe", "Ø": "O"})


def fold_accents(text: str) -> str:
    """Accented letters as their plain letters ("móvil" -> "movil", "Mülleimer" ->
    "Mulleimer"): the reader's words are ASCII, and an accent must not cut a word in two.
    Only combining marks go (canonical decomposition): "½" and symbols stay as typed."""
    if text.isascii():
        return text
    parts = unicodedata.normalize("NFD", text.translate(_LIGATURES))
    return unicodedata.normalize("NFC", "".join(c for c in parts if not unicodedata.combining(c)))


def normalize(text: str) -> str:
    """The instruction as lower-case words and punctuation separated by single spaces."""
    text = fold_accents(text)
    text = _BROKEN_OFF.sub(r"\1 , i mean , ", _arrows(_finish_cut_words(text)))
    text = apply_rewrites(_REPLACE, text)
    text = apply_rewrites(_CONTRACTIONS, split_camel(text).lower())
    text = apply_rewrites(_CHAT, spoken(text))
    text = _HYPHEN.sub(" ", text)   # counter-top, well-lit
    text = rephrase(text)
    text = _ORDINAL_SUFFIX.sub("", text)   # 2nd -> 2
    text = _MARK.sub(r" \1 ", text)
    text = _OTHER.sub(" ", text)
    return _SPACES.sub(" ", text).strip()


_HYPHEN, _ORDINAL_SUFFIX = re.compile(r"(?<=[a-z])-(?=[a-z])"), re.compile(r"(?<=\d)(st|nd|rd|th)\b")
_MARK, _OTHER, _SPACES = re.compile(r"([.,;:!?])"), re.compile(r"[^a-z0-9.,;:!? ]+"), re.compile(r"\s+")


def tokenize(text: str) -> list[Token]:
    """Normalise and split into tokens."""
    return [Token(w, i) for i, w in enumerate(normalize(text).split())]
