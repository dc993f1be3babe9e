"""Kill a benchmark run for real (SIGKILL to the runner process) and resume it: the
orphaned workers exit, every job ends up stored exactly once, finished jobs are not
recomputed, interrupted ones re-run once."""

from __future__ import annotations

import contextlib
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

from emboteam.bench.store import ResultStore
from test_bench_runner import CALLS_ENV, DELAY_ENV, calls, worker_pids

TESTS = Path(__file__).resolve().parent
N_TASKS = 12

SCRIPT = f"""
import sys
sys.path.insert(0, {str(TESTS)!r})

from emboteam.bench.jobs import BenchConfig, expand_jobs
from emboteam.bench.runner import run_bench
import pytest
from test_bench_runner import make_task, scripted_episode

if __name__ == "__main__":
    out, resume = sys.argv[1], sys.argv[2] == "resume"
    cfg = BenchConfig.build(suite="unit", out_dir=out, workers=2, resume=resume)
    tasks = [make_task(f"t{{i}}", "temporal" if i % 3 else "parallel") for i in range({N_TASKS})]
    episodes = run_bench(cfg, expand_jobs(cfg, tasks), scripted_episode, progress=False, reports=False)
    print(len(episodes))
"""


def _stored_keys(store: Path) -> set[str]:
    if not store.exists():
        return set()
    try:
        with sqlite3.connect(f"file:{store}?mode=ro", uri=True) as db:
            return {r[0] for r in db.execute("SELECT key FROM episodes")}
    except sqlite3.OperationalError:  # created but no table yet
        return set()


def _alive(pid: int) -> bool:
    """Running (a zombie waiting for its new parent to reap it counts as gone)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except (FileNotFoundError, ProcessLookupError):
        return False
    return "\nState:\tZ" not in status


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="watches worker processes through /proc")
def test_sigkill_midway_then_resume_runs_each_job_exactly_once(tmp_path: Path) -> None:
    script = tmp_path / "bench_script.py"
    script.write_text(SCRIPT)
    out = tmp_path / "out"
    store = out / "results.sqlite"
    call_log = tmp_path / "calls.txt"
    env = {**os.environ, CALLS_ENV: str(call_log), DELAY_ENV: "0.25"}

    run = subprocess.Popen([sys.executable, str(script), str(out), "fresh"], env=env,
                           start_new_session=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    while len(_stored_keys(store)) < 3:
        assert run.poll() is None, run.stderr.read().decode() if run.stderr else "run ended early"
        assert time.monotonic() < deadline, "the run stored nothing within 60 s"
        time.sleep(0.05)
    os.kill(run.pid, signal.SIGKILL)  # the runner only, as `kill -9 PID` would
    run.wait()
    workers = worker_pids(call_log) - {run.pid}
    try:
        deadline = time.monotonic() + 10
        while any(_alive(pid) for pid in workers) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not any(_alive(pid) for pid in workers), "workers outlived the killed runner"
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(run.pid, signal.SIGKILL)  # whatever is left of that session, if anything

    finished_before = _stored_keys(store)
    started_before = set(calls(call_log))
    interrupted = started_before - finished_before
    assert 3 <= len(finished_before) < N_TASKS, "the kill must land midway"
    assert interrupted, "some job was running when the run was killed"

    resumed = subprocess.run([sys.executable, str(script), str(out), "resume"], env=env,
                             capture_output=True, text=True, timeout=120)
    assert resumed.returncode == 0, resumed.stderr
    assert resumed.stdout.strip() == str(N_TASKS)

    with ResultStore(store) as db:
        keys = [r.key for r in db.results()]
        assert len(keys) == len(set(keys)) == N_TASKS
        assert {k for k in interrupted if db.attempts(k) == 2} == interrupted
    starts = calls(call_log)
    assert set(starts) == set(keys)
    for key in keys:
        expected = 2 if key in interrupted else 1
        assert starts[key] == expected, f"{key} ran {starts[key]} times, expected {expected}"
    for key in finished_before:
        assert starts[key] == 1, f"finished job {key} was recomputed"
    assert len(list((out / "episodes").iterdir())) == N_TASKS
