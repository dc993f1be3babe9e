"""Fast Downward as a subprocess: limits, exit codes, plan files, a content-keyed cache
and a pool of parallel calls.

Fast Downward is GPL-licensed: it runs as a separate process, never imported into ours
(``import up_fast_downward`` would also fail without ``unified_planning``). The driver
script is located through the installed ``up_fast_downward`` package and run with our
interpreter. Exit codes follow Fast Downward's documentation
(https://www.fast-downward.org/latest/documentation/exit-codes/, mirrored in the
driver's ``returncodes.py``).
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import math
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Literal

from emboteam.pddl.errors import (
    PlannerInputError,
    PlannerLimitError,
    PlannerMemoryError,
    PlannerTimeoutError,
    PlanningError,
)

Status = Literal["solved", "unsolvable"]

#: exit codes, from the driver's returncodes.py
SOLVED = frozenset({0, 1, 2, 3})  # 1-3: a plan was found, a later portfolio run hit a limit
UNSOLVABLE = {10: "the translator proved the task unsolvable",
              11: "the search proved the task unsolvable",
              12: "the search ended without a plan (incomplete search)",
              13: "no plan within the cost bound"}
OUT_OF_MEMORY = {20: "translator out of memory", 22: "search out of memory"}
OUT_OF_TIME = {21: "translator out of time", 23: "search out of time",
               24: "search out of memory and time"}
INPUT_ERRORS = {30: "translator critical error", 31: "translator input error",
                32: "search critical error", 33: "search input error",
                34: "search does not support the task's features",
                35: "driver critical error", 36: "driver input error", 37: "driver unsupported"}


@dataclass(frozen=True)
class SolveResult:
    """Outcome of one call: a plan (lower-case action lines, as Fast Downward writes them)
    or a proof/report that none was found."""

    status: Status
    plan: tuple[str, ...] = ()
    exit_code: int = 0
    seconds: float = 0.0
    cached: bool = False
    message: str = ""

    @property
    def solved(self) -> bool:
        return self.status == "solved"


@cache
def driver_path() -> Path:
    """``downward/fast-downward.py`` inside the installed up-fast-downward package."""
    spec = importlib.util.find_spec("up_fast_downward")
    locations = list(spec.submodule_search_locations or []) if spec is not None else []
    for loc in locations:
        candidate = Path(loc) / "downward" / "fast-downward.py"
        if candidate.is_file():
            return candidate
    raise PlannerInputError("Fast Downward is not installed: pip install up-fast-downward")


class PlanCache:
    """Results keyed by sha256 of (configuration, domain, problem): in memory, and in
    ``directory`` (one JSON file per key) when given, so repeated benchmark seeds and
    re-runs skip the planner. Only definite answers are cached, never limits or errors."""

    def __init__(self, directory: Path | str | None = None) -> None:
        self.directory = Path(directory) if directory is not None else None
        self._memory: dict[str, SolveResult] = {}
        self._lock = threading.Lock()
        if self.directory is not None:
            self.directory.mkdir(parents=True, exist_ok=True)

    @staticmethod
    def key(config: str, domain: str, problem: str) -> str:
        h = hashlib.sha256()
        for part in (config, domain, problem):
            h.update(part.encode())
            h.update(b"\0")
        return h.hexdigest()

    def get(self, key: str) -> SolveResult | None:
        with self._lock:
            hit = self._memory.get(key)
        if hit is not None or self.directory is None:
            return hit
        path = self.directory / f"{key}.json"
        try:
            raw = json.loads(path.read_text())
            hit = SolveResult(status=raw["status"], plan=tuple(raw["plan"]), exit_code=raw["exit_code"],
                              message=raw.get("message", ""))
        except (OSError, ValueError, KeyError, TypeError):
            return None
        with self._lock:
            self._memory[key] = hit
        return hit

    def put(self, key: str, result: SolveResult) -> None:
        with self._lock:
            self._memory[key] = result
        if self.directory is not None:
            path = self.directory / f"{key}.json"
            tmp = path.with_suffix(".tmp")
            tmp.write_text(json.dumps({"status": result.status, "plan": list(result.plan),
                                       "exit_code": result.exit_code, "message": result.message}))
            tmp.replace(path)

    def __len__(self) -> int:
        return len(self._memory)


class FastDownward:
    """One planner configuration. Thread-safe: :meth:`solve_many` runs calls in parallel.

    ``alias`` is a Fast Downward alias (``lama-first``, ``seq-opt-lmcut``) or, when it
    contains a parenthesis, a search string passed as ``--search`` (``astar(hmax())``).
    """

    def __init__(self, alias: str = "lama-first", *, time_limit: float = 30.0,
                 memory_limit_mb: int = 2048, cache: PlanCache | None = None) -> None:
        if time_limit <= 0 or memory_limit_mb <= 0:
            raise PlannerInputError("planner time and memory limits must be positive")
        self.alias = alias
        self.time_limit = time_limit
        self.memory_limit_mb = memory_limit_mb
        self.cache = cache
        self._lock = threading.Lock()
        self.calls = 0
        self.cache_hits = 0
        self.seconds = 0.0

    @property
    def config(self) -> str:
        return f"{self.alias}|{self.time_limit}|{self.memory_limit_mb}"

    def command(self, domain_file: str, problem_file: str) -> list[str]:
        limits = ["--overall-time-limit", f"{max(1, math.ceil(self.time_limit))}s",
                  "--overall-memory-limit", f"{self.memory_limit_mb}M", "--plan-file", "sas_plan"]
        base = [sys.executable, str(driver_path()), *limits]
        if "(" in self.alias:
            return [*base, domain_file, problem_file, "--search", self.alias]
        return [*base, "--alias", self.alias, domain_file, problem_file]

    def solve(self, domain: str, problem: str) -> SolveResult:
        """Solve one problem; raise :class:`PlannerLimitError` or :class:`PlannerInputError`
        when Fast Downward cannot answer."""
        key = PlanCache.key(self.config, domain, problem)
        if self.cache is not None:
            hit = self.cache.get(key)
            if hit is not None:
                with self._lock:
                    self.cache_hits += 1
                return SolveResult(status=hit.status, plan=hit.plan, exit_code=hit.exit_code,
                                   cached=True, message=hit.message)
        result = self._run(domain, problem)
        if self.cache is not None:
            self.cache.put(key, result)
        return result

    def solve_many(self, jobs: Sequence[tuple[str, str]], workers: int = 2
                   ) -> list[SolveResult | PlanningError]:
        """Solve (domain, problem) pairs in parallel; each slot holds the result or the
        typed error of that job, in job order."""
        def one(job: tuple[str, str]) -> SolveResult | PlanningError:
            try:
                return self.solve(*job)
            except PlanningError as exc:
                return exc
        if len(jobs) <= 1 or workers <= 1:
            return [one(j) for j in jobs]
        with ThreadPoolExecutor(max_workers=workers) as pool:
            return list(pool.map(one, jobs))

    def _run(self, domain: str, problem: str) -> SolveResult:
        with tempfile.TemporaryDirectory(prefix="emboteam-fd-") as tmp:
            work = Path(tmp)
            (work / "domain.pddl").write_text(domain)
            (work / "problem.pddl").write_text(problem)
            t0 = time.perf_counter()
            try:
                proc = subprocess.run(self.command("domain.pddl", "problem.pddl"), cwd=work,
                                      capture_output=True, text=True,
                                      timeout=self.time_limit + 30.0)
            except subprocess.TimeoutExpired:
                raise PlannerTimeoutError(f"Fast Downward did not stop within {self.time_limit:g} s "
                                          "and was killed") from None
            except OSError as exc:
                raise PlannerInputError(f"cannot run Fast Downward: {exc}") from None
            seconds = time.perf_counter() - t0
            with self._lock:
                self.calls += 1
                self.seconds += seconds
            return interpret(proc.returncode, _read_plan(work), _excerpt(proc), seconds=seconds,
                             time_limit=self.time_limit, memory_limit_mb=self.memory_limit_mb)


def interpret(code: int, plan: tuple[str, ...] | None, message: str, *, seconds: float = 0.0,
              time_limit: float = 0.0, memory_limit_mb: int = 0) -> SolveResult:
    """Fast Downward's exit code as a result (solved, unsolvable) or a typed error."""
    if code in SOLVED:
        if plan is None:
            raise PlannerInputError(f"Fast Downward exited {code} without a plan file: {message}")
        return SolveResult(status="solved", plan=plan, exit_code=code, seconds=seconds)
    if code in UNSOLVABLE:
        return SolveResult(status="unsolvable", exit_code=code, seconds=seconds, message=UNSOLVABLE[code])
    if plan is not None and (code in OUT_OF_TIME or code in OUT_OF_MEMORY):
        # an anytime configuration (lama) found plans before the limit: keep the best
        return SolveResult(status="solved", plan=plan, exit_code=code, seconds=seconds,
                           message="best plan found before the limit")
    if code in OUT_OF_TIME:
        raise PlannerTimeoutError(f"Fast Downward: {OUT_OF_TIME[code]} (limit {time_limit:g} s, exit {code})")
    if code in OUT_OF_MEMORY:
        raise PlannerMemoryError(f"Fast Downward: {OUT_OF_MEMORY[code]} (limit {memory_limit_mb} MB, "
                                 f"exit {code})")
    if code < 0 or code >= 128:
        # a component killed by a signal: the driver exits with the negative signal number
        # (seen as 256 - signal); SIGXCPU is the CPU time limit the driver sets
        sig = -code if code < 0 else 256 - code
        if sig == signal.SIGXCPU:
            raise PlannerTimeoutError(f"Fast Downward: out of time (limit {time_limit:g} s, CPU limit signal)")
        raise PlannerLimitError(f"Fast Downward was killed by signal {sig}: {message}")
    what = INPUT_ERRORS.get(code, "unexpected exit")
    raise PlannerInputError(f"Fast Downward: {what} (exit {code}): {message}")


def _read_plan(work: Path) -> tuple[str, ...] | None:
    """The plan file; anytime configurations write sas_plan.1, .2, ...: the last is best."""
    files = sorted(work.glob("sas_plan.*"), key=lambda p: int(p.suffix[1:]) if p.suffix[1:].isdigit() else -1)
    path = files[-1] if files else work / "sas_plan"
    if not path.is_file():
        return None
    return tuple(line.strip() for line in path.read_text().splitlines()
                 if line.strip() and not line.startswith(";"))


def _excerpt(proc: subprocess.CompletedProcess[str], limit: int = 600) -> str:
    """Fast Downward's own explanation: stderr first, else the last lines of stdout."""
    text = (proc.stderr or "").strip()
    lines = [ln for ln in (proc.stdout or "").splitlines() if ln.strip()]
    interesting = [ln for ln in lines if any(w in ln.lower() for w in ("error", "unsupported", "could not",
                                                                       "undefined", "expected", "mismatch"))]
    if not text:
        text = " | ".join((interesting or lines)[-6:])
    text = " ".join(text.split())
    return text[:limit] + ("..." if len(text) > limit else "")
