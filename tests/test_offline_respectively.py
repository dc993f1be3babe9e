""""Respectively" pairs the things of one list with the places of another, in order
(data: the four `respectively` phrasings of pfg/offline/data/idioms.json): before, every
thing went to the first place, or the second place was read as a thing to move."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from offline_reading import read_offline


@pytest.fixture(scope="module")
def frontend() -> OfflineFrontend:
    return OfflineFrontend()


def _goals(frontend: OfflineFrontend, text: str, floor_plan: str = "FloorPlan1") -> set[str]:
    return {str(c) for c in read_offline(frontend, text, floor_plan).spec.goal().conditions}


@pytest.mark.parametrize("text", [
    "The apple and the egg go in the fridge and the sink, respectively.",
    "the apple and the egg belong in the fridge and in the sink respectively",
    "Put the apple and the egg into the fridge and into the sink, respectively.",
    "put the apple and the egg in the fridge and the sink respectively",
])
def test_each_thing_goes_to_its_own_place_in_order(frontend: OfflineFrontend, text: str) -> None:
    assert _goals(frontend, text) == {"inside(Apple, Fridge)", "inside(Egg, SinkBasin)"}


def test_the_order_of_the_places_decides(frontend: OfflineFrontend) -> None:
    text = "The egg and the apple go in the fridge and the sink, respectively."
    assert _goals(frontend, text) == {"inside(Egg, Fridge)", "inside(Apple, SinkBasin)"}


def test_without_respectively_a_list_keeps_its_reading(frontend: OfflineFrontend) -> None:
    text = "Put the apple and the egg in the fridge."
    assert _goals(frontend, text) == {"inside(Apple, Fridge)", "inside(Egg, Fridge)"}
