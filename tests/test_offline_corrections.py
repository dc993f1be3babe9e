"""Self-corrections (pfg/offline/corrections.py): the correcting part names a slot (the
place, the thing, a list member taken out or kept, the state, a clause said again) and only
that slot of what came before is replaced; the rest of the earlier request stands. Where
the slot is in doubt the other reading is a candidate of kind ``correction``. Sentences
written for these tests (not taken from a development round)."""

from __future__ import annotations

import pytest

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.reading import Reading
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

FRONTEND = OfflineFrontend()


def read(text: str, fp: int) -> Reading:
    scene = load_scene(fp)
    team = parse_team("1,2")
    return FRONTEND.parse(text, scene, initial_state({"setup": []}, scene, team), team)


def goal(text: str, fp: int) -> set[str]:
    return {str(c) for c in read(text, fp).spec.goal().conditions}


@pytest.mark.parametrize(("text", "fp", "expected"), [
    # the place
    ("Put the mug in the cabinet, no wait, in the sink.", 1, {"inside(Mug, SinkBasin)"}),
    ("Put the alarm clock on the desk, or rather on the dresser.", 301, {"inside(AlarmClock, Dresser)"}),
    ("Put the keychain in the box, actually no, on the coffee table.", 201, {"inside(KeyChain, CoffeeTable)"}),
    # the thing
    ("Throw the egg in the bin - sorry, I mean the potato.", 1, {"inside(Potato, GarbageCan)"}),
    ("Turn on the floor lamp - no, actually, the desk lamp.", 201, {"switched_on(DeskLamp)"}),
    # a member taken out, the list cut, a member swapped
    ("Put the pen, the pencil and the CD in the drawer, oh wait, not the CD.", 301,
     {"inside(Pen, Drawer)", "inside(Pencil, Drawer)"}),
    ("Put the apple and the tomato in the fridge - no, only the tomato.", 1, {"inside(Tomato, Fridge)"}),
    ("Put the cup and the mug in the sink. Wait, no, the bowl instead of the mug.", 5,
     {"inside(Cup, SinkBasin)", "inside(Bowl, SinkBasin)"}),
    # the state
    ("Switch the TV off, sorry, on.", 201, {"switched_on(Television)"}),
    # a clause said again: by a pronoun, or naming the thing it takes out
    ("Heat the potato - I mean, cook it.", 1, {"cooked(Potato)"}),
    ("Put the book on the bed, no not the book, the laptop goes on the bed.", 301, {"inside(Laptop, Bed)"}),
    ("Slice the bread, no wait, don't, just put it in the fridge.", 1, {"inside(Bread, Fridge)"}),
    # said without a pause: the member taken out goes where the correcting part says
    ("put the fork and the spoon in the drawer and the knife as well no not the knife that goes in the sink", 1,
     {"inside(Fork, Drawer)", "inside(Spoon, Drawer)", "inside(Knife, SinkBasin)"}),
])
def test_the_correcting_part_replaces_its_slot_only(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected


def test_the_rest_of_the_earlier_request_stands_and_a_keep_is_added() -> None:
    # the desk lamp leaves the list; the floor lamp is still switched off
    goals = goal("Turn off the floor lamp and the desk lamp too. No, wait, the desk lamp can stay on.", 201)
    assert goals == {"switched_off(FloorLamp)", "switched_on(DeskLamp)"}
    # the other thing goes where the first was to go; the first one is kept where it is
    goals = goal("Put the remote on the sofa, no, the laptop; the remote stays where it is.", 212)
    assert "inside(Laptop, Sofa)" in goals and not any(g.startswith("inside(RemoteControl, Box") for g in goals)


def test_an_aside_inside_the_corrected_request_keeps_its_place() -> None:
    goals = goal("Put the bowl - sorry, the plate, the bowl stays - in the cabinet.", 1)
    assert "inside(Plate, Cabinet)" in goals and "inside(Bowl, Cabinet)" not in goals


def test_a_thing_that_could_be_the_place_or_the_member_offers_both() -> None:
    reading = read("Put the cup and the mug in the sink - no, the bowl.", 5)
    offered = [{str(g) for g in c.goals} for c in reading.candidates]
    assert offered[0] == {"inside(Cup, SinkBasin)", "inside(Bowl, SinkBasin)"}
    assert {"inside(Bowl, SinkBasin)"} in offered     # the bowl instead of both
    other = next(c for c in reading.candidates if {str(g) for g in c.goals} == {"inside(Bowl, SinkBasin)"})
    assert {r.kind for r in other.resolves} == {"correction"}


def test_the_rejected_side_stays_a_candidate() -> None:
    reading = read("Put the kettle on the stove - no, on the counter.", 5)
    assert {str(g) for g in reading.candidates[0].goals} == {"inside(Kettle, CounterTop)"}
    assert any({str(g) for g in c.goals} == {"inside(Kettle, StoveBurner)"} for c in reading.candidates)


@pytest.mark.parametrize(("text", "fp", "expected"), [
    ("Nobody needs the lights on.", 1, {"switched_off(LightSwitch)"}),
    ("Valuables live in the drawer - by valuables I mean the watch.", 201, None),
    ("Actually, could you put the apple in the fridge?", 1, {"inside(Apple, Fridge)"}),
    ("Put the apple in the fridge. Actually, slice the bread too.", 1, {"inside(Apple, Fridge)", "sliced(Bread)"}),
])
def test_what_is_no_correction_is_read_as_said(text: str, fp: int, expected: set[str] | None) -> None:
    goals = goal(text, fp)
    if expected is None:     # a definition, not a correction: the watch is not put aside
        assert any("Watch" in g for g in goals)
    else:
        assert goals == expected
