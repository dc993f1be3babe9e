"""Things singled out by comparison, "the other one" kept, and the one excepted from a
quantified whole, resolved against the scene (pfg/offline/doubts/compare.py, others.py,
scope.py), on sentences written for these tests (not round tasks). Masses from the
scenes: FloorPlan1 a cup (0.4, in a cabinet) and a mug (1.0, on the counter), a pan
(0.67) and a pot (0.57) on the counters; FloorPlan310 a bat (0.9), a basketball (0.6) and a
racket (0.31) on the floor; FloorPlan224 a desk lamp and a floor lamp, both on;
FloorPlan426 two toilet rolls on the toilet; FloorPlan409 a roll in a drawer, one in the bin."""

from __future__ import annotations

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.reading import Reading
from offline_reading import read_offline

_READER = OfflineFrontend()


def read(text: str, fp: int) -> Reading:
    return read_offline(_READER, text, f"FloorPlan{fp}")


def goals(text: str, fp: int) -> set[str]:
    return {str(c) for c in read(text, fp).spec.goal().conditions}


def test_the_heavier_of_a_named_pair_is_the_one_of_greater_mass() -> None:
    got = goals("Of the cup and the mug, the heavier one belongs in the fridge.", 1)
    assert "inside(Mug, Fridge)" in got and "inside(Cup, Fridge)" not in got


def test_the_lighter_of_a_named_pair_is_the_one_of_least_mass() -> None:
    got = goals("Of the pan and the pot, put the lighter one in the sink.", 1)
    assert "inside(Pot, SinkBasin)" in got and "inside(Pan, SinkBasin)" not in got


def test_a_comparative_among_the_things_a_place_holds() -> None:
    # no type named: the things on the floor, the heaviest that can be carried
    got = goals("The biggest of the things lying on the floor goes onto the bed.", 310)
    assert "inside(BaseballBat, Bed)" in got
    assert "inside(TennisRacket, Bed)" not in got and "inside(BasketBall, Bed)" not in got


def test_the_others_of_the_pool_stay_when_a_keeping_clause_follows() -> None:
    got = goals("From the sports things on the floor, the smallest goes on the desk; the rest can stay.", 310)
    assert "inside(TennisRacket, Desk)" in got
    assert {"inside(BaseballBat, Floor)", "inside(BasketBall, Floor)"} <= got


def test_the_scene_pick_is_offered_with_the_other_as_a_candidate() -> None:
    reading = read("Of the cup and the mug, the heavier one belongs in the fridge.", 1)
    readings = [{str(c) for c in cand.goals} for cand in reading.candidates]
    assert any("inside(Cup, Fridge)" in g for g in readings[1:])


def test_one_excepted_from_a_quantified_whole_by_a_word_of_its_name() -> None:
    got = goals("Every lamp in the room apart from the floor one should be switched off.", 224)
    assert "switched_off(DeskLamp)" in got and "switched_off(FloorLamp)" not in got


def test_the_other_one_is_fine_where_it_is_keeps_it() -> None:
    got = goals("One of the two rolls on the toilet goes on the holder; the other one is fine.", 426)
    assert {"inside(ToiletPaper, ToiletPaperHanger)", "inside(ToiletPaper, Toilet)"} <= got
    assert "inside(2 of ToiletPaper, ToiletPaperHanger)" not in got


def test_the_one_already_where_the_other_goes_counts_with_it() -> None:
    got = goals("Rolls go in a drawer, so fish the one out of the bin; the one already in the drawer is fine.", 409)
    assert "inside(2 of ToiletPaper, Drawer)" in got
