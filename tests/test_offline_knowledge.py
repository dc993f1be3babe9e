"""The offline parser's knowledge files (src/emboteam/pfg/offline/data/*.json): each is
checked against its schema when loaded, and a malformed entry is one clear error that
names the file and the entry, so a phrasing taught wrongly is found at once."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from emboteam.errors import EmboTeamError
from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.acts import ActsFile
from emboteam.pfg.offline.constructions import ConstructionsFile
from emboteam.pfg.offline.frames import PreambleFile
from emboteam.pfg.offline.idioms import IdiomsFile
from emboteam.pfg.offline.knowledge import DATA_DIR, KnowledgeDataError, WordsFile, WordTables, read
from emboteam.pfg.offline.lexicon import LexiconFile
from emboteam.pfg.offline.surface import SurfaceFile
from emboteam.pfg.offline.text import TextFile


def _broken(tmp_path: Path, name: str, change: Any) -> Path:
    """A copy of the shipped file ``name`` with one entry changed by ``change(data)``."""
    data = json.loads((DATA_DIR / name).read_text())
    change(data)
    path = tmp_path / name
    path.write_text(json.dumps(data))
    return path


@pytest.mark.parametrize(("name", "schema"), [("lexicon.json", LexiconFile), ("idioms.json", IdiomsFile),
                                              ("text.json", TextFile), ("words.json", WordsFile),
                                              ("preamble.json", PreambleFile), ("acts.json", ActsFile),
                                              ("constructions.json", ConstructionsFile),
                                              ("surface.json", SurfaceFile)])
def test_every_shipped_knowledge_file_passes_its_schema(name: str, schema: Any) -> None:
    read(DATA_DIR / name, schema)


def test_an_unknown_act_names_the_file_and_the_verb_group(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["verbs"][0]["act"] = "plaice"
    with pytest.raises(KnowledgeDataError) as err:
        read(_broken(tmp_path, "lexicon.json", change), LexiconFile)
    assert isinstance(err.value, EmboTeamError)
    assert err.value.file == "lexicon.json"
    assert err.value.entry.startswith("verbs[0] (put, place, move, ...)") and err.value.entry.endswith("-> 'act'")
    assert "plaice" in str(err.value) or "place" in str(err.value)


def test_a_noun_with_an_unknown_concept_names_the_noun(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["nouns"]["veggie"] = {"concept": "vegetabels"}
    with pytest.raises(KnowledgeDataError, match=r"^lexicon\.json: .*'veggie'.*no concept 'vegetabels'"):
        read(_broken(tmp_path, "lexicon.json", change), LexiconFile)


def test_a_noun_that_names_nothing_is_refused(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["nouns"]["settee"] = {"fallback": ["Sofa"]}
    with pytest.raises(KnowledgeDataError, match=r"^lexicon\.json: nouns -> 'settee': .*exactly one"):
        read(_broken(tmp_path, "lexicon.json", change), LexiconFile)


def test_a_bad_regular_expression_names_the_rule_by_its_pattern(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["phrasings"][3]["pattern"] = r"\bput the lid (back"
    with pytest.raises(KnowledgeDataError) as err:
        read(_broken(tmp_path, "idioms.json", change), IdiomsFile)
    assert err.value.file == "idioms.json"
    assert err.value.entry.startswith("phrasings[3] ('\\\\bput the lid (back'")
    assert "no regular expression" in err.value.problem


def test_a_replacement_that_refers_to_a_missing_group_is_refused(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["chat"][0]["replace"] = r"\2"
    with pytest.raises(KnowledgeDataError, match=r"^text\.json: chat\[0\].*refers to group 2"):
        read(_broken(tmp_path, "text.json", change), TextFile)


def test_a_misspelt_table_name_is_an_error_not_ignored(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["kept_inn"] = data.pop("kept_in")
    with pytest.raises(KnowledgeDataError, match=r"^idioms\.json: kept_in"):
        read(_broken(tmp_path, "idioms.json", change), IdiomsFile)


def test_a_file_that_is_no_json_names_the_line(tmp_path: Path) -> None:
    path = tmp_path / "idioms.json"
    path.write_text('{"spoken": [\n  {"pattern": "x" "replace": "y"}\n]}')
    with pytest.raises(KnowledgeDataError, match=r"^idioms\.json: line 2 column \d+: not JSON"):
        read(path, IdiomsFile)


def test_a_word_table_in_capitals_names_the_module_and_the_table(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["tables"]["cues"]["excluding"].append("Except")
    with pytest.raises(KnowledgeDataError, match=r"^words\.json: .*'cues' -> 'excluding': 'Except' is not a lower-case"):
        read(_broken(tmp_path, "words.json", change), WordsFile)


def test_a_table_a_module_needs_and_the_file_lacks_is_named() -> None:
    with pytest.raises(KnowledgeDataError, match=r"^words\.json: tables -> 'cues' -> 'no_such_table': missing"):
        WordTables("cues").set("no_such_table")


def test_a_preamble_pattern_that_does_not_compile_is_named_by_its_index(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["preamble"][2]["pattern"] = "(?:be )?(?:able|willing to"
    with pytest.raises(KnowledgeDataError, match=r"^preamble\.json: preamble\[2\]: .*no regular expression"):
        read(_broken(tmp_path, "preamble.json", change), PreambleFile)


def test_a_noun_of_a_type_the_catalogue_lacks_is_named(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(lx._NOUNS, "settee", lx._obj("Sofaa"))
    lx.nouns.cache_clear()
    try:
        with pytest.raises(KnowledgeDataError, match=r"^lexicon\.json: nouns -> 'settee': no object type 'Sofaa'"):
            lx.nouns()
    finally:
        lx.nouns.cache_clear()


def test_a_dish_with_an_unknown_goal_names_the_dish(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["dishes"]["coffee"]["conditions"][1]["predicate"] = "warm"
    with pytest.raises(KnowledgeDataError, match=r"^acts\.json: dishes -> 'coffee' -> 'conditions'\[1\].*'predicate'"):
        read(_broken(tmp_path, "acts.json", change), ActsFile)


def test_a_state_without_a_rule_is_named(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        del data["states"]["toasted"]
    with pytest.raises(KnowledgeDataError, match=r"^acts\.json: states: no rule for 'toasted'"):
        read(_broken(tmp_path, "acts.json", change), ActsFile)


def test_a_described_pattern_naming_an_unknown_piece_is_named(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["described"]["kept_in"][1] = "{keepin} with"
    with pytest.raises(KnowledgeDataError, match=r"^idioms\.json: described -> kept_in\[1\]: no piece 'keepin'"):
        read(_broken(tmp_path, "idioms.json", change), IdiomsFile)


def test_a_dish_of_a_type_the_catalogue_lacks_is_named(monkeypatch: pytest.MonkeyPatch) -> None:
    from emboteam.pfg.offline import acts
    monkeypatch.setitem(acts.DISHES, "stew", acts.Dish.model_validate(
        {"served_in": "StewPot", "conditions": [{"predicate": "cooked"}]}))
    with pytest.raises(KnowledgeDataError, match=r"^acts\.json: dishes -> 'stew': no object type 'StewPot'"):
        acts._check_types()


def test_a_light_act_that_is_no_act_names_the_table(tmp_path: Path) -> None:
    def change(data: dict[str, Any]) -> None:
        data["light_acts"].append("scrubb")
    with pytest.raises(KnowledgeDataError, match=r"^constructions\.json: light_acts"):
        read(_broken(tmp_path, "constructions.json", change), ConstructionsFile)


def test_the_doubts_data_files_are_checked_by_their_schema_and_name_the_entry(tmp_path: Path) -> None:
    """The affordances and sound-alike tables of the points of doubt are knowledge files too:
    a wrong value is refused at load, naming the file and the entry."""
    from emboteam.pfg.offline.doubts.affordances import AFFORDANCES_FILE, load_affordances
    from emboteam.pfg.offline.doubts.sound_alike import SOUND_FILE, load_sound_alike

    assert load_affordances().place and load_sound_alike().rewrites
    sound = json.loads(SOUND_FILE.read_text())
    sound["max_join"] = "two"
    (tmp_path / "sound_alike.json").write_text(json.dumps(sound))
    with pytest.raises(KnowledgeDataError, match=r"^sound_alike\.json: max_join"):
        load_sound_alike(tmp_path / "sound_alike.json")
    afford = json.loads(AFFORDANCES_FILE.read_text())
    del afford["switch"]
    (tmp_path / "affordances.json").write_text(json.dumps(afford))
    with pytest.raises(KnowledgeDataError, match=r"^affordances\.json: .*switch"):
        load_affordances(tmp_path / "affordances.json")
