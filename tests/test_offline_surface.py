"""The surface layer of the offline reader (offline/surface.py, data/surface.json): texting,
speech-to-text transcripts and non-native calques read as the plain requests they are;
a guess kept as an alternative, a cue the scene settles made for certain."""

from __future__ import annotations

import pytest

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.knowledge import KnowledgeDataError, validate
from emboteam.pfg.offline.surface import SurfaceFile, read_surface
from emboteam.pfg.reading import Reading
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

FRONTEND = OfflineFrontend()


def read(text: str, fp: int) -> Reading:
    scene = load_scene(fp)
    team = parse_team("1,2,3")
    return FRONTEND.parse(text, scene, initial_state({"setup": []}, scene, team), team)


def goal(reading: Reading) -> set[str]:
    return {str(c) for c in reading.spec.goal().conditions}


def types(fp: int) -> frozenset[str]:
    return frozenset(load_scene(fp).types())


@pytest.mark.parametrize(("text", "fp", "expected"), [
    # texting: abbreviations and symbols
    ("b4 dinner: brd sliced pls", 1, {"sliced(Bread)"}),
    ("kettle 2 the stove, thx", 1, {"inside(Kettle, StoveBurner)"}),
    ("mug -> coffee tbl pls", 315, {"inside(Mug, CoffeeTable)"}),
    # a transcript: split names, "and" heard as "an"/"end", "off" as "of", "too" as "to"
    ("put the news paper on the sofa an turn the tele vision on", 218,
     {"inside(Newspaper, Sofa)", "switched_on(Television)"}),
    ("put the potato in the micro wave end switch the lights of", 1,
     {"inside(Potato, Microwave)", "switched_off(LightSwitch)"}),
    ("put the sell fone in the draw and close it to", 218, {"inside(CellPhone, Drawer)", "closed(Drawer)"}),
    # non-native calques
    ("Make the curtain of the shower open and give the soap inside the sink.", 415,
     {"open(ShowerCurtain)", "inside(SoapBar, SinkBasin)"}),
    ("Please, make the bread in slices and make the toaster to burn.", 1, {"sliced(Bread)", "switched_on(Toaster)"}),
])
def test_surface_styles_read_as_the_plain_request(text: str, fp: int, expected: set[str]) -> None:
    assert expected <= goal(read(text, fp))


def test_a_homophone_is_rewritten_only_when_the_scene_has_the_thing() -> None:
    # FloorPlan14 has no drawer: "draw" stays a word; FloorPlan1 has one
    assert "drawer" not in read_surface("put the knife in the draw", types(14)).text
    assert read_surface("put the knife in the draw", types(1)).text == "put the knife in the drawer"


def test_an_article_before_a_vowel_stays_an_article() -> None:
    surface = read_surface("the light is never on in an empty room", types(1))
    assert surface.text == "the light is never on in an empty room" and surface.alternative is None


def test_a_split_name_is_joined_only_into_a_thing_of_the_scene() -> None:
    assert "microwave" in read_surface("heat it in the micro wave", types(1)).text
    # no television in FloorPlan1: the words stay as they are
    assert "television" not in read_surface("turn the tele vision on", types(1)).text


def test_a_misheard_in_is_a_guess_the_reader_weighs_not_a_rewrite() -> None:
    text = "put the watch in the drawer in the key chain too"
    surface = read_surface(text, types(218))
    assert surface.text == text                                  # the words as said stay the reading's input
    assert surface.alternative == "put the watch in the drawer and the key chain too"
    assert surface.label == "and_heard"            # priced by priors.json surface/and_heard


def test_an_unpunctuated_transcript_gets_its_clause_breaks_as_an_alternative() -> None:
    text = "grab the mug put it in the coffee machine and switch it on and the potato goes in the fridge"
    surface = read_surface(text, types(1))
    assert surface.alternative is not None
    assert "mug , put it" in surface.alternative and "on , and the potato goes" in surface.alternative


def test_the_compound_of_a_calque_is_made_only_when_it_names_a_scene_type() -> None:
    assert read_surface("open the curtain of the shower", types(415)).text == "open the shower curtain"
    # a measure word is no calque: "a slice of the bread" stays
    assert read_surface("put a slice of the bread in the toaster", types(1)).text == \
        "put a slice of the bread in the toaster"


def test_a_malformed_surface_entry_names_the_file_and_the_entry() -> None:
    bad = {"rewrites": [{"pattern": "(", "replace": "x", "kind": "texting"}], "and_sounds": [],
           "transcript": {"clause_verbs": [], "no_break_after": []}, "calque": {"not_heads": []}}
    with pytest.raises(KnowledgeDataError) as err:
        validate("surface.json", bad, SurfaceFile)
    assert "surface.json" in str(err.value) and "rewrites" in str(err.value)
