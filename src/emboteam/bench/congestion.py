"""The congestion suite: tasks built to make robots meet on the navigation grid.

4 to 8 robots in bathrooms and small kitchens (grids of 25 to 100 cells), errands on
opposite sides of the room so that paths cross, and rooms whose grid has a one-cell
doorway with a robot parked in it (``starts``). The tasks are package data
(``bench/data/congestion.json``, written by ``scripts/build_congestion_suite.py``, which
keeps only tasks the oracle front end solves with avoidance on); the suite measures
collisions, waits, re-plans and the makespan price of not colliding (docs/navigation.md).
"""

from __future__ import annotations

import json
from functools import cache
from importlib import resources

from emboteam.bench.mace_thor import SuiteDataError, parse_tasks
from emboteam.task import BenchTask

SUITE_NAME = "congestion"


@cache
def load_congestion() -> tuple[BenchTask, ...]:
    """The congestion tasks (validated once per process)."""
    text = resources.files("emboteam.bench").joinpath("data/congestion.json").read_text()
    try:
        raw = json.loads(text)
    except json.JSONDecodeError as exc:
        raise SuiteDataError(f"congestion.json is not JSON: {exc}") from None
    return parse_tasks(raw, suite=SUITE_NAME, where="congestion.json")
