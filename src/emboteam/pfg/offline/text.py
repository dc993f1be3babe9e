"""Normalisation and tokenisation: from what people type to a clean token stream.

Lower-cases, splits CamelCase type names (``CounterTop`` -> ``counter top``), expands
contractions (``don't`` -> ``do not``), turns arrows and ampersands into words and keeps
sentence punctuation as tokens, because clause boundaries depend on it. Kept by hand
(a few regular expressions): a tokenizer library would not know AI2-THOR's CamelCase
names, and the parser must stay dependency-free and fast.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

#: punctuation kept as tokens: they delimit sentences and clauses
PUNCT = frozenset(".,;:!?")

_REPLACE: tuple[tuple[str, str], ...] = (
    (r"[\u2018\u2019\u201b`´]", "'"),
    (r"[\u201c\u201d\"]", " "),
    (r"\s*(?:->|=>|\u2192|\u27f6)\s*", " to "),
    (r"\s*[\u2014\u2013]\s*|\s+-\s+|\s*--\s*", " , "),
    (r"&", " and "),
    (r"\+", " and "),
    (r"(?<=[a-z])/(?=[a-z])", " or "),
    # "(both on the table)": a parenthesis that says where things already are
    (r"\(\s*(?:both|all|each|all three|they are|they're|it is|it's|which (?:is|are))\b[^)]*\)", " "),
    (r"\(|\)|\[|\]", " , "),
    (r"\.\.\.+", " . "),
)

_CONTRACTIONS: tuple[tuple[str, str], ...] = (
    (r"\bwon't\b", "will not"), (r"\bcan't\b", "can not"), (r"\bcannot\b", "can not"),
    (r"\bshan't\b", "shall not"), (r"\bain't\b", "is not"),
    (r"n't\b", " not"),
    (r"\b(it|that|there|what|here|who|this)'s\b", r"\1 is"),
    (r"\blet's\b", "let us"),
    (r"'re\b", " are"), (r"'m\b", " am"), (r"'ll\b", " will"), (r"'ve\b", " have"),
    (r"'d\b", " would"),
    # "the lamp's off", "the faucet's dripping": "is" before a state, an adverb or a
    # participle; otherwise a possessive
    (r"'s(?=\s+(?:still|not|now|already|always|again|on|off|open|closed|shut|dirty|clean|"
     r"empty|full|broken|wide|too|so|very|really|left|been|\w+ing|\w+ed|"
     # "the mug's in one of the cupboards": a place or an article after it, never a noun
     r"in|on|inside|under|by|next|behind|near|at|over|here|there|gone|somewhere|probably|down|up|out|"
     r"maybe|a|an|the|"
     # "microwave's fine": an evaluation
     r"fine|ok|okay|good|best|easiest|better|enough)\b)", " is"),
    (r"'s\b", ""),          # possessive: "the robot's arm" -> "the robot arm"
    (r"s'(?=\s|$)", "s"),   # plural possessive
    (r"'", ""),
    # apostrophe-less spellings people type
    (r"\bdont\b", "do not"), (r"\bdoesnt\b", "does not"), (r"\bdidnt\b", "did not"),
    (r"\bcant\b", "can not"), (r"\bisnt\b", "is not"), (r"\barent\b", "are not"),
    (r"\bshouldnt\b", "should not"), (r"\bwouldnt\b", "would not"), (r"\bim\b", "i am"),
    (r"\bthats\b", "that is"), (r"\blets\b", "let us"), (r"\bpls\b|\bplz\b", "please"),
    # chat spellings
    (r"\bu\b", "you"), (r"\bur\b", "your"), (r"\bthx\b|\bthnx\b|\bty\b", "thanks"),
)


@dataclass(frozen=True, slots=True)
class Token:
    """One word, number or punctuation mark, lower-case."""

    text: str
    index: int

    @property
    def is_punct(self) -> bool:
        return self.text in PUNCT

    @property
    def is_number(self) -> bool:
        return self.text.isdigit()


def split_camel(text: str) -> str:
    """``CounterTop`` -> ``Counter Top``, ``TVStand`` -> ``TV Stand``, ``robot2`` -> ``robot 2``."""
    text = re.sub(r"(?<=[a-z])(?=[A-Z])", " ", text)
    text = re.sub(r"(?<=[A-Z])(?=[A-Z][a-rt-z]|[A-Z]s[a-z])", " ", text)   # not "CDs"
    text = re.sub(r"(?<=[A-Za-z])(?=\d)|(?<=\d)(?=[A-Za-z])", " ", text)
    return text


#: a posture before a state says nothing more ("the door hanging open" is open); "leave
#: the microwave going" is running
_POSTURES: tuple[tuple[str, str], ...] = (
    (r"\b(?:hanging|standing|sitting|lying|swinging) (open|ajar|on|off)\b"
     r"(?!\s+(?:the|a|an|my|your|his|her|our|their|this|that|top)\b)", r"\1"),
    (r"\b(leave|leaving|left|keep|keeping|kept)((?: [a-z]+){1,3}) going\b", r"\1\2 running"),
    # "put the lid back down on the hamper": close it (AI2-THOR has no lids apart)
    (r"\b(?:put|pop|stick|drop|get) the lid (?:back )?(?:down )?(?:on|onto) ", "close "),
    (r"\b(close|shut) the lid (?:of|on) ", r"\1 "),
    # "..., with the door shut properly": and shut it
    (r"\bwith the (?:door|lid) (?:shut|closed)\b", "and shut the door"),
    # "so into the fridge with that": put that into the fridge
    (r"\b(into|onto|in|on) the ([a-z]+(?: [a-z]+)?) with (that|it|them|those)\b", r"put \3 \1 the \2"),
    # ", dry or not,": an aside between commas, nothing to do
    (r",\s*[a-z]+ or not\s*,", " "),
    # "one slice of each": one piece is "a" piece (the number would read "slice" as a verb)
    (r"\bone (slice|piece|chunk|wedge|bit|half) of\b", r"a \1 of"),
)


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


def normalize(text: str) -> str:
    """The instruction as lower-case words and punctuation separated by single spaces."""
    text = _BROKEN_OFF.sub(r"\1 , i mean , ", _arrows(text))
    for pattern, repl in _REPLACE:
        text = re.sub(pattern, repl, text)
    text = split_camel(text)
    text = text.lower()
    for pattern, repl in _CONTRACTIONS:
        text = re.sub(pattern, repl, text)
    text = re.sub(r"(?<=[a-z])-(?=[a-z])", " ", text)   # counter-top, well-lit
    for pattern, repl in _POSTURES:
        text = re.sub(pattern, repl, text)
    text = re.sub(r"(?<=\d)(st|nd|rd|th)\b", "", text)   # 2nd -> 2
    text = re.sub(r"([.,;:!?])", r" \1 ", text)
    text = re.sub(r"[^a-z0-9.,;:!? ]+", " ", text)
    return re.sub(r"\s+", " ", text).strip()


def tokenize(text: str) -> list[Token]:
    """Normalise and split into tokens."""
    return [Token(w, i) for i, w in enumerate(normalize(text).split())]
