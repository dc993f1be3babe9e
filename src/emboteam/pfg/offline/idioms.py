"""Everyday phrasing read as the grammar's phrasing: what people say that the clause
grammar would misread, rewritten to what it means before tagging ("the pen that's lying on
the side table" -> "the pen from the side table", "I could really use a coffee" -> "I would
love a coffee", "is to warm" -> "is too warm"). The rules are data, ``data/idioms.json``
(one table of regular expressions per stage, each rule with the phrasing it is for),
checked against :class:`IdiomsFile` at import: these are closed idioms and fixed word
orders, where a statistical tagger would need training data we do not have.
"""

from __future__ import annotations

import re
from functools import cache

from pydantic import BaseModel, ConfigDict, model_validator

from emboteam.pfg.offline.described import name_described
from emboteam.pfg.offline.knowledge import Rewrite, Strict, apply_rewrites, compile_rewrites, load

_PIECE = re.compile(r"\{([a-z_]+)\}")


class _Described(Strict):
    """Things named by where they are, what they hold or what they are for: patterns
    written with named pieces (``{posture}``)."""

    relative_place: str
    participle_place: str
    kept_in: tuple[str, str]


class _Fractions(Strict):
    """Fraction words and their value (numerator, denominator)."""

    why: str = ""
    words: dict[str, tuple[int, int]]

    @model_validator(mode="after")
    def _proper(self) -> _Fractions:
        for word, (num, den) in self.words.items():
            if not 0 < num < den:
                raise ValueError(f"fractions -> {word!r}: {num}/{den} is not a proper fraction")
        return self


class IdiomsFile(Strict):
    """``data/idioms.json``."""

    about: str = ""
    spoken: tuple[Rewrite, ...]
    phrasings: tuple[Rewrite, ...]
    #: words after which a posture is where something should be ("leave it sitting on the
    #: counter", "find the pen sitting on the dresser", "the book is lying on the bed")
    result_words: frozenset[str]
    #: a wish or a finding earlier in the sentence makes a posture the wished place
    wish_words: frozenset[str]
    #: what a thing is known by holding ("the thing we keep valuables in"): what is kept ->
    #: the container the lexicon knows
    kept_in: dict[str, str]
    #: regular expressions the patterns of ``described`` name as ``{name}``
    pieces: dict[str, str]
    described: _Described
    fractions: _Fractions

    def expand(self, pattern: str) -> str:
        """The pattern with its pieces filled in; ``{kept}`` is the keys of ``kept_in``,
        longest first."""
        pieces = {**self.pieces, "kept": _alternatives(self.kept_in)}
        return _PIECE.sub(lambda m: pieces[m.group(1)], pattern)

    @model_validator(mode="after")
    def _patterns_compile(self) -> IdiomsFile:
        known = {*self.pieces, "kept"}
        for name, value in self.described:
            for k, pattern in enumerate((value,) if isinstance(value, str) else value):
                where = f"described -> {name}" + ("" if isinstance(value, str) else f"[{k}]")
                unknown = [p for p in _PIECE.findall(pattern) if p not in known]
                if unknown:
                    raise ValueError(f"{where}: no piece {unknown[0]!r} (pieces: {', '.join(sorted(known))})")
                Rewrite(pattern=self.expand(pattern), replace="")
        return self


def _alternatives(table: dict[str, str]) -> str:
    return "|".join(sorted(table, key=len, reverse=True))


_DATA = load("idioms.json", IdiomsFile)
#: spoken and typed variants, applied right after contractions are expanded
SPOKEN = compile_rewrites(_DATA.spoken)
#: postures, corrected places, clefts, asides: applied after :func:`_where_things_are`
PHRASINGS = compile_rewrites(_DATA.phrasings)
KEPT_IN = _DATA.kept_in
_RESULT_WORDS = _DATA.result_words
_WISH_WORDS = _DATA.wish_words

_ON_IN = _DATA.expand("{on_in}")
_RELATIVE_PLACE, _PARTICIPLE_PLACE = (re.compile(_DATA.expand(p)) for p in (
    _DATA.described.relative_place, _DATA.described.participle_place))
_KEPT_IN = tuple(re.compile(_DATA.expand(p)) for p in _DATA.described.kept_in)


_FRACTION = _alternatives({re.escape(w): "" for w in _DATA.fractions.words})
_ANY_FRACTION = re.compile(rf"(?:{_FRACTION})")
_OF_THE = r"(?:the |my |those |these |all |all the )?"
#: "half of the four vases", "of the four vases, half"
_FRACTION_OF = re.compile(rf"\b(?:just |only )?({_FRACTION}) of {_OF_THE}([a-z]+|\d+)\b")
_OF_N_FRACTION = re.compile(rf"\bof {_OF_THE}([a-z]+|\d+) ([a-z]+(?: [a-z]+)?) ?, ?({_FRACTION})(?=\s|$)")


class _NumberWords(BaseModel):
    """The number words of ``data/lexicon.json`` (read here without the lexicon module,
    which imports the text stage this module belongs to)."""

    model_config = ConfigDict(extra="ignore", frozen=True)
    numbers: dict[str, int]


@cache
def _numbers() -> tuple[dict[str, int], dict[int, str]]:
    """The number words both ways (the first word of a number: "two", not "both")."""
    numbers = load("lexicon.json", _NumberWords).numbers
    words: dict[int, str] = {}
    for w, n in numbers.items():
        words.setdefault(n, w)
    return numbers, words


def warm_idioms() -> None:
    """Load the number words ahead of the first instruction."""
    _numbers()


def _fractions(text: str) -> str:
    """A fraction of a said number is that count ("half of the four vases" -> "two vases");
    left as said when the number is no number or the part no whole count."""
    if not _ANY_FRACTION.search(text):
        return text
    numbers, words = _numbers()

    def part(fraction: str, number: str) -> str | None:
        total = int(number) if number.isdigit() else numbers.get(number)
        num, den = _DATA.fractions.words[fraction]
        if total is None or (total * num) % den:
            return None
        n = total * num // den
        return words.get(n, str(n))

    def fraction_of(m: re.Match[str]) -> str:
        return part(m.group(1), m.group(2)) or m.group()

    def of_n_fraction(m: re.Match[str]) -> str:
        n = part(m.group(3), m.group(1))
        return f"{n} {m.group(2)}" if n else m.group()

    return _OF_N_FRACTION.sub(of_n_fraction, _FRACTION_OF.sub(fraction_of, text))


def _where_things_are(text: str) -> str:
    """"the pen that's lying on the side table", "my phone, which is sitting on a shelf,",
    "the sponge lying in the tub": a relative clause or a participle of posture after a
    noun says where the thing is now. It becomes "from the side table", which no verb reads
    as where the thing goes ("put the vase that's on the shelf and the keys in the box");
    a place beside something stays as it is. After "leave", "find" or a copula the posture
    is the wished place ("leave it sitting on the counter")."""
    def relative(m: re.Match[str]) -> str:
        prep = "from" if re.fullmatch(_ON_IN, m.group(2)) else m.group(2)
        if m.group(1) is not None and m.group(4) is not None:
            return f" {prep} {m.group(3)} "         # an aside between commas
        return f"{m.group(1) or ' '}{prep} {m.group(3)}{m.group(4) or ' '}"

    def participle(m: re.Match[str]) -> str:
        if m.group(1) in _RESULT_WORDS or not re.fullmatch(_ON_IN, m.group(2)):
            return f"{m.group(1)} {m.group(2)} "
        # "I want to ... find the racket on the bed, the pen sitting on the dresser": a
        # wish or a finding earlier in the sentence makes it the wished place
        sentence = re.split(r"[.!?;]", text[:m.start()])[-1].split()
        if any(w in _WISH_WORDS for w in sentence):
            return f"{m.group(1)} {m.group(2)} "
        return f"{m.group(1)} from "

    text = _RELATIVE_PLACE.sub(relative, text)
    return _PARTICIPLE_PLACE.sub(participle, text)


def _described_by_contents(text: str) -> str:
    """"in the thing we keep valuables in", "where we keep the dirty laundry": the
    container what it holds names (:data:`KEPT_IN`)."""
    def name(m: re.Match[str]) -> str:
        return f"the {KEPT_IN[m.group(1)]}"

    text = _KEPT_IN[0].sub(name, text)
    return _KEPT_IN[1].sub(lambda m: f"in {name(m)}", text)


def spoken(text: str) -> str:
    """The spoken and typed variants of :data:`SPOKEN`, in order."""
    return apply_rewrites(SPOKEN, text)


def rephrase(text: str) -> str:
    """Where things are, things described by their use or look (:mod:`.described`, here
    without a scene: the front end names them for its scene first) or contents, then
    :data:`PHRASINGS`."""
    text = _described_by_contents(name_described(_where_things_are(_fractions(text))))
    return apply_rewrites(PHRASINGS, text)
