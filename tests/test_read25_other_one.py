"""One of two, the other one, joining the others (issue 25, other25): a thing of a type the
scene has several of, kept or moved against the others ("of the two rolls, one stays and the
spare goes ..."), or sent where the others of its kind are ("joins the other one", "with the
others"). The sentences are new, written for these tests (FloorPlan307: three CDs, two on the
desk, one on the side table; FloorPlan407: a roll on the counter, one on the floor;
FloorPlan409: a roll in a drawer, one in the bin; FloorPlan401/419: two rolls together)."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.joins import JoinWords, load_join_words
from emboteam.pfg.offline.knowledge import KnowledgeDataError, validate
from offline_reading import goal_of

FRONTEND = OfflineFrontend()


def goal(text: str, fp: int) -> set[str]:
    return goal_of(FRONTEND, text, fp)


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("The odd CD out should join the other two, please.", 307, {"inside(3 of CD, Desk)"}),
    ("That roll lying on the floor can join the other one.", 407, {"inside(2 of ToiletPaper, CounterTop)"}),
    ("Fish the roll out of the bin and put it in a drawer with the other one.", 409,
     {"inside(2 of ToiletPaper, Drawer)"}),
])
def test_the_one_goes_where_the_others_are(text: str, fp: int, expected: set[str]) -> None:
    got = goal(text, fp)
    assert expected <= got
    assert not any(c.startswith("inside(ToiletPaper, Floor)") for c in got)


@pytest.mark.parametrize(("text", "fp"), [
    ("Of the two rolls on the toilet, one remains where it is and the spare one goes into the drawer.", 419),
    ("Both rolls are on the toilet: one of them remains there, the other goes in the drawer.", 419),
])
def test_the_kept_one_said_first(text: str, fp: int) -> None:
    got = goal(text, fp)
    assert {"inside(ToiletPaper, Drawer)", "inside(ToiletPaper, Toilet)"} <= got
    assert "inside(2 of ToiletPaper, Toilet)" not in got


def test_a_thing_with_the_others_named_with_no_several_is_left_as_read() -> None:
    # one racket: "with the other stuff" finds no others of its kind, nothing to join
    assert "inside(TennisRacket, Bed)" in goal("The racket goes on the bed with the other stuff.", 307)


def test_the_join_words_are_checked_at_load() -> None:
    words = load_join_words()
    assert "joins" in words.joining and "other" in words.others
    with pytest.raises(KnowledgeDataError):
        validate("joins.json", {"about": "", "joining": ["joins"], "others": ["other"]}, JoinWords)
