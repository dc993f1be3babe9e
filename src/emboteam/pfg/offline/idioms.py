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

from emboteam.pfg.offline.knowledge import Rewrite, Strict, apply_rewrites, compile_rewrites, load


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
    #: what a thing described by its use is ("the thing for unblocking the loo"): the verb of
    #: the use -> the noun the lexicon knows
    tool_for: dict[str, str]
    #: what a thing is known by holding ("the thing we keep valuables in"): what is kept ->
    #: the container the lexicon knows
    kept_in: dict[str, str]


_DATA = load("idioms.json", IdiomsFile)
#: spoken and typed variants, applied right after contractions are expanded
SPOKEN = compile_rewrites(_DATA.spoken)
#: postures, corrected places, clefts, asides: applied after :func:`_where_things_are`
PHRASINGS = compile_rewrites(_DATA.phrasings)
TOOL_FOR = _DATA.tool_for
KEPT_IN = _DATA.kept_in
_RESULT_WORDS = _DATA.result_words
_WISH_WORDS = _DATA.wish_words

_POSTURE = r"(?:lying|laying|sitting|standing|resting|perched|sat|stood|hanging)"
#: places a thing can go onto or into: after a relative clause they become "from"
_ON_IN = r"(?:on top of|on|in|inside|over on|out on|down on|up on)"
_BESIDE = r"(?:next to|by|near|under|beside|behind|at)"
_DET = r"(?:the|a|an|my|your|his|her|our|their|this|that|one)"
_RELATIVE_PLACE = re.compile(
    r"(,\s*)?\b(?:that|which) (?:is|are|was|were) (?:(?:still|currently|now|just|already) )?(?:" + _POSTURE + r" )?"
    r"(" + _ON_IN + "|" + _BESIDE + r") ((?:" + _DET + r" )?[a-z][^,.;:!?]{0,60})(\s*,\s*(?=[a-z]))?")
_PARTICIPLE_PLACE = re.compile(r"\b(\w+) " + _POSTURE + r" (" + _ON_IN + "|" + _BESIDE + r") (?=" + _DET + r"\b)")


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


_DESCRIBED = r"(?:the|that|this|a) (?:thing|thingy|tool|gadget|device|whatsit|doodah|doohickey|one|stuff)"
_PERSON_USE = r"(?: (?:that |which )?(?:you|we|i|u|people) (?:use|need|want|have)?)?"
_KEPT = "|".join(sorted(KEPT_IN, key=len, reverse=True))
_HOLDER = r"(?:thing|thingy|box|place|one|spot|container|cupboard|unit)"


def _described_by_contents(text: str) -> str:
    """"in the thing we keep valuables in", "where we keep the dirty laundry": the
    container what it holds names (:data:`KEPT_IN`)."""
    def name(m: re.Match[str]) -> str:
        return f"the {KEPT_IN[m.group(1)]}"

    text = re.sub(r"\b(?:the|that|this) " + _HOLDER + r" (?:that |which |where )?(?:we|i|you|u|they) "
                  r"(?:keep|store|put|lock|stash|hide)(?: (?:the|our|my|all the|all our|any))? (" + _KEPT
                  + r")(?: in| into| away in)?\b", name, text)
    return re.sub(r"\b(?:in |into )?where (?:we|i|you|u|they) (?:keep|store|put|lock|stash|hide)"
                  r"(?: (?:the|our|my|all the|all our|any))? (" + _KEPT + r")\b",
                  lambda m: f"in {name(m)}", text)


def _described_by_use(text: str) -> str:
    """"the thing for unblocking the loo", "the thing you cut bread with", "the tool to
    flip pancakes": the object the use names (:data:`TOOL_FOR`)."""
    verbs = "|".join(sorted(TOOL_FOR, key=len, reverse=True))

    def name(m: re.Match[str]) -> str:
        verb = m.group(1)
        return f"the {TOOL_FOR.get(verb) or TOOL_FOR.get(verb.rstrip('s'), verb)}"

    text = re.sub(_DESCRIBED + _PERSON_USE + r" (?:for|to) (" + verbs + r")(?:ing)?\b"
                  r"(?: (?:the|a|an|some|my|your|our) [a-z]+| [a-z]+s)?(?: with)?", name, text)
    return re.sub(_DESCRIBED + r" (?:that |which )?(?:you|we|i|u) (" + verbs + r")s?\b(?: [a-z]+){0,3}? with\b",
                  name, text)


def spoken(text: str) -> str:
    """The spoken and typed variants of :data:`SPOKEN`, in order."""
    return apply_rewrites(SPOKEN, text)


def rephrase(text: str) -> str:
    """Where things are, things described by their use or contents, then :data:`PHRASINGS`."""
    text = _described_by_contents(_described_by_use(_where_things_are(text)))
    return apply_rewrites(PHRASINGS, text)
