"""The needle test that skips a normalisation rewrite (pfg/offline/regex_filter.py) must
never skip one that would have changed the text: a skipped rewrite that matches would be a
silently different reading."""

from __future__ import annotations

import re

import pytest

from emboteam.pfg.offline import idioms, text
from emboteam.pfg.offline.knowledge import apply_rewrites
from emboteam.pfg.offline.regex_filter import needles

#: sentences written for this test, with the spoken, chat and contracted forms the
#: rewrites are for (not copied from any round)
SENTENCES = [
    "Umm, could u pls pop the kettle on the hob & make me a cuppa?",
    "Don't forget - the blinds've gotta be down b4 the film starts!!",
    "erm the towel thingy, the one that's hanging in the bathroom, it goes in the hamper",
    "I'd kill for a hot chocolate rn... mug's in the cupboard next 2 the fridge",
    "Lamp -> off, TV -> off, laptop -> closed, the candle can stay lit",
    "The bread's gone stale, chuck it in the bin & grab the 2nd loaf from the pantry",
    "Could the plates be put away, and the cutlery too (forks in the drawer)?",
    "‘Put the mug in the sink’ — that’s all I’m asking, mate",
    "my daughter left her teddy on the stairs again, can someone pop it on her bed",
    "if the oven's still on when you're done, switch it off, ta",
]


def _all_rules() -> list[tuple[re.Pattern[str], str, frozenset[str] | None]]:
    return [*text._REPLACE, *text._CONTRACTIONS, *text._CHAT, *idioms.SPOKEN, *idioms.PHRASINGS]


@pytest.mark.parametrize("sentence", SENTENCES)
def test_skipped_rewrites_would_not_have_matched(sentence: str) -> None:
    # every stage's input, as normalize() feeds it: a skipped rule finds nothing there
    for stage in (sentence, text.split_camel(sentence).lower()):
        current = stage
        for pattern, repl, required in _all_rules():
            if required is not None and not any(n in current for n in required):
                assert pattern.search(current) is None, pattern.pattern
            current = pattern.sub(repl, current)


@pytest.mark.parametrize("sentence", SENTENCES)
def test_filtered_rewrites_give_the_unfiltered_text(sentence: str) -> None:
    rules = _all_rules()
    unfiltered = tuple((p, r, None) for p, r, _ in rules)
    lowered = sentence.lower()
    assert apply_rewrites(rules, lowered) == apply_rewrites(unfiltered, lowered)


@pytest.mark.parametrize(("pattern", "text_with", "text_without"), [
    (r"\b(the|a) (?:cup|mug) of tea\b", "a mug of tea please", "a mug of coffee please"),
    (r"(?:ab)+c", "xxababc", "xxac"),
    (r"\bcolou?r\b", "what colour", "what shade"),
])
def test_needles_are_in_every_match(pattern: str, text_with: str, text_without: str) -> None:
    compiled = re.compile(pattern)
    found = needles(compiled)
    assert found is not None
    assert compiled.search(text_with) and any(n in text_with for n in found)
    assert not compiled.search(text_without)


@pytest.mark.parametrize("pattern", [r"(?i)tea", r"x*", r"(?:a|)b?", r"(?<=a)(?=b)"])
def test_no_needles_when_a_match_needs_no_fixed_string(pattern: str) -> None:
    assert needles(re.compile(pattern)) is None
