"""The committed cassettes of the live hybrid runs on the development rounds r40, r41 and
on MACE-THOR (benchmarks/hybrid_live.py: Qwen2.5-Coder-0.5B through llama.cpp, the model
scoring the offline reader's close readings) replay through the full system and give
exactly the metrics recorded in benchmarks/llm_local/read25_results.json. A change to the
reader's candidates, their sentences or the scoring prompt shows up here as a replay miss
or a different number."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "llm_local" / "read25_results.json"


def _hybrid_live() -> Any:
    sys.path.insert(0, str(ROOT / "benchmarks"))  # benchmarks/ is no package
    import hybrid_live

    return hybrid_live


def _scored() -> list[tuple[str, str]]:
    """(suite, task) of every recorded task that made a scoring call (the others are the
    offline reading: nothing to replay)."""
    if not RESULTS.exists():
        return []
    runs = json.loads(RESULTS.read_text())["runs"]
    return [(suite, task) for suite, run in runs.items() for task, row in run["rows"].items() if row["llm_calls"]]


@pytest.mark.parametrize(("suite", "task_id"), _scored(), ids=lambda v: v)
def test_a_scored_task_replays_with_the_same_metrics(suite: str, task_id: str) -> None:
    live = _hybrid_live()
    want = json.loads(RESULTS.read_text())["runs"][suite]["rows"][task_id]
    task = next(t for t in live.tasks_of(suite) if t.id == task_id)
    got = live.run_task(task, f"replay:{live.cassette(suite)}", None)
    assert {m: got[m] for m in live.METRICS} == {m: want[m] for m in live.METRICS}


def test_the_recorded_summary_is_the_rows() -> None:
    live = _hybrid_live()
    runs = json.loads(RESULTS.read_text())["runs"]
    assert set(runs) >= {"r40", "r41", "mace"}
    for run in runs.values():
        assert live.summary(run["rows"]) == run["summary"]
    assert runs["mace"]["summary"]["score_calls_per_task"] <= 0.5
