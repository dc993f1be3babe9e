"""The benchmark runner: jobs, process-pool workers, failures as recorded episodes, resume.

The episode functions here stand in for the pipeline (the runner takes any episode
function); they are module-level so spawned worker processes can import them, and they
log every call to the file named by ``EMBOTEAM_TEST_CALLS`` so tests can count how often
each job really ran.
"""

from __future__ import annotations

import os
import time
from collections import Counter
from pathlib import Path

import pytest

from emboteam.bench.jobs import (
    BenchConfig,
    BenchConfigError,
    Job,
    expand_jobs,
    modes_from_options,
    parse_fault_levels,
)
from emboteam.bench.runner import run_bench, store_path
from emboteam.bench.store import ResultStore
from emboteam.exec.episode import Episode
from emboteam.exec.trace import TraceEvent
from emboteam.report.loading import load_episode_dir
from emboteam.task import BenchTask
from emboteam.world.goals import Goal

CALLS_ENV = "EMBOTEAM_TEST_CALLS"
DELAY_ENV = "EMBOTEAM_TEST_DELAY"


def make_task(tid: str, category: str = "parallel", suite: str = "unit") -> BenchTask:
    return BenchTask(id=tid, suite=suite, floor_plan="FloorPlan1", robots=("1", "2"),
                     category=category, instruction=f"do task {tid}",  # type: ignore[arg-type]
                     goal=Goal.parse("sliced(Apple) & off(LightSwitch)"))


def _log_call(what: str, job: Job) -> None:
    path = os.environ.get(CALLS_ENV)
    if path:
        with open(path, "a") as fh:  # one short O_APPEND write per line: safe across processes
            fh.write(f"{what} {os.getpid()} {job.key}\n")


def scripted_episode(job: Job) -> Episode:
    """A deterministic outcome per job: task ``boom`` raises, task ``die`` kills its worker
    process, the others succeed when their number plus the seed is even, less often
    under faults."""
    _log_call("start", job)
    if job.task_id == "boom":
        raise RuntimeError("planner crashed")
    if job.task_id == "die":
        os._exit(3)
    time.sleep(float(os.environ.get(DELAY_ENV, "0")))
    number = int("".join(ch for ch in job.task_id if ch.isdigit()) or 0)
    success = (number + job.seed) % 2 == 0 and job.fault_level < 0.3
    episode = Episode(
        task=job.task.key, instruction=job.task.instruction, floor_plan=job.task.floor_plan,
        robots=("robot1", "robot2"), category=job.task.category, mode=job.mode, frontend=job.frontend,
        seed=job.seed, fault_level=job.fault_level, faults=job.fault_config(), success=success,
        gcr=1.0 if success else 0.5, exec=1.0 - job.fault_level, makespan=10.0 + number, actions=4,
        trace=(TraceEvent(t=0.0, kind="action_start", robot="robot1", data={"action": "GoToObject(Apple)"}),
               TraceEvent(t=3.0, kind="action_end", robot="robot1", data={"success": True})),
    )
    _log_call("end", job)
    return episode


def calls(path: Path, what: str = "start") -> Counter[str]:
    if not path.exists():
        return Counter()
    return Counter(line.split(" ", 2)[2] for line in path.read_text().splitlines()
                   if line.startswith(what + " "))


def worker_pids(path: Path) -> set[int]:
    return {int(line.split(" ", 2)[1]) for line in path.read_text().splitlines()}


def config(out: Path, **fields: object) -> BenchConfig:
    base: dict[str, object] = {"suite": "unit", "out_dir": out, "workers": 2, "executor": "local"}
    base.update(fields)
    return BenchConfig.build(**base)


@pytest.fixture
def call_log(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    path = tmp_path / "calls.txt"
    monkeypatch.setenv(CALLS_ENV, str(path))
    return path


# --------------------------------------------------------------------------- jobs

def test_expand_jobs_covers_every_combination_with_stable_keys(tmp_path: Path) -> None:
    tasks = [make_task("t1"), make_task("t2", "temporal"), make_task("t3")]
    cfg = config(tmp_path, modes=["full", "no-hp"], seeds=2, fault_levels=[0.0, 0.1])
    jobs = expand_jobs(cfg, tasks)
    assert len(jobs) == 2 * 2 * 2 * 3
    assert len({j.key for j in jobs}) == len(jobs)
    assert len({j.dirname for j in jobs}) == len(jobs)
    assert jobs[0].key == "unit/t1|full|offline|-|seed=0|faults=0.0"
    assert jobs[-1].key == "unit/t3|no-hp|offline|-|seed=1|faults=0.1"
    # the same configuration gives the same keys (what resume relies on)
    assert [j.key for j in expand_jobs(cfg, tasks)] == [j.key for j in jobs]


def test_keys_tell_apart_what_directory_names_would_merge() -> None:
    task = make_task("t1")
    a = Job(task=task, frontend="llm", llm="openai:m@http://h:1/v1")
    b = Job(task=task, frontend="llm", llm="openai:m@http_h:1/v1")
    assert a.key != b.key and a.dirname != b.dirname
    assert "/" not in a.dirname and ":" not in a.dirname and "|" not in a.dirname


def test_bad_options_are_one_line_typed_errors() -> None:
    with pytest.raises(BenchConfigError, match="modes"):
        BenchConfig.build(suite="unit", modes=["fast"])
    with pytest.raises(BenchConfigError, match="LLM spec"):
        BenchConfig.build(suite="unit", frontends=["llm"])
    with pytest.raises(BenchConfigError, match="not a probability"):
        BenchConfig.build(suite="unit", fault_levels=[1.5])
    with pytest.raises(BenchConfigError, match="seeds"):
        BenchConfig.build(suite="unit", seeds=0)
    assert parse_fault_levels(["0,0.1", "0.2", 0.1]) == (0.0, 0.1, 0.2)
    with pytest.raises(BenchConfigError, match="probabilities"):
        parse_fault_levels(["low"])
    with pytest.raises(BenchConfigError, match="not a probability"):
        parse_fault_levels(["2"])
    cfg = BenchConfig.build(suite="unit")
    with pytest.raises(BenchConfigError, match="twice"):
        expand_jobs(cfg, [make_task("t1"), make_task("t1")])
    with pytest.raises(BenchConfigError, match="no tasks"):
        expand_jobs(cfg, [])


def test_ablation_and_baseline_options_become_modes() -> None:
    assert modes_from_options() == ("full",)
    assert modes_from_options(baselines=["smart-llm", "lamma-p"]) == ("full", "smart-llm", "lamma-p")
    assert modes_from_options(["full", "no-pfg-hp", "no-hp", "no-btc"]) == ("full", "no-pfg-hp", "no-hp", "no-btc")
    assert modes_from_options(["no-hp"]) == ("no-hp",)
    with pytest.raises(BenchConfigError, match="a baseline: use --baseline"):
        modes_from_options(["smart-llm"])
    with pytest.raises(BenchConfigError, match="unknown baseline 'gpt'"):
        modes_from_options(baselines=["gpt"])


def test_the_pipeline_episode_function_passes_the_job_through(monkeypatch: pytest.MonkeyPatch) -> None:
    import emboteam.pipeline as pipeline
    from emboteam.bench.jobs import resolve_episode_fn
    from emboteam.bench.runner import PIPELINE_EPISODE_FN, pipeline_episode

    seen: list[tuple[BenchTask, pipeline.RunConfig]] = []

    def fake_run_episode(task: BenchTask, cfg: pipeline.RunConfig) -> Episode:
        seen.append((task, cfg))
        return scripted_episode(Job(task=task, mode=cfg.mode, seed=cfg.seed))

    monkeypatch.setattr(pipeline, "run_episode", fake_run_episode)
    assert resolve_episode_fn(PIPELINE_EPISODE_FN) is pipeline_episode
    task = make_task("t2")
    job = Job(task=task, mode="no-btc", frontend="llm", llm="replay:cassettes/x", seed=3, fault_level=0.2,
              llm_timeout=12.0)
    episode = pipeline_episode(job)
    [(given_task, cfg)] = seen
    assert given_task == task
    assert (cfg.mode, cfg.frontend, cfg.llm, cfg.seed, cfg.fault_level, cfg.llm_timeout) == \
        ("no-btc", "llm", "replay:cassettes/x", 3, 0.2, 12.0)
    assert cfg.fault_config() == job.fault_config()
    assert episode.mode == "no-btc"


# --------------------------------------------------------------------------- running

def test_process_pool_run_stores_every_episode_and_its_trace(tmp_path: Path, call_log: Path) -> None:
    out = tmp_path / "out"
    tasks = [make_task("t1"), make_task("t2", "temporal"), make_task("boom"), make_task("t4")]
    cfg = config(out)
    jobs = expand_jobs(cfg, tasks)
    episodes = run_bench(cfg, jobs, scripted_episode, progress=False, reports=False)

    assert [e.task for e in episodes] == [t.key for t in tasks]
    assert [e.success for e in episodes] == [False, True, False, True]
    boom = episodes[2]
    assert boom.error == "RuntimeError: planner crashed" and not boom.success
    assert boom.robots == ("robot1", "robot2") and boom.category == "parallel"
    assert calls(call_log) == Counter({j.key: 1 for j in jobs})
    assert calls(call_log, "end") == Counter({j.key: 1 for j in jobs if j.task_id != "boom"})
    assert os.getpid() not in worker_pids(call_log)  # the episodes ran in worker processes

    with ResultStore(store_path(out)) as store:
        rows = {r.key: r for r in store.results()}
    assert set(rows) == {j.key for j in jobs}
    crashed = rows[jobs[2].key]
    assert crashed.crashed and crashed.traceback is not None and "planner crashed" in crashed.traceback
    for job in jobs:
        saved = load_episode_dir(out / rows[job.key].episode_dir)
        assert saved.task == job.task.key
        if job.task_id != "boom":
            assert [ev.kind for ev in saved.trace] == ["action_start", "action_end"]


def test_a_worker_that_dies_fails_only_its_own_job(tmp_path: Path, call_log: Path) -> None:
    out = tmp_path / "out"
    tasks = [make_task("t1"), make_task("die"), make_task("t2"), make_task("t3"), make_task("t4")]
    cfg = config(out)
    jobs = expand_jobs(cfg, tasks)
    episodes = run_bench(cfg, jobs, scripted_episode, progress=False, reports=False)

    by_task = {e.task: e for e in episodes}
    assert by_task["unit/die"].error is not None and by_task["unit/die"].error.startswith("WorkerDied")
    others = [e for e in episodes if e.task != "unit/die"]
    assert all(e.error is None for e in others)
    assert [e.success for e in others] == [False, True, False, True]
    # every job finished exactly once; the innocent ones lost with the pool re-ran alone
    ends = calls(call_log, "end")
    assert ends == Counter({j.key: 1 for j in jobs if j.task_id != "die"})
    with ResultStore(store_path(out)) as store:
        assert store.done_keys() == {j.key for j in jobs}


def test_an_out_dir_with_results_needs_resume_and_resume_reruns_nothing(tmp_path: Path, call_log: Path) -> None:
    out = tmp_path / "out"
    tasks = [make_task("t1"), make_task("t2")]
    cfg = config(out, executor="inline")
    jobs = expand_jobs(cfg, tasks)
    first = run_bench(cfg, jobs, scripted_episode, progress=False, reports=False)
    with pytest.raises(BenchConfigError, match="--resume"):
        run_bench(cfg, jobs, scripted_episode, progress=False, reports=False)

    resumed_cfg = config(out, executor="inline", resume=True, seeds=2)
    more_jobs = expand_jobs(resumed_cfg, tasks)
    again = run_bench(resumed_cfg, more_jobs, scripted_episode, progress=False, reports=False)
    assert again[:2] == first
    assert [e.seed for e in again] == [0, 0, 1, 1]
    assert calls(call_log) == Counter({j.key: 1 for j in more_jobs})


@pytest.mark.parametrize("terminal", [True, False])
def test_progress_on_stderr_and_import_path_episode_function(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch, terminal: bool) -> None:
    if terminal:
        monkeypatch.setenv("FORCE_COLOR", "1")  # rich then draws its bar as on a terminal
    else:
        monkeypatch.delenv("FORCE_COLOR", raising=False)
        monkeypatch.delenv("TTY_COMPATIBLE", raising=False)
    out = tmp_path / "out"
    cfg = config(out, executor="inline")
    jobs = expand_jobs(cfg, [make_task("t2"), make_task("boom"), make_task("t4")])
    episodes = run_bench(cfg, jobs, "test_bench_runner:scripted_episode", progress=True, reports=False)
    assert [e.success for e in episodes] == [True, False, True]
    captured = capsys.readouterr()
    assert captured.out == ""  # stdout stays free for --json
    assert "3/3" in captured.err and "SR 66.7%" in captured.err
    if terminal:
        assert "━" in captured.err and "errors 1" in captured.err
    else:  # one plain line per episode, for logs
        lines = captured.err.splitlines()
        assert lines[1].startswith("[2/3] unit/boom|full|offline|-|seed=0|faults=0.0: failure "
                                   "(RuntimeError: planner crashed)  SR 50.0%  ETA ")
        assert len(lines) == 3


def test_unusable_episode_functions_are_refused_before_running(tmp_path: Path) -> None:
    cfg = config(tmp_path / "out")
    jobs = expand_jobs(cfg, [make_task("t1")])
    with pytest.raises(BenchConfigError, match="cannot be pickled"):
        run_bench(cfg, jobs, lambda job: scripted_episode(job), progress=False, reports=False)
    with pytest.raises(BenchConfigError, match="cannot import"):
        run_bench(cfg, jobs, "no_such_module_xyz:run", progress=False, reports=False)
    with pytest.raises(BenchConfigError, match="has no"):
        run_bench(cfg, jobs, "test_bench_runner:no_such_function", progress=False, reports=False)
    with pytest.raises(BenchConfigError, match=r"package\.module:function"):
        run_bench(cfg, jobs, "scripted_episode", progress=False, reports=False)


def test_one_out_dir_holds_one_llm(tmp_path: Path) -> None:
    out = tmp_path / "out"
    tasks = [make_task("t1")]
    cfg = config(out, executor="inline", frontends=["llm"], llm="replay:cassettes/a")
    run_bench(cfg, expand_jobs(cfg, tasks), scripted_episode, progress=False, reports=False)
    other = config(out, executor="inline", frontends=["llm"], llm="replay:cassettes/b", resume=True)
    with pytest.raises(BenchConfigError, match="another --out"):
        run_bench(other, expand_jobs(other, tasks), scripted_episode, progress=False, reports=False)
