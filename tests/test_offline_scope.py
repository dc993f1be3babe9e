"""Scope constructions of the offline reader (issue 25, scope25), on sentences written for
these tests: accented words kept whole, household words of other languages read in English
(pfg/offline/foreign.py, data/foreign.json), checklist ticks and crosses (data/surface.json,
kind ``checklist``), and an undo that sends a moved thing back where it came from
(doubts/scope.py, rule_words.json ``undo``)."""

from __future__ import annotations

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.foreign import translate
from emboteam.pfg.offline.surface import read_surface
from emboteam.pfg.offline.text import fold_accents, normalize
from emboteam.pfg.reading import Reading
from offline_reading import read_offline

_READER = OfflineFrontend()


def read(text: str, fp: int) -> Reading:
    return read_offline(_READER, text, f"FloorPlan{fp}")


def first(reading: Reading) -> set[str]:
    return {str(c) for c in reading.candidates[0].goals}


# accents: a letter with an accent is its letter, never a cut in the word
def test_accented_letters_fold_to_their_letters_and_symbols_stay() -> None:
    assert fold_accents("Le café, la crème brûlée, straße") == "Le cafe, la creme brulee, strasse"
    assert fold_accents("½ of them ✓") == "½ of them ✓"
    assert "jalapeno" in normalize("Slice the jalapeño.").split()


# other languages: their household words in English; joining words only before them
def test_foreign_nouns_states_and_their_articles_read_in_english() -> None:
    assert translate(["la", "bougie", "allumee"]) == ["the", "candle", "on"]
    assert translate(["die", "Kerze"]) == ["the", "candle"]
    assert translate(["la", "tenda", "della", "doccia"]) == ["the", "curtain", "of the", "shower"]


def test_english_words_that_are_also_foreign_articles_stay_english() -> None:
    words = ["the", "plants", "will", "die", "without", "la", "water"]
    assert translate(words) == words


def test_a_mixed_language_request_reads_as_its_english() -> None:
    text = read_surface("Bitte: das Buch goes into la caja, und die Lampe aus.", ()).text
    assert normalize(text).startswith("please : the book goes into the box , and the lamp off")
    goals = first(read("Por favor, el libro goes into the caja. Also the lámpara de pie apagada.", 201))
    assert "inside(Book, Box)" in goals


# checklists: a crossed-out line's thing is left as it is; ticks and boxes open items
def test_a_crossed_out_checklist_line_leaves_its_thing_where_it_is() -> None:
    text = "Tidy up list:\n☐ the book onto the sofa\n✗ the laptop, it stays\n☐ keys into the box"
    goals = first(read(text, 201))     # FloorPlan201: the laptop lies on the dining table
    assert {"inside(Book, Sofa)", "inside(KeyChain, Box)"} <= goals
    assert not {g for g in goals if g.startswith("inside(Laptop") and g != "inside(Laptop, DiningTable)"}


def test_checklist_marks_become_item_breaks() -> None:
    said = normalize(read_surface("list\n✓ mug to the sink\n✗ the kettle\nplate ✗", ()).text)
    assert "; mug to the sink ; ; leave the kettle" in said
    assert said.endswith("plate stays ;")


# undo: a thing moved from one place to another goes back where it came from or lived
# (FloorPlan201: the book and the laptop lie on the dining table)
def test_an_undo_sends_a_moved_thing_back_to_where_it_came_from() -> None:
    goals = first(read("The kids moved the book from the sofa to the dining table yesterday. Put it back, please.", 201))
    assert "inside(Book, Sofa)" in goals and "inside(Book, DiningTable)" not in goals


def test_where_a_thing_lived_before_it_was_moved_is_its_way_back() -> None:
    reading = read("Undo the tidying: the laptop lived on the sofa before someone carried it over to the dining table.", 201)
    assert "inside(Laptop, Sofa)" in first(reading)
    assert any(d.kind == "undo" for d in reading.doubts)


def test_no_undo_asked_no_way_back() -> None:
    reading = read("Carry the book from the dining table over to the sofa.", 201)
    assert "inside(Book, Sofa)" in first(reading)
    assert not any(d.kind == "undo" for d in reading.doubts)


# fractions: a fraction sign is its words, so a fraction of a said number is a count
def test_a_fraction_sign_reads_as_its_words() -> None:
    assert normalize("Move ½ of the six plates") == normalize("Move half of the six plates") == "move three plates"
    assert "1 half" not in normalize("1½ cups")


# self-corrections: the reason given for taking a place back is an aside
def test_a_reason_between_the_taken_back_place_and_the_corrected_one_is_an_aside() -> None:
    goals = first(read("Put the vase on the shelf - no, not the shelf, it would fall off - the coffee table.", 201))
    assert "inside(Vase, CoffeeTable)" in goals and "inside(Vase, Shelf)" not in goals
