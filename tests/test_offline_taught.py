"""Phrasings taught to the offline parser by editing its data files only
(src/emboteam/pfg/offline/data/*.json; docs/teach_a_phrasing.md): one row each, the
instruction, the floor plan and the goal it must read to. A row here is how a taught
phrasing is kept: before its data entry the parser misread or refused it."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from offline_reading import goal_of

FRONTEND = OfflineFrontend()


def goal(text: str, fp: int) -> set[str]:
    return goal_of(FRONTEND, text, fp)


@pytest.mark.parametrize(("text", "fp", "expected"), [
    # lexicon.json, nouns: "chilly bin" (a cool box) was read as a garbage can by its last word
    ("Pop the spud in the chilly bin.", 1, {"inside(Potato, Fridge)"}),
    # lexicon.json, nouns: "crisper" (the fridge's drawer) named nothing
    ("Put the apple in the crisper.", 1, {"inside(Apple, Fridge)"}),
    # lexicon.json, verbs (act "trash"): "jettison" was no verb
    ("Jettison the apple.", 1, {"inside(Apple, GarbageCan)"}),
    # idioms.json, phrasings: "give the plant a drink" was read as handing the plant over
    ("Give the plant a drink.", 1, {"filled(HousePlant, water)"}),
])
def test_a_taught_phrasing_reads_to_its_goal(text: str, fp: int, expected: set[str]) -> None:
    assert goal(text, fp) == expected
