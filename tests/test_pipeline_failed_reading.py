"""A failed episode still shows what was read: when the planner refuses the goal the
front end read, the episode (and so `run --json`, the bench store, the hybrid's overturn
count) keeps the reading's notes and candidates. Before, an error after the reading
dropped them, and a model overturn that led to an unplannable goal was counted as none."""

from __future__ import annotations

import pytest

from emboteam import modes
from emboteam.config import RunConfig
from emboteam.errors import EmboTeamError
from emboteam.pipeline import run_episode
from emboteam.task import Instruction


class _Refused(EmboTeamError):
    """The planner's refusal, as any typed error after the reading."""


def test_a_goal_the_planner_refuses_keeps_the_readings_notes_and_candidates(monkeypatch: pytest.MonkeyPatch) -> None:
    task = Instruction.typed("Movie time: the television should be the only thing that is lit.", "FloorPlan201",
                             "1,2,3")
    kept = run_episode(task, RunConfig(mode="full", frontend="offline"))
    assert kept.notes and kept.candidates           # the reading is a choice with notes

    def refuse(*_: object, **__: object) -> None:
        raise _Refused("no plan for that goal")

    monkeypatch.setattr(modes, "plan_spec", refuse)
    failed = run_episode(task, RunConfig(mode="full", frontend="offline"))
    assert not failed.success and failed.error is not None and failed.error.startswith("_Refused")
    assert failed.notes == kept.notes
    assert failed.candidates == kept.candidates


def test_an_error_before_any_reading_has_no_notes() -> None:
    task = Instruction.typed("", "FloorPlan201", "1")
    failed = run_episode(task, RunConfig(mode="full", frontend="offline"))
    assert failed.error is not None and failed.notes == () and failed.candidates == ()
