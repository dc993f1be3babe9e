"""The past participle of an English verb, for messages that quote the user's verb
("what should be put?", "what should be chopped?").

Written by hand rather than with an inflection library: messages need one form of a few
hundred household verbs, and the rules plus a short table of irregular verbs cover them
(tests/test_inflection.py)."""

from __future__ import annotations

import re

#: irregular verbs a household instruction uses (base form -> past participle)
IRREGULAR: dict[str, str] = {
    "be": "been", "bring": "brought", "buy": "bought", "catch": "caught", "come": "come", "cut": "cut",
    "do": "done", "draw": "drawn", "drink": "drunk", "drive": "driven", "eat": "eaten", "feed": "fed",
    "find": "found", "freeze": "frozen", "get": "got", "give": "given", "go": "gone", "grind": "ground",
    "hang": "hung", "have": "had", "hide": "hidden", "hold": "held", "keep": "kept", "lay": "laid",
    "leave": "left", "let": "let", "lie": "lain", "light": "lit", "make": "made", "put": "put",
    "read": "read", "ride": "ridden", "run": "run", "see": "seen", "sell": "sold", "send": "sent",
    "set": "set", "shake": "shaken", "shut": "shut", "sit": "sat", "slice": "sliced", "split": "split",
    "spread": "spread", "stand": "stood", "stick": "stuck", "sweep": "swept", "take": "taken",
    "tear": "torn", "throw": "thrown", "wake": "woken", "wear": "worn", "wind": "wound", "wring": "wrung",
    "write": "written",
}

_VOWELS = "aeiou"


def _doubles_final_consonant(verb: str) -> bool:
    """stop -> stopped, chop -> chopped: one syllable ending consonant-vowel-consonant
    (not w, x or y: "fix", "stow", "stay")."""
    return (len(re.findall(r"[aeiouy]+", verb)) == 1 and len(verb) >= 3 and verb[-1] not in _VOWELS + "wxy"
            and verb[-2] in _VOWELS and verb[-3] not in _VOWELS)


def past_participle(verb: str) -> str:
    """``put`` -> ``put``, ``chop`` -> ``chopped``, ``empty`` -> ``emptied``, ``place`` ->
    ``placed``, ``turn on`` -> ``turned on`` (a particle is kept after the verb)."""
    head, sep, rest = verb.strip().partition(" ")
    word = head.lower()
    if word in IRREGULAR:
        done = IRREGULAR[word]
    elif word.endswith("e"):
        done = word + "d"
    elif len(word) > 2 and word.endswith("y") and word[-2] not in _VOWELS:
        done = word[:-1] + "ied"
    elif _doubles_final_consonant(word):
        done = word + word[-1] + "ed"
    else:
        done = word + "ed"
    return done + sep + rest
