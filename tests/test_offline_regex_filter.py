"""The needle test that skips a normalisation rewrite (pfg/offline/regex_filter.py) must
never skip one that would have changed the text: a skipped rewrite that matches would be a
silently different reading."""

from __future__ import annotations

import re

import pytest

from emboteam.pfg.offline import idioms, text
from emboteam.pfg.offline.knowledge import CompiledRewrite, apply_rewrites
from emboteam.pfg.offline.regex_filter import needle_groups, needles

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


def _all_rules() -> list[CompiledRewrite]:
    return [*text._REPLACE, *text._CONTRACTIONS, *text._CHAT, *idioms.SPOKEN, *idioms.PHRASINGS]


def _has_all(groups: tuple[frozenset[str], ...], probe: str) -> bool:
    return all(any(n in probe for n in group) for group in groups)


@pytest.mark.parametrize("sentence", SENTENCES)
def test_skipped_rewrites_would_not_have_matched(sentence: str) -> None:
    # every stage's input, as normalize() feeds it: a skipped rule finds nothing there
    for stage in (sentence, text.split_camel(sentence).lower()):
        current = stage
        for pattern, repl, groups, blind in _all_rules():
            probe = current.lower() if blind else current
            if groups and (current.isascii() or not blind) and not _has_all(groups, probe):
                assert pattern.search(current) is None, pattern.pattern
            current = pattern.sub(repl, current)


@pytest.mark.parametrize("sentence", SENTENCES)
@pytest.mark.parametrize("case", [str.lower, str])
def test_filtered_rewrites_give_the_unfiltered_text(sentence: str, case: object) -> None:
    rules = tuple(_all_rules())
    unfiltered = tuple((p, r, (), False) for p, r, _, _ in rules)
    typed = case(sentence)  # type: ignore[operator]
    assert apply_rewrites(rules, typed) == apply_rewrites(unfiltered, typed)


def test_every_part_of_a_rule_is_a_group() -> None:
    # "the" is in most texts: the rule is still skipped when "toilet" is not
    groups = needle_groups(re.compile(r"\b(?:lift|raise) the (loo|toilet) (?:lid|seat)\b"))
    assert frozenset({"loo", "toilet"}) in groups or frozenset({" loo", " toilet"}) in groups
    assert not _has_all(groups, "lift the lid of the box")
    assert _has_all(groups, "lift the toilet seat")


def test_case_blind_groups_are_lower_case_and_ascii() -> None:
    groups = needle_groups(re.compile(r"(?i)\bthe Kettle\b"))
    assert groups and all(n == n.lower() for group in groups for n in group)
    assert _has_all(groups, "Put THE KETTLE on".lower())
    assert needle_groups(re.compile(r"(?i)caf\u00e9")) == ()


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
