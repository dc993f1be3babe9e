"""The evaluation runner behind ``emboteam bench``: runs jobs on workers, stores every
episode as it finishes, resumes a killed run, and writes the tables and plots.

Guarantees (docs/benchmarking.md):

- every finished episode is committed to ``DIR/results.sqlite`` and saved under
  ``DIR/episodes/<job dir>/`` before the next result is taken, so a killed run loses only
  the episodes that were running;
- ``resume=True`` skips every job whose key is stored and runs the rest once, the ones
  the kill interrupted included;
- an exception inside an episode, or a worker process that dies, becomes a recorded
  failed episode carrying the error; the run goes on.

Executors: ``local`` (a ``ProcessPoolExecutor`` of ``workers`` processes; the default),
``ray`` (:mod:`emboteam.bench.ray_executor`) and ``inline`` (this process, one job at a
time: for debugging, and for episode functions that cannot be pickled).
"""

from __future__ import annotations

import json
import logging
import multiprocessing
import os
import pickle
import re
import signal
import sys
import threading
import time
from collections import deque
from collections.abc import Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager
from pathlib import Path
from types import TracebackType
from typing import Protocol

from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TaskID,
    TextColumn,
    TimeElapsedColumn,
)

from emboteam.bench.jobs import (
    BenchConfig,
    BenchConfigError,
    EpisodeFn,
    Job,
    JobResult,
    execute_job,
    failed_episode,
    resolve_episode_fn,
)
from emboteam.bench.store import ResultStore, ResultStoreError
from emboteam.errors import EXIT_INTERRUPTED, EmboTeamError
from emboteam.exec.episode import Episode

log = logging.getLogger(__name__)

#: the episode function ``emboteam bench`` uses: the full pipeline, by import path so that
#: local worker processes and Ray nodes import it themselves
PIPELINE_EPISODE_FN = "emboteam.bench.runner:pipeline_episode"

STORE_NAME = "results.sqlite"
#: the store's meta entry listing the tasks a disturbance does not apply to
NOT_APPLICABLE = "not_applicable"
EPISODES_DIR = "episodes"


def pipeline_episode(job: Job) -> Episode:
    """Plan and execute one job with :func:`emboteam.pipeline.run_episode` (a job is its
    own episode configuration)."""
    from emboteam.pipeline import (
        run_episode,  # a worker imports the pipeline, the runner's parent does not need to
    )

    return run_episode(job.task, job)


# --------------------------------------------------------------------------- executors

class JobExecutor(Protocol):
    """Where jobs run. The runner hands out jobs while :meth:`has_capacity` and collects
    them with :meth:`wait`; an executor never raises for a failing job, it returns a
    :class:`JobResult` holding a failed episode."""

    def has_capacity(self) -> bool: ...

    def busy(self) -> bool: ...

    def submit(self, job: Job) -> None: ...

    def wait(self) -> list[tuple[Job, JobResult]]: ...

    def close(self) -> None: ...


class InlineExecutor:
    """Runs each job in this process when it is collected."""

    def __init__(self, episode_fn: EpisodeFn) -> None:
        self._fn = episode_fn
        self._queue: deque[Job] = deque()

    def has_capacity(self) -> bool:
        return not self._queue

    def busy(self) -> bool:
        return bool(self._queue)

    def submit(self, job: Job) -> None:
        self._queue.append(job)

    def wait(self) -> list[tuple[Job, JobResult]]:
        job = self._queue.popleft()
        return [(job, execute_job(self._fn, job))]

    def close(self) -> None:
        self._queue.clear()


def worker_died(job: Job, detail: str) -> JobResult:
    """The result of a job whose worker process died under it (segfault, OOM kill, exit)."""
    return JobResult(key=job.key, episode=failed_episode(job, f"WorkerDied: {detail}"),
                     traceback=detail)


class ProcessExecutor:
    """A ``ProcessPoolExecutor`` of ``workers`` spawned processes.

    At most ``workers`` jobs are in flight, so "handed to a worker" means "running".
    When a worker dies the pool breaks and every job in flight on it is lost with it;
    those jobs are re-run one at a time on a new pool, so the one that kills its worker
    again is recorded as failed and the others are not blamed for it.
    """

    def __init__(self, episode_fn: EpisodeFn, workers: int) -> None:
        self._fn = episode_fn
        self._workers = workers
        # spawn, not fork: the runner has threads (the progress bar), and forking a
        # threaded process can deadlock the child
        self._ctx = multiprocessing.get_context("spawn")
        _quiet_resource_tracker()
        self._pool = self._new_pool()
        self._generation = 0  # which pool a future belongs to: only a broken pool's jobs are lost
        self._running: dict[Future[JobResult], tuple[Job, int]] = {}
        self._suspects: deque[Job] = deque()
        self._isolating = False

    def _new_pool(self) -> ProcessPoolExecutor:
        return ProcessPoolExecutor(max_workers=self._workers, mp_context=self._ctx,
                                   initializer=_exit_with_parent, initargs=(os.getpid(),))

    def _replace_pool(self) -> None:
        self._pool.shutdown(wait=False, cancel_futures=True)
        self._pool = self._new_pool()
        self._generation += 1

    def has_capacity(self) -> bool:
        return not self._suspects and not self._isolating and len(self._running) < self._workers

    def busy(self) -> bool:
        return bool(self._running or self._suspects)

    def submit(self, job: Job) -> None:
        with _workers_start_ignoring_sigint():  # the pool starts its processes on submit
            try:
                future = self._pool.submit(execute_job, self._fn, job)
            except BrokenProcessPool:
                # a worker died since the last wait(); the jobs it took down are collected by
                # wait() from their futures, this one never started
                self._replace_pool()
                future = self._pool.submit(execute_job, self._fn, job)
        self._running[future] = (job, self._generation)

    def wait(self) -> list[tuple[Job, JobResult]]:
        if not self._running:
            self._isolating = True
            self.submit(self._suspects.popleft())
        done, _ = wait(list(self._running), return_when=FIRST_COMPLETED)
        results: list[tuple[Job, JobResult]] = []
        lost: list[Job] = []
        broken: set[int] = set()
        for future in done:
            job, generation = self._running.pop(future)
            try:
                results.append((job, future.result()))
            except BrokenProcessPool:
                lost.append(job)
                broken.add(generation)
        if broken:
            # the rest of a broken pool's jobs are lost too, unless they finished just now
            for future, (job, generation) in list(self._running.items()):
                if generation in broken:
                    del self._running[future]
                    if future.done() and future.exception() is None:
                        results.append((job, future.result()))
                    else:
                        lost.append(job)
            if self._generation in broken:
                self._replace_pool()
        if self._isolating and not self._running:
            self._isolating = False
        if len(lost) == 1:
            # it was alone on its pool, so it is the one that killed its worker
            results.append((lost[0], worker_died(lost[0], "the worker process died while running it")))
        elif lost:
            log.warning("a worker process died; re-running its %d jobs one at a time", len(lost))
            self._suspects.extend(lost)
        return results

    def close(self) -> None:
        if self._running:
            # the run is being abandoned (an error, Ctrl-C): do not wait for episodes whose
            # results nobody will record. ProcessPoolExecutor has no public way to stop
            # running workers before Python 3.14 (terminate_workers), hence _processes.
            stop = getattr(self._pool, "terminate_workers", None)
            if callable(stop):
                stop()
            else:
                for process in list((getattr(self._pool, "_processes", None) or {}).values()):
                    process.terminate()
        self._pool.shutdown(wait=True, cancel_futures=True)


@contextmanager
def _workers_start_ignoring_sigint() -> Iterator[None]:
    """Processes started in this block ignore SIGINT from their first instruction.

    Ctrl-C reaches the whole process group, and a worker still importing EmboTeam (before
    the pool's initializer sets SIG_IGN) would die of it with a KeyboardInterrupt trace. An
    ignored signal stays ignored across fork and exec, and Python then installs no
    KeyboardInterrupt handler. The runner's own Ctrl-C is blocked meanwhile, not lost: it
    is delivered when the block ends."""
    if threading.current_thread() is not threading.main_thread():
        yield  # signal dispositions can only be changed from the main thread
        return
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


_TRACKER_WARNING = "ignore:resource_tracker:UserWarning"


def _quiet_resource_tracker() -> None:
    """Keep the resource tracker from warning about "leaked semaphore objects" when the
    runner is SIGKILLed (or Ctrl-C kills its workers mid-queue).

    The pool's queues hold POSIX semaphores that a killed process cannot release; the
    tracker process is there to release them, and does, but says so on the terminal after
    the shell prompt is back. It starts with the runner's ``-W`` options
    (``multiprocessing.util._args_from_interpreter_flags``), so this filter, added before
    the first pool starts it, silences only that message of that process; the clean-up
    itself still runs."""
    if _TRACKER_WARNING not in sys.warnoptions:
        sys.warnoptions.append(_TRACKER_WARNING)


def _exit_with_parent(parent: int, every: float = 0.5) -> None:
    """Worker initializer: end this worker when the runner dies.

    A worker of a SIGKILLed runner would otherwise wait on its task queue for ever (it
    holds both ends of the pipe, so it never sees end-of-file) and keep running episodes
    nobody records."""

    # Ctrl-C reaches the whole process group: the runner handles it (it stops the
    # workers and says what is saved); a worker would only add a KeyboardInterrupt trace
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    from emboteam.logs import configure

    configure()  # the runner's -v level (EMBOTEAM_LOG_VERBOSITY): no log lines on stderr by default

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(every)
        os._exit(1)

    threading.Thread(target=watch, name="exit-with-parent", daemon=True).start()


def make_executor(config: BenchConfig, episode_fn: EpisodeFn) -> JobExecutor:
    if config.executor == "inline":
        return InlineExecutor(episode_fn)
    _check_picklable(episode_fn, config.executor)
    if config.executor == "ray":
        from emboteam.bench.ray_executor import RayExecutor

        return RayExecutor(episode_fn, config.workers, address=config.ray_address)
    return ProcessExecutor(episode_fn, config.workers)


def _check_picklable(episode_fn: EpisodeFn, executor: str) -> None:
    if isinstance(episode_fn, str):
        return
    try:
        pickle.dumps(episode_fn)
    except (pickle.PicklingError, AttributeError, TypeError) as exc:
        raise BenchConfigError(
            f"the {executor} executor sends the episode function to other processes, and "
            f"{getattr(episode_fn, '__qualname__', episode_fn)!r} cannot be pickled ({exc}); give a "
            "module-level function or its import path package.module:function") from None


# --------------------------------------------------------------------------- progress

class _Progress:
    """done/total, SR so far, errors and ETA on stderr: a rich progress bar on a terminal,
    one plain line per episode otherwise (CI logs, ``2> file``), log records when quiet.

    A resumed run says so first ("resuming: N of M ..."). The ETA is the remaining
    episodes times the mean wall time of the episodes this run finished, shared among the
    workers: neither the stored episodes nor the workers' start-up (imports, the first
    planner call) count, so the first estimate is not dominated by start-up."""

    def __init__(self, total: int, previous: Sequence[Episode], enabled: bool, workers: int = 1) -> None:
        self.total, self.done = total, len(previous)
        self.successes = sum(e.success for e in previous)
        self.errors = sum(e.error is not None for e in previous)
        self._resumed = self.done
        self._workers = max(1, workers)
        self._episode_seconds = 0.0  # wall time of the episodes this run finished
        self._console = Console(stderr=True) if enabled else None
        self._bar: Progress | None = None
        self._task: TaskID | None = None
        if self._console is not None and self._console.is_terminal:
            self._bar = Progress(
                TextColumn("[bold]bench"), BarColumn(), MofNCompleteColumn(),
                TextColumn("SR {task.fields[sr]}"), TextColumn("{task.fields[errors]}"),
                TimeElapsedColumn(), TextColumn("ETA {task.fields[eta]}"),
                console=self._console, transient=False,
            )
            self._task = self._bar.add_task("bench", total=total, completed=self.done, sr=self._sr(),
                                            errors=self._errors(), eta=self._eta())

    def _sr(self) -> str:
        return f"{self.successes / self.done:.1%}" if self.done else "-"

    def _errors(self) -> str:
        return f"errors {self.errors}" if self.errors else ""

    def _eta(self) -> str:
        ran = self.done - self._resumed
        if not ran:
            return "-"
        remaining = self.total - self.done
        seconds = round(self._episode_seconds / ran * remaining / min(self._workers, max(remaining, 1)))
        return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"

    def resuming(self) -> str | None:
        """What a resumed run continues, or None for a fresh one."""
        if not self._resumed:
            return None
        return f"resuming {self.total - self._resumed} of {self.total} episodes ({self._resumed} already stored)"

    def __enter__(self) -> _Progress:
        line = self.resuming()
        if line is not None:
            if self._console is not None:
                self._console.print(line, markup=False, highlight=False, soft_wrap=True)
            else:
                log.info("%s", line)
        if self._bar is not None:
            self._bar.start()
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        if self._bar is not None:
            self._bar.stop()

    def finished(self, job: Job, episode: Episode) -> None:
        self.done += 1
        self.successes += int(episode.success)
        self.errors += int(episode.error is not None)
        self._episode_seconds += episode.wall_seconds
        if self._bar is not None and self._task is not None:
            self._bar.update(self._task, advance=1, sr=self._sr(), errors=self._errors(), eta=self._eta())
            return
        outcome = "success" if episode.success else "failure"
        error = f" ({episode.error})" if episode.error else ""
        if self._console is not None:
            self._console.print(f"[{self.done}/{self.total}] {job.key}: {outcome}{error}  SR {self._sr()}  "
                                f"ETA {self._eta()}", markup=False, highlight=False, soft_wrap=True)
        else:
            log.info("[%d/%d] %s: %s%s", self.done, self.total, job.key, outcome, error)


# --------------------------------------------------------------------------- the run

def store_path(out_dir: Path) -> Path:
    return Path(out_dir) / STORE_NAME


class BenchInterrupted(EmboTeamError):
    """Ctrl-C during a run. The episodes finished so far are stored; ``saved`` says how
    many, so the user knows what ``--resume`` will skip."""

    exit_code = EXIT_INTERRUPTED

    def __init__(self, out_dir: Path, saved: int, total: int) -> None:
        super().__init__(f"interrupted: {saved} of {total} episodes are saved in {out_dir}")
        self.out_dir, self.saved, self.total = Path(out_dir), saved, total


def default_out_dir(config: BenchConfig, *, root: Path = Path("bench-out"), now: float | None = None) -> Path:
    """``bench-out/<suite>_<modes>_<front ends>_f<faults>_s<seeds>_<YYYYmmdd-HHMMSS>``: a
    new folder per run without ``--out``, so a second run never meets the first one's
    results (``--out DIR`` stays strict). ``-2``, ``-3`` ... if that second is taken."""
    stamp = time.strftime("%Y%m%d-%H%M%S", time.localtime(now))
    suite = Path(config.suite.removeprefix("smart-llm:").rstrip("/")).name or config.suite
    if config.suite.startswith("smart-llm:"):
        suite = f"smart-llm-{suite}"
    parts = [suite, "+".join(config.modes), "+".join(config.frontends),
             "f" + "+".join(f"{p:g}" for p in config.fault_levels), f"s{config.seeds}", stamp]
    name = "_".join(re.sub(r"[^A-Za-z0-9.+=-]+", "-", part) for part in parts)
    candidate, n = root / name, 1
    while candidate.exists():
        n += 1
        candidate = root / f"{name}-{n}"
    return candidate


def run_bench(config: BenchConfig, jobs: Sequence[Job], episode_fn: EpisodeFn = PIPELINE_EPISODE_FN,
              *, progress: bool = True, reports: bool = True, not_applicable: Sequence[str] = ()) -> list[Episode]:
    """Run every job not yet in ``config.out_dir``'s store; return the episodes of all
    ``jobs`` (stored earlier or now) in job order, then write tables and plots.
    ``not_applicable``: ``"TASK: why"`` of the tasks the disturbance cannot happen in
    (bench/disturbance_scope.py), kept in the store and listed in the tables.

    Without ``config.resume`` an out dir that already holds results is refused, so a run
    never mixes into another by accident.
    """
    out_dir = Path(config.out_dir)
    unique = list({job.key: job for job in jobs}.values())
    resolve_episode_fn(episode_fn)  # a bad import path fails here, before any worker starts
    if config.executor == "ray":  # fail before the store exists when Ray is not installed
        from emboteam.bench.ray_executor import _import_ray, probe_address

        _import_ray()
        probe_address(config.ray_address)  # a cluster that does not answer: exit 3 in seconds
    fresh = not store_path(out_dir).exists()
    try:
        episodes = _run_stored(config, unique, episode_fn, out_dir, progress, not_applicable)
    except EmboTeamError as exc:
        if fresh and not isinstance(exc, BenchInterrupted):
            _drop_empty_store(out_dir)  # a refused run (an executor that cannot start) leaves nothing
        raise
    if reports:
        write_reports(out_dir)
    return episodes


def _drop_empty_store(out_dir: Path) -> None:
    path = store_path(out_dir)
    if not path.exists():
        return
    with ResultStore(path) as store:
        if len(store):
            return
    for leftover in (path, path.with_name(path.name + "-wal"), path.with_name(path.name + "-shm"),
                     path.with_name(path.name + "-journal")):
        leftover.unlink(missing_ok=True)


def _run_stored(config: BenchConfig, unique: list[Job], episode_fn: EpisodeFn, out_dir: Path,
                progress: bool, not_applicable: Sequence[str] = ()) -> list[Episode]:
    with ResultStore(store_path(out_dir)) as store:
        stored = len(store)
        if stored and not config.resume:
            raise BenchConfigError(f"{out_dir} already holds {stored} results: pass --resume to "
                                   "continue that run, or choose another --out")
        _check_same_llm(store, config)
        done = store.done_keys()
        pending = [job for job in unique if job.key not in done]
        interrupted = store.interrupted_keys() & {job.key for job in pending}
        if interrupted:
            log.info("%d jobs the last run left unfinished are run again", len(interrupted))
        store.set_meta("config", config.model_dump_json())
        store.set_meta(NOT_APPLICABLE, json.dumps(list(not_applicable)))
        previous = store.episodes(keys={j.key for j in unique})
        if pending:
            try:
                _run_pending(config, pending, episode_fn, store, out_dir,
                             _Progress(len(unique), previous, progress, workers=config.workers))
            except KeyboardInterrupt:
                saved = len(store.done_keys() & {j.key for j in unique})
                raise BenchInterrupted(out_dir, saved, len(unique)) from None
        by_key = {r.key: r.episode for r in store.results(keys={j.key for j in unique})}
        return [by_key[job.key] for job in unique]


def _check_same_llm(store: ResultStore, config: BenchConfig) -> None:
    """Episodes do not record the LLM spec, so tables pool everything in a store by mode
    and front end: one out dir must hold one LLM's results."""
    stored = store.llm_specs()
    if stored and stored != {config.llm}:
        shown = ", ".join(sorted(s or "none" for s in stored))
        raise BenchConfigError(f"{config.out_dir} holds results of --llm {shown}, not "
                               f"{config.llm or 'none'}: use another --out for another LLM")


def _run_pending(config: BenchConfig, pending: list[Job], episode_fn: EpisodeFn, store: ResultStore,
                 out_dir: Path, bar: _Progress) -> None:
    queue = deque(pending)
    executor = make_executor(config, episode_fn)
    try:
        with bar:
            while queue or executor.busy():
                while queue and executor.has_capacity():
                    job = queue.popleft()
                    store.mark_started(job)
                    executor.submit(job)
                for job, result in executor.wait():
                    _record(store, out_dir, job, result)
                    bar.finished(job, result.episode)
    except BaseException:
        _close_abandoned(executor)
        raise
    executor.close()


def _close_abandoned(executor: JobExecutor) -> None:
    """Stop the workers of a run an error or Ctrl-C ended. A failure to stop them is logged,
    not raised: it would replace the error the user must see (Ctrl-C exiting 70, not 130)."""
    try:
        executor.close()
    except Exception:
        log.warning("the benchmark's workers did not stop cleanly", exc_info=True)


def _record(store: ResultStore, out_dir: Path, job: Job, result: JobResult) -> None:
    """Trace files first, then the row: a row always points at a complete episode dir."""
    relative = f"{EPISODES_DIR}/{job.dirname}"
    try:
        result.episode.save(out_dir / relative)
    except OSError as exc:
        raise ResultStoreError(f"cannot write the episode of {job.key} to {out_dir / relative}: {exc}") from None
    store.add(job, result.episode, episode_dir=relative, traceback=result.traceback)


def write_reports(out_dir: Path) -> list[Path]:
    """``DIR/tables.md``, ``DIR/summary.json`` and the PNG plots from everything in the
    store of ``out_dir`` (what ``emboteam report`` rebuilds after a run)."""
    from emboteam.bench.plots import write_plots
    from emboteam.bench.tables import GroupSummaries, write_summary, write_tables

    out_dir = Path(out_dir)
    path = store_path(out_dir)
    if not path.exists():
        raise ResultStoreError(f"{out_dir} holds no benchmark results ({STORE_NAME} is missing)")
    with ResultStore(path) as store:
        episodes = store.episodes()
        suite = _suite_name(store)
        skipped = stored_not_applicable(store)
    summaries = GroupSummaries(episodes)
    written = [write_tables(summaries, out_dir / "tables.md", not_applicable=skipped),
               write_summary(episodes, out_dir / "summary.json", suite=suite, not_applicable=skipped)]
    written += write_plots(summaries, out_dir)
    return written


def stored_not_applicable(store: ResultStore) -> list[str]:
    """The ``"TASK: why"`` lines of the tasks the run's disturbance did not apply to."""
    text = store.meta(NOT_APPLICABLE)
    return list(json.loads(text)) if text else []


def _suite_name(store: ResultStore) -> str:
    config = store.meta("config")
    if config is None:
        return ""
    return BenchConfig.model_validate_json(config).suite

