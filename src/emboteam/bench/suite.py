"""A loaded suite and the errors of naming one: what :mod:`emboteam.bench.suites` (which
resolves names) and the importers (which build suites) share, kept below both so neither
imports the other."""

from __future__ import annotations

import difflib
from collections import Counter

from pydantic import BaseModel, ConfigDict

from emboteam.errors import EmboTeamError
from emboteam.task import BenchTask


class UnknownSuiteError(EmboTeamError):
    """A suite spec that names no known suite, or a smart-llm PATH with no task files."""


class UnknownTaskError(EmboTeamError):
    """A task id that is not in its suite."""


class Suite(BaseModel):
    """A loaded suite: its tasks, and what an importer had to leave out (``problems``:
    one line each, ``FILE:LINE: why``)."""

    model_config = ConfigDict(frozen=True)

    name: str
    tasks: tuple[BenchTask, ...]
    problems: tuple[str, ...] = ()

    def task(self, task_id: str) -> BenchTask:
        for t in self.tasks:
            if t.id == task_id:
                return t
        ids = [t.id for t in self.tasks]
        close = difflib.get_close_matches(task_id, ids, n=5, cutoff=0.5)
        hint = f"; did you mean {', '.join(close)}?" if close else f"; it has {len(ids)} tasks " \
            f"(emboteam tasks --suite {self.name})"
        raise UnknownTaskError(f"suite {self.name} has no task {task_id!r}{hint}")

    def categories(self) -> dict[str, int]:
        """Number of tasks per category, in first-seen order."""
        return dict(Counter(t.category for t in self.tasks))
