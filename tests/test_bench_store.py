"""The results store: one committed row per episode, readable after reopening."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest

from emboteam.bench.jobs import Job
from emboteam.bench.store import ResultStore, ResultStoreError
from emboteam.exec.episode import Episode
from emboteam.task import BenchTask
from emboteam.world.goals import Goal


def _task(tid: str, category: str = "parallel") -> BenchTask:
    return BenchTask(id=tid, suite="unit", floor_plan="FloorPlan1", robots=("1", "2"),
                     category=category, instruction=f"task {tid}",  # type: ignore[arg-type]
                     goal=Goal.parse("sliced(Apple)"))


def _episode(job: Job, success: bool, gcr: float) -> Episode:
    return Episode(task=job.task.key, instruction=job.task.instruction, floor_plan="FloorPlan1",
                   robots=("robot1", "robot2"), category=job.task.category, mode=job.mode,
                   frontend=job.frontend, seed=job.seed, fault_level=job.fault_level,
                   success=success, gcr=gcr, exec=0.9, makespan=12.5, actions=7, llm_calls=2, tokens=300)


def test_rows_survive_reopening_with_their_columns(tmp_path: Path) -> None:
    path = tmp_path / "results.sqlite"
    a = Job(task=_task("a"), mode="full", seed=0)
    b = Job(task=_task("b", "temporal"), mode="no-btc", seed=1, fault_level=0.2)
    with ResultStore(path) as store:
        store.add(a, _episode(a, True, 1.0), episode_dir="episodes/a")
        store.add(b, _episode(b, False, 0.5), traceback="Traceback ...\nRuntimeError: x")
    with ResultStore(path) as store:
        assert len(store) == 2
        assert store.done_keys() == {a.key, b.key}
        [row_b] = store.results(mode="no-btc")
        assert row_b.episode == _episode(b, False, 0.5)
        assert row_b.crashed and row_b.traceback is not None and "RuntimeError" in row_b.traceback
        assert [e.task for e in store.episodes(category="parallel")] == ["unit/a"]
        assert store.episodes(fault_level=0.2, seed=1) == [_episode(b, False, 0.5)]
        assert store.jobs() == [a, b]
    # plain SQL works too: the summary metrics are real columns
    with sqlite3.connect(path) as db:
        rows = db.execute("SELECT task_id, mode, success, gcr, tokens FROM episodes ORDER BY task_id").fetchall()
    assert rows == [("a", "full", 1, 1.0, 300), ("b", "no-btc", 0, 0.5, 300)]


def test_a_key_is_stored_once(tmp_path: Path) -> None:
    job = Job(task=_task("a"))
    with ResultStore(tmp_path / "r.sqlite") as store:
        store.add(job, _episode(job, True, 1.0))
        with pytest.raises(ResultStoreError, match="already in"):
            store.add(job, _episode(job, False, 0.0))
        assert len(store) == 1
        assert store.episodes()[0].success


def test_started_but_unfinished_jobs_are_reported_as_interrupted(tmp_path: Path) -> None:
    a, b = Job(task=_task("a")), Job(task=_task("b"))
    with ResultStore(tmp_path / "r.sqlite") as store:
        store.mark_started(a)
        store.mark_started(b)
        store.add(a, _episode(a, True, 1.0))
        assert store.interrupted_keys() == {b.key}
        assert store.attempts(b.key) == 1


def test_unknown_filter_and_unreadable_file_are_typed_errors(tmp_path: Path) -> None:
    with ResultStore(tmp_path / "r.sqlite") as store, pytest.raises(ResultStoreError, match="cannot filter"):
        store.episodes(colour="red")
    junk = tmp_path / "junk.sqlite"
    junk.write_bytes(b"this is not a database" * 100)
    with pytest.raises(ResultStoreError, match="cannot open"):
        ResultStore(junk)


def test_a_newer_schema_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "r.sqlite"
    ResultStore(path).close()
    with sqlite3.connect(path) as db:
        db.execute("UPDATE meta SET value = '99' WHERE name = 'schema_version'")
    with pytest.raises(ResultStoreError, match="schema 99"):
        ResultStore(path)
