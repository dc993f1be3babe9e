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

from emboteam.pfg.offline.idioms import rephrase, spoken

#: punctuation kept as tokens: they delimit sentences and clauses
PUNCT = frozenset(".,;:!?")

_REPLACE: tuple[tuple[str, str], ...] = (
    (r"[\u2018\u2019\u201b`´]", "'"),
    (r"[\u201c\u201d\"]", " "),
    (r"\s*(?:->|=>|\u2192|\u27f6)\s*", " to "),
    # "the cloths on the floor - laundry basket pls": a dash before a last short phrase
    # labels it like a colon
    (r"\s+(?:-|--|\u2013|\u2014)\s+(?=(?:the |a |an |my |into the |in the |on the )?[A-Za-z]+(?: [A-Za-z]+)?"
     r"(?: please| pls| plz| thanks| thx)?\s*(?:[.!?]|$))", " : "),
    # "my book - it's on the desk next to the laptop - can go on the bed": an aside between
    # dashes that says where it is now
    (r"\s[-\u2013\u2014]\s*(?:it's|it is|its|they're|they are|which is|that's)\b[^-\u2013\u2014.!?]{1,60}"
     r"[-\u2013\u2014]\s", " "),
    # bullets: "\u2022 a new roll on the holder \u2022 light off"
    (r"\s*[\u2022\u25cf\u25aa\u2023\u2043]\s*", " ; "),
    (r"\s*[\u2014\u2013]\s*|\s+-\s+|\s*--\s*", " , "),
    (r"&", " and "),
    (r"\+", " and "),
    (r"(?<=[a-z])/(?=[a-z])", " or "),
    # "(both on the table)": a parenthesis that says where things already are
    (r"\(\s*(?:both|all|each|all three|they are|they're|it is|it's|which (?:is|are))\b[^)]*\)", " "),
    # "(a slice, not the whole loaf)", "(the big knife is next to it)", "(dining table)": an
    # aside that corrects, or says where a thing is, is no request (and its nouns are no
    # antecedents for the "it" after it)
    (r"\(\s*[^()]*\bnot\b[^()]*\)", " "),
    (r"\(\s*(?:the|my|a|an|it|they|there|which|that)\b[^()]*\b(?:is|are|s|re|was|were|'s|'re)\b[^()]*\)", " "),
    (r"\(\s*(?:(?:on|in|by|at|from|next to|under|near|beside)\s+)?(?:the\s+|my\s+|a\s+)?(?:[A-Za-z]+\s+){0,5}"
     r"(?:table|counter|countertop|sofa|couch|desk|shelf|bed|dresser|drawer|cabinet|cupboard|sink|floor|fridge|"
     r"armchair|chair|toilet|bath|tub|stand|nightstand|box|basket|bin)\s*\)", " "),
    # "1) lights off 2) ladle in the sink": a number and a bracket open an item of a list
    (r"(?<![\w(])(\d{1,2})\)", r" , \1 , "),
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
    (r"'s(?=\s+(?:still|not|now|already|always|again|just|only|never|all|sat|on|off|open|closed|shut|dirty|clean|"
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
    (r"\bid (?=(?:like|love|prefer|rather|want|appreciate|need|be)\b)", "i would "),
    (r"\bive\b", "i have"), (r"\bwont\b", "will not"), (r"\bhavent\b", "have not"),
    (r"\bthats\b", "that is"), (r"\blets\b", "let us"), (r"\bpls\b|\bplz\b", "please"),
)

#: chat spellings, after the spoken variants of :mod:`~emboteam.pfg.offline.idioms`
_CHAT: tuple[tuple[str, str], ...] = (
    (r"\bu\b", "you"), (r"\bur\b", "your"), (r"\bem\b", "them"), (r"\boutta\b", "out of"), (r"\bthx\b|\bthnx\b|\bty\b", "thanks"),
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
    text = spoken(text)
    for pattern, repl in _CHAT:
        text = re.sub(pattern, repl, text)
    text = re.sub(r"(?<=[a-z])-(?=[a-z])", " ", text)   # counter-top, well-lit
    text = rephrase(text)
    text = re.sub(r"(?<=\d)(st|nd|rd|th)\b", "", text)   # 2nd -> 2
    text = re.sub(r"([.,;:!?])", r" \1 ", text)
    text = re.sub(r"[^a-z0-9.,;:!? ]+", " ", text)
    return re.sub(r"\s+", " ", text).strip()


def tokenize(text: str) -> list[Token]:
    """Normalise and split into tokens."""
    return [Token(w, i) for i, w in enumerate(normalize(text).split())]
