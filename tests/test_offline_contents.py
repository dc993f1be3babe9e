"""Things named as a receptacle's contents, or as the other instances of a kind, resolved
against the scene (pfg/offline/doubts/contents.py, others.py), on sentences written for
these tests (not round tasks). FloorPlan312: the desk holds a book, keys, a pen and a
pencil, the shelf a phone and a card; FloorPlan24: the counter by the sink a bowl, knives,
a pan, the soap bottle and the toaster; FloorPlan206: three statues (coffee table, TV
stand, a shelf), the coffee table also holds a bowl; FloorPlan5: the sink basin a cup, an
egg and a lettuce."""

from __future__ import annotations

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.reading import Reading
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

_READER = OfflineFrontend()


def read(text: str, fp: int) -> Reading:
    scene = load_scene(f"FloorPlan{fp}")
    team = parse_team("1,2,3")
    return _READER.parse(text, scene, initial_state({}, scene, team), team)


def goals(text: str, fp: int) -> set[str]:
    return {str(c) for c in read(text, fp).spec.goal().conditions}


def test_an_emptying_verb_in_any_form_clears_its_receptacle_but_the_excepted() -> None:
    got = goals("Robot 2 clears the desk into the drawer - all of it except the pen and the keys.", 312)
    assert {"inside(Book, Drawer)", "inside(Pencil, Drawer)"} <= got
    assert "inside(Pen, Drawer)" not in got and "inside(KeyChain, Drawer)" not in got


def test_a_post_positive_exception_keeps_the_thing_where_it_is() -> None:
    got = goals("Whatever is on the shelf goes in the drawer, the phone excepted.", 312)
    assert "inside(CreditCard, Drawer)" in got
    assert "inside(CellPhone, Drawer)" not in got


def test_an_excepted_thing_with_its_own_place_goes_there() -> None:
    got = goals("Everything in the sink goes in the fridge except the egg, which goes on the counter.", 5)
    assert {"inside(Cup, Fridge)", "inside(Lettuce, Fridge)", "inside(Egg, CounterTop)"} <= got
    assert "inside(Egg, Fridge)" not in got


def test_empty_it_means_the_place_not_its_landmark_and_what_cannot_go_there_stays() -> None:
    # "the counter by the sink": the counter; knives cannot go in a cabinet (AI2-THOR's
    # placement rules), so they are no part of what is moved
    got = goals("The counter by the sink is cluttered - empty it into the cabinet, all but the toaster and the soap.",
                24)
    assert {"inside(Bowl, Cabinet)", "inside(Pan, Cabinet)"} <= got
    assert "inside(SoapBottle, Cabinet)" not in got and "inside(Knife, Cabinet)" not in got


def test_up_there_refers_to_the_place_named_before() -> None:
    got = goals("The coffee table is a mess - clear it? Everything on there goes in the box, apart from the bowl.", 206)
    assert "inside(Statue, Box)" in got and "inside(Bowl, Box)" not in got


def test_a_list_after_a_chore_is_no_contents() -> None:
    reading = read("Clear the desk: the pen goes in the drawer.", 312)
    assert not any(d.kind == "contents" for d in reading.doubts)


def test_the_one_on_a_place_moves_and_the_other_ones_stay() -> None:
    got = goals("The statue on the coffee table goes in the box and the other ones stay where they are.", 206)
    # by type: with the other two kept where they are, only the coffee table's can move
    assert {"inside(Statue, Box)", "inside(Statue, TVStand)", "inside(Statue, Shelf)"} <= got
    assert not any(g.startswith("inside(2 of Statue, Box)") for g in got)


def test_the_other_statues_named_by_their_kind_stay_put() -> None:
    got = goals("Put the statue from the TV stand in the box; the other statues stay put.", 206)
    assert {"inside(Statue, Box)", "inside(Statue, CoffeeTable)", "inside(Statue, Shelf)"} <= got


def test_the_one_on_a_place_that_stays_keeps_it_there() -> None:
    # FloorPlan412: one roll in each of two cabinets (1 and 3)
    got = goals("Put a toilet roll on the counter. The one in the other cabinet stays where it is.", 412)
    assert {"inside(ToiletPaper, CounterTop)", "inside(ToiletPaper, Cabinet)"} <= got


def test_no_other_ones_without_a_keeping_word() -> None:
    reading = read("Put the statue from the TV stand in the box and the other one on the sofa.", 206)
    assert not any(d.kind == "others" for d in reading.doubts)


def test_a_quantified_pronoun_takes_up_the_counted_things_said_before() -> None:
    # FloorPlan412: two toilet rolls, one in each of two cabinets
    got = goals("The toilet rolls in the cabinets, both of them you put on the counter.", 412)
    assert "inside(2 of ToiletPaper, CounterTop)" in got
    assert not any("Cabinet)" in g and "ToiletPaper" in g for g in got)


def test_a_thing_said_to_stay_or_sent_elsewhere_later_is_no_part_of_the_cleared_set() -> None:
    got = goals("Clear the desk into the drawer - the keys stay. The pen goes on the shelf.", 312)
    assert {"inside(Book, Drawer)", "inside(Pencil, Drawer)", "inside(Pen, Shelf)"} <= got
    assert "inside(KeyChain, Drawer)" not in got and "inside(Pen, Drawer)" not in got


def test_a_source_of_several_instances_offers_each_as_an_alternative() -> None:
    # FloorPlan5: three shelves (a statue; two vases; one vase): "the shelf" is uncertain
    reading = read("Everything on the shelf goes on the counter.", 5)
    sets = [{str(c) for c in ch.add} for d in reading.doubts if d.kind == "contents" for ch in d.choices[1:]]
    assert {"inside(2 of Vase, CounterTop)"} in sets and {"inside(Statue, CounterTop)"} in sets
    assert any(s in sets for s in ({"inside(Vase, CounterTop)"},))
