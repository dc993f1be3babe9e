"""Normalisation, morphology and spelling correction of the offline parser."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.morphology import correct, edit_distance, singular, verb_lemma
from emboteam.pfg.offline.tagger import tag
from emboteam.pfg.offline.text import normalize, split_camel


@pytest.mark.parametrize(("raw", "clean"), [
    ("Put the Apple in the CounterTop!", "put the apple in the counter top !"),
    ("Don't leave the TVStand's lights on", "do not leave the tv stand lights on"),
    ("apple -> fridge & bread \u2192 toaster", "apple to fridge and bread to toaster"),
    ("it's too dark; won't you help?", "it is too dark ; will not you help ?"),
    ("put the CDs on the well-lit shelf", "put the cds on the well lit shelf"),
    ("robot2 should go", "robot 2 should go"),
])
def test_normalize(raw: str, clean: str) -> None:
    assert normalize(raw) == clean


def test_split_camel_keeps_acronyms() -> None:
    assert split_camel("TVStand") == "TV Stand"
    assert split_camel("ToiletPaperHanger") == "Toilet Paper Hanger"
    assert split_camel("CDs") == "CDs"


def test_edit_distance_counts_transpositions_once() -> None:
    assert edit_distance("frigde", "fridge") == 1
    assert edit_distance("labtop", "laptop") == 1
    assert edit_distance("apple", "apple") == 0
    assert edit_distance("kitten", "sitting") == 3


@pytest.mark.parametrize(("typo", "word"), [
    ("frigde", "fridge"), ("tomatoe", "tomato"), ("labtop", "laptop"), ("letuce", "lettuce"),
    ("microwve", "microwave"), ("televison", "television"), ("trun", "turn"), ("plat", "plate"),
    ("bowel", "bowl"), ("garbege", "garbage"), ("vegetabels", "vegetable"),
])
def test_typos_correct_to_lexicon_words(typo: str, word: str) -> None:
    assert correct(typo) == word


@pytest.mark.parametrize("word", ["there", "three", "quickly", "thinking", "capacitor", "pan",
                                  "pen", "pot"])
def test_ordinary_and_short_words_are_left_alone(word: str) -> None:
    assert correct(word) is None


def test_after_a_determiner_only_nouns_are_candidates() -> None:
    assert correct("bred", True) == "bread"


@pytest.mark.parametrize(("form", "lemma"), [
    ("chopping", "chop"), ("sliced", "slice"), ("fried", "fry"), ("frying", "fry"),
    ("washes", "wash"), ("putting", "put"), ("thrown", "throw"), ("microwaved", "microwave"),
    ("placed", "place"), ("left", "leave"), ("lit", "light"),
])
def test_verb_lemmas(form: str, lemma: str) -> None:
    result = verb_lemma(form)
    assert result is not None and result[0] == lemma


def test_plurals() -> None:
    known = lx.noun_words()
    assert singular("tomatoes", known) == ("tomato", True)
    assert singular("boxes", known) == ("box", True)
    assert singular("apple", known) == ("apple", False)


def test_every_catalogue_type_is_reachable_by_its_own_name() -> None:
    from emboteam.world.catalogue import load_catalogue
    cat = load_catalogue()
    pieces = {p for p, _ in cat.slice_products.values()}
    for name in cat.types:
        if name in pieces:
            continue
        items = [i for i in tag(f"the {name}") if i.noun is not None]
        assert items, name
        concept = items[0].noun.concept  # type: ignore[union-attr]
        assert name in concept.types or name in concept.fallback, (name, concept)


def test_tagger_finds_multiword_units_and_readings() -> None:
    items = tag("then turn off the light switch next to the coffee machine")
    texts = [i.text for i in items]
    assert "light switch" in texts and "next to" in texts and "coffee machine" in texts
    assert items[0].seq == "then"
    assert tag("microwave the potato")[0].verb is not None
    assert tag("robot 3")[0].robot == ("number", 3)
    assert tag("the second robot")[1].robot == ("ordinal", 2)
