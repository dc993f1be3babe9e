"""The banded distance of the sound-alike search (morphology.distance_within) decides as
the full one does: the same distance when it is within the bound, over the bound when not."""

from __future__ import annotations

import itertools

import pytest

from emboteam.pfg.offline.morphology import distance_within, edit_distance

WORDS = ["", "a", "sink", "sync", "snik", "kettle", "ketle", "kettel", "microwave", "micro wave",
         "remotecontrol", "remote controll", "tele vision", "television", "bin", "pin", "ab", "ba"]


@pytest.mark.parametrize("k", [0, 1, 2, 3, 4])
def test_banded_distance_agrees_with_the_full_one(k: int) -> None:
    for a, b in itertools.product(WORDS, repeat=2):
        full = edit_distance(a, b, k + 1)
        banded = distance_within(a, b, k)
        if full <= k:
            assert banded == full, (a, b, k)
        else:
            assert banded == k + 1, (a, b, k)


def test_a_transposition_costs_one() -> None:
    assert distance_within("kettle", "ketlte", 2) == 1
    assert distance_within("sink", "snik", 1) == 1
