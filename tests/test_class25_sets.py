"""A quantified set over a place or a class, minus its exceptions (pfg/offline/doubts/contents.py),
on sentences written for these tests (not round tasks). Default scenes: FloorPlan11's sink
holds a sponge, a lettuce, a potato and a tomato, its basin a fork and a spoon; FloorPlan406's
bathtub a cloth, a soap bar and a soap bottle; FloorPlan421's counter a candle, a cloth, a
soap bar, a soap bottle, a spray bottle and a roll; FloorPlan317's dresser a book, a bowl, a
CD, a phone, a laptop, a pen and a pencil."""

from __future__ import annotations

from test_offline_contents import goals


def test_a_sink_is_also_its_basin_and_the_excepted_stay_where_they_are() -> None:
    got = goals("Everything in the sink goes on the counter, except the sponge and the spoon.", 11)
    assert {"inside(Lettuce, CounterTop)", "inside(Potato, CounterTop)", "inside(Tomato, CounterTop)",
            "inside(Fork, CounterTop)"} <= got
    # each excepted thing keeps the place it has now: the sponge the sink, the spoon its basin
    assert {"inside(DishSponge, Sink)", "inside(Spoon, SinkBasin)"} <= got
    assert "inside(DishSponge, CounterTop)" not in got and "inside(Spoon, CounterTop)" not in got


def test_the_basin_named_alone_is_not_the_whole_sink() -> None:
    got = goals("Whatever is in the basin goes in the drawer.", 11)
    assert {"inside(Fork, Drawer)", "inside(Spoon, Drawer)"} <= got
    assert "inside(Lettuce, Drawer)" not in got


def test_a_class_noun_under_a_quantifier_picks_the_set() -> None:
    got = goals("All the produce in the sink goes in the fridge.", 11)
    assert {"inside(Lettuce, Fridge)", "inside(Potato, Fridge)", "inside(Tomato, Fridge)"} <= got
    assert "inside(DishSponge, Fridge)" not in got and "inside(Fork, Fridge)" not in got


def test_a_copula_not_says_what_a_thing_is_and_leaves_nothing_out() -> None:
    got = goals("Everything in the sink you could actually eat goes in the fridge - the sponge is not food.", 11)
    assert {"inside(Lettuce, Fridge)", "inside(Potato, Fridge)", "inside(Tomato, Fridge)"} <= got
    assert "inside(DishSponge, Fridge)" not in got


def test_its_contents_and_thereon_name_the_place_said_before() -> None:
    got = goals("The dresser: all its contents into the box, except the laptop and the bowl.", 317)
    assert {"inside(Book, Box)", "inside(CD, Box)", "inside(Pen, Box)", "inside(Laptop, Dresser)",
            "inside(Bowl, Dresser)"} <= got
    got = goals("The counter is cluttered; remove all items thereon to the drawers, except the candle.", 421)
    assert {"inside(Cloth, Drawer)", "inside(SoapBar, Drawer)", "inside(Candle, CounterTop)"} <= got


def test_an_aside_of_exceptions_does_not_take_the_sets_destination() -> None:
    # the verb after the dash is the sentence's own: the book is excepted, not sent to the box
    got = goals("Everything on the dresser - everything except the laptop and the book - goes in the box.", 317)
    assert {"inside(CD, Box)", "inside(Pen, Box)", "inside(Book, Dresser)", "inside(Laptop, Dresser)"} <= got
    assert "inside(Book, Box)" not in got


def test_an_aside_of_examples_is_part_of_the_set() -> None:
    got = goals("The tub: everything in it - the cloth, the soap - goes to the counter, except the soap bar.", 406)
    assert {"inside(Cloth, CounterTop)", "inside(SoapBottle, CounterTop)", "inside(SoapBar, Bathtub)"} <= got


def test_an_exception_list_goes_on_after_a_bracketed_aside() -> None:
    got = goals("Everything on the counter goes in the drawers except the candle (lit, please) and the soap bottle.",
                421)
    assert {"inside(Cloth, Drawer)", "inside(SoapBottle, CounterTop)", "inside(Candle, CounterTop)"} <= got
    assert "inside(SoapBottle, Drawer)" not in got
