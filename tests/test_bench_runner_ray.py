"""``--executor ray`` on a local Ray instance started by the test (1 CPU, no dashboard):
the same episodes as locally, exceptions and dead workers recorded as failed episodes."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import pytest

import emboteam
from emboteam.bench.jobs import expand_jobs
from emboteam.bench.runner import run_bench, store_path
from emboteam.bench.store import ResultStore
from emboteam.report.loading import load_episode_dir
from test_bench_runner import CALLS_ENV, calls, config, make_task, worker_pids

ray = pytest.importorskip("ray", reason="ray is not installed (pip install 'emboteam[ray]')")

TESTS = Path(__file__).resolve().parent
#: the source tree of the emboteam under test (not necessarily the venv's installed one)
SRC = Path(emboteam.__file__).resolve().parents[1]


def test_without_a_running_ray_the_executor_starts_and_stops_its_own(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    assert not ray.is_initialized()
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join((str(TESTS), str(SRC))))  # the local instance's workers inherit it
    out = tmp_path / "out"
    cfg = config(out, executor="ray", workers=1)
    jobs = expand_jobs(cfg, [make_task("t2"), make_task("t3")])
    episodes = run_bench(cfg, jobs, "test_bench_runner:scripted_episode", progress=False, reports=False)
    assert [e.success for e in episodes] == [True, False]
    assert not ray.is_initialized()


@pytest.fixture(scope="module")
def local_ray(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    call_log = tmp_path_factory.mktemp("ray") / "calls.txt"
    # Ray workers are fresh processes: they find the test's episode function through
    # PYTHONPATH and log their calls to the file the test reads
    ray.init(num_cpus=1, include_dashboard=False, log_to_driver=False,
             runtime_env={"env_vars": {"PYTHONPATH": os.pathsep.join((str(TESTS), str(SRC))),
                                       CALLS_ENV: str(call_log)}})
    try:
        yield call_log
    finally:
        ray.shutdown()


def test_ray_executor_runs_the_jobs_and_records_failures(tmp_path: Path, local_ray: Path) -> None:
    out = tmp_path / "out"
    tasks = [make_task("t1"), make_task("boom"), make_task("die"), make_task("t2", "temporal")]
    cfg = config(out, executor="ray", workers=1)
    jobs = expand_jobs(cfg, tasks)
    episodes = run_bench(cfg, jobs, "test_bench_runner:scripted_episode", progress=False, reports=False)

    assert [e.task for e in episodes] == [t.key for t in tasks]
    assert [e.success for e in episodes] == [False, False, False, True]
    assert episodes[1].error == "RuntimeError: planner crashed"
    died = episodes[2].error
    assert died is not None and died.startswith("WorkerDied"), died
    assert episodes[0].error is None and episodes[3].error is None
    assert os.getpid() not in worker_pids(local_ray)  # they ran in Ray workers
    # Ray retried the dying job once; the others ran exactly once
    assert calls(local_ray) == {jobs[0].key: 1, jobs[1].key: 1, jobs[2].key: 2, jobs[3].key: 1}
    with ResultStore(store_path(out)) as store:
        assert store.done_keys() == {j.key for j in jobs}
        saved = load_episode_dir(out / store.results(task_id="t2")[0].episode_dir)
    assert [ev.kind for ev in saved.trace] == ["action_start", "action_end"]
    assert ray.is_initialized(), "a Ray instance the caller started is left running"
