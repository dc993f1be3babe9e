"""Token patterns as data (src/emboteam/pfg/offline/data/patterns.json, read by
pfg/offline/patterns.py): what a pattern matches on the tagger's items, and that a malformed
entry is refused at load with an error naming the file and the entry."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from emboteam.pfg.offline.knowledge import DATA_DIR, KnowledgeDataError, WordTables, read
from emboteam.pfg.offline.patterns import Pattern, PatternsFile, PatternTables, Rule, first_rule
from emboteam.pfg.offline.tagger import tag


def _rule(*alternatives: list[dict[str, Any]], **fields: Any) -> Rule:
    return Rule(Pattern.model_validate({"patterns": list(alternatives), **fields}), WordTables("frames"))


def _broken(tmp_path: Path, change: Any) -> Path:
    data = json.loads((DATA_DIR / "patterns.json").read_text())
    change(data)
    path = tmp_path / "patterns.json"
    path.write_text(json.dumps(data))
    return path


def test_the_shipped_patterns_pass_their_schema() -> None:
    assert read(DATA_DIR / "patterns.json", PatternsFile).modules["frames"].rules["aux"]


def test_a_repeated_token_takes_every_word_it_can_then_the_next_constraint_applies() -> None:
    items = tag("I really still need the mug")
    person_then_verb = _rule([{"LOWER": "i"}, {"LOWER": {"IN": ["really", "still"]}, "OP": "*"}, {"VERB": True}])
    assert person_then_verb.end(items, 0) == 4
    assert not person_then_verb.at(tag("I really the mug"), 0)


def test_end_and_optional_tokens() -> None:
    the_noun_alone = _rule([{"LOWER": "please", "OP": "?"}, {"DET": True}, {"NOUN": True}, {"END": True}])
    assert the_noun_alone.end(tag("please the mug"), 0) == 3
    assert the_noun_alone.at(tag("the mug"), 0)
    assert not the_noun_alone.at(tag("the mug please"), 0)


def test_a_value_constraint_needs_the_reading() -> None:
    """``{"PREP": {"NOT_IN": [...]}}``: a preposition other than those, not a word without one."""
    not_in = _rule([{"PREP": {"NOT_IN": ["in"]}}])
    items = tag("put it on the counter")
    assert not_in.at(items, 2)          # "on"
    assert not not_in.at(items, 4)      # "counter": no preposition at all


def test_not_after_and_a_word_table_of_the_module() -> None:
    perfect = _rule([{"LOWER": "have"}, {"VERB": True}], not_after={"IN": ["should"]})
    assert perfect.at(tag("I have gone"), 1)
    assert not perfect.at(tag("should have gone"), 1)
    wished = _rule([{"VERB_LEMMA": {"IN": "@want"}}])      # words.json, tables -> frames -> want
    assert wished.at(tag("I need the mug"), 1)


def test_the_first_rule_of_a_table_decides() -> None:
    table = (_rule([{"NEG": True}], then="neg"), _rule([{"LOWER": "not"}], then="word"))
    rule = first_rule(table, tag("not the mug"), 0)
    assert rule is not None and rule.then == "neg"
    assert first_rule(table, tag("the mug"), 0) is None


def test_a_constraint_spacy_and_the_tagger_lack_names_the_pattern(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["modules"]["frames"]["patterns"]["nobody"]["patterns"][0][0] = {"LOWERR": "nobody"}
    with pytest.raises(KnowledgeDataError) as err:
        read(_broken(tmp_path, change), PatternsFile)
    assert err.value.file == "patterns.json"
    assert err.value.entry.startswith("modules -> 'frames' -> 'patterns' -> 'nobody' -> 'patterns'[0][0]")
    assert "LOWERR" in err.value.entry


def test_an_operator_spacy_lacks_is_refused(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["modules"]["clauses"]["rules"]["new_clause"][2]["patterns"][0][1]["OP"] = "{2}"
    with pytest.raises(KnowledgeDataError, match=r"^patterns\.json: modules -> 'clauses' -> 'rules' -> 'new_clause'\[2\].*'OP'"):
        read(_broken(tmp_path, change), PatternsFile)


def test_an_empty_pattern_is_refused(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["modules"]["frames"]["patterns"]["need_to"]["patterns"] = [[]]
    with pytest.raises(KnowledgeDataError, match=r"^patterns\.json: .*'need_to'.*at least one token"):
        read(_broken(tmp_path, change), PatternsFile)


def test_a_pattern_a_module_needs_and_the_file_lacks_is_named() -> None:
    with pytest.raises(KnowledgeDataError, match=r"^patterns\.json: modules -> 'frames' -> patterns -> 'no_such': missing"):
        PatternTables("frames").pattern("no_such")
    with pytest.raises(KnowledgeDataError, match=r"^patterns\.json: modules -> 'frames' -> rules -> 'no_such': missing"):
        PatternTables("frames").table("no_such")


def test_a_word_table_a_pattern_names_and_the_words_file_lacks_is_named() -> None:
    with pytest.raises(KnowledgeDataError, match=r"^words\.json: tables -> 'frames' -> 'no_such_table': missing"):
        _rule([{"LOWER": {"IN": "@no_such_table"}}])
    with pytest.raises(KnowledgeDataError, match=r"^patterns\.json: @lexicon\.no_such: the lexicon has no such word list"):
        _rule([{"LOWER": {"IN": "@lexicon.no_such"}}])


def test_a_search_window_finds_the_pattern_a_few_words_on() -> None:
    goes = _rule([{"VERB_ACT": "go"}, {"PREP": {"IN": ["in", "on"]}}], within=[1, 2])
    assert goes.end(tag("they both go in the drawer"), 0) == 4
    assert not goes.at(tag("they go in the drawer"), 1)        # "in" is no verb of going
    assert not goes.at(tag("the mug and the cup go in the sink"), 0)    # "go" too far on
