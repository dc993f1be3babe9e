"""MACE-THOR: the 42 multi-robot household tasks shipped as package data.

The tasks live in ``bench/data/mace_thor.json`` (one object per task; docs/mace_thor.md
explains their design). Loading validates every task against the schema (unknown fields
are errors), its floor plan, team, initial-state changes and goal, and the suite as a
whole (unique ids); a broken file is a :class:`SuiteDataError`, never a half-loaded suite.
"""

from __future__ import annotations

import json
from functools import cache
from importlib import resources
from typing import Any

from pydantic import BaseModel, ConfigDict, ValidationError

from emboteam.errors import EmboTeamError
from emboteam.task import BenchTask, InvalidTaskError

SUITE_NAME = "mace-thor"

#: The eight iTHOR layouts of the benchmark: four kitchens, two living rooms, a bedroom and
#: a bathroom (the layouts of SMART-LLM's test set plus FloorPlan1).
FLOOR_PLANS: tuple[str, ...] = ("FloorPlan1", "FloorPlan6", "FloorPlan15", "FloorPlan21",
                                "FloorPlan201", "FloorPlan209", "FloorPlan303", "FloorPlan414")


class SuiteDataError(EmboTeamError):
    """A suite file that does not validate (schema, scene, team or goal)."""


class _SuiteFile(BaseModel):
    """The file's envelope; tasks are validated one by one to name the culprit."""

    model_config = ConfigDict(extra="forbid")

    suite: str
    version: int
    description: str = ""
    tasks: list[dict[str, Any]]


def parse_tasks(raw: Any, *, suite: str = SUITE_NAME, where: str = "mace_thor.json") -> tuple[BenchTask, ...]:
    """Validate a MACE-THOR-format document and return its tasks, in file order."""
    try:
        doc = _SuiteFile.model_validate(raw)
    except ValidationError as exc:
        raise SuiteDataError(f"{where}: {_first_error(exc)}") from None
    if doc.suite != suite:
        raise SuiteDataError(f"{where}: suite is {doc.suite!r}, expected {suite!r}")
    tasks: list[BenchTask] = []
    seen: set[str] = set()
    for i, entry in enumerate(doc.tasks, start=1):
        label = f"{where}: task #{i} ({entry.get('id', '?')})"
        if "suite" in entry:
            raise SuiteDataError(f"{label}: 'suite' is set by the file, not per task")
        try:
            task = BenchTask.model_validate({**entry, "suite": suite})
        except ValidationError as exc:
            raise SuiteDataError(f"{label}: {_first_error(exc)}") from None
        if task.id in seen:
            raise SuiteDataError(f"{label}: duplicate task id {task.id!r}")
        seen.add(task.id)
        try:
            task.check()
        except InvalidTaskError as exc:
            raise SuiteDataError(f"{label}: {exc}") from None
        tasks.append(task)
    return tuple(tasks)


def _first_error(exc: ValidationError) -> str:
    err = exc.errors()[0]
    loc = ".".join(str(p) for p in err["loc"])
    more = f" (and {exc.error_count() - 1} more)" if exc.error_count() > 1 else ""
    return f"{loc}: {err['msg']}{more}" if loc else f"{err['msg']}{more}"


@cache
def load_mace_thor() -> tuple[BenchTask, ...]:
    """The 42 tasks (validated once per process, then cached: they are immutable)."""
    text = resources.files("emboteam.bench").joinpath("data/mace_thor.json").read_text()
    try:
        raw = json.loads(text)
    except json.JSONDecodeError as exc:
        raise SuiteDataError(f"mace_thor.json is not JSON: {exc}") from None
    return parse_tasks(raw)
