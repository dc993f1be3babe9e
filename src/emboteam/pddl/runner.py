"""Fast Downward as a subprocess: limits, exit codes, plan files, a content-keyed cache
and a pool of parallel calls.

Fast Downward is GPL-licensed: it runs as a separate process, never imported into ours
(``import up_fast_downward`` would also fail without ``unified_planning``). Two inputs:

- ``"sas"`` (default): we ground the problem ourselves (:mod:`emboteam.pddl.sas`) and pipe
  the finite-domain task into the *search binary* (``builds/release/bin/downward``), with
  the CPU-time and address-space limits the driver would set (``driver/limits.py``),
  set on the process before the task is written to its stdin. No driver, no
  translator, no second interpreter: a call costs the search itself plus process start.
- ``"pddl"``: the driver script (``fast-downward.py``) with domain and problem files, run
  with our interpreter; the translator grounds. Kept as the reference the SAS path is
  tested against (``tests/test_pddl_sas.py``).

Both executables are located through the installed ``up_fast_downward`` package. Exit
codes follow Fast Downward's documentation
(https://www.fast-downward.org/latest/documentation/exit-codes/, mirrored in the
driver's ``returncodes.py``); the search binary returns the same codes the driver
passes on.
"""

from __future__ import annotations

import atexit
import contextlib
import hashlib
import importlib.util
import json
import math
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Literal

from emboteam.pddl.errors import (
    PlannerInputError,
    PlannerLimitError,
    PlannerMemoryError,
    PlannerTimeoutError,
    PlanningError,
)

if TYPE_CHECKING:
    from emboteam.pddl.problem import Problem

Status = Literal["solved", "unsolvable"]
#: what Fast Downward is given: our own SAS task (search binary only) or PDDL (driver)
PlannerInput = Literal["pddl", "sas"]
PLANNER_INPUTS: tuple[str, ...] = ("sas", "pddl")

#: driver aliases that are one search configuration, as the installed driver defines them
#: (``driver/aliases.py`` of Fast Downward 26.6); with SAS input the search binary gets the
#: configuration itself. Other aliases are portfolios or driver features: use PDDL input.
SEARCH_ALIASES: dict[str, tuple[str, ...]] = {
    "lama-first": (
        "--search",
        "let(hlm, eval_modify_costs(landmark_sum(lm_factory=lm_reasonable_orders_hps(lm_rhw()),pref=false),"
        "cost_type=one),let(hff, eval_modify_costs(ff(),cost_type=one),"
        "lazy_greedy([hff,hlm],preferred=[hff,hlm],cost_type=one,reopen_closed=false)))"),
    "seq-opt-lmcut": ("--search", "astar(lmcut())"),
    # ours, not the driver's: lama-first's heuristics on the action costs (+1, as LAMA's
    # later iterations use them) in a lazy weighted A* (w=5, LAMA's second iteration):
    # with ``action_costs`` it prefers plans of fewer seconds, where greedy search
    # (lama-first) takes the first plan its heuristics lead to (docs/planning.md,
    # "Makespan against the resource-aware bound")
    "lama-wastar5": (
        "--search",
        "let(hlm, eval_modify_costs(landmark_sum(lm_factory=lm_reasonable_orders_hps(lm_rhw()),pref=false),"
        "cost_type=plusone),let(hff, eval_modify_costs(ff(),cost_type=plusone),"
        "lazy_wastar([hff,hlm],preferred=[hff,hlm],w=5)))"),
}
#: the entries of SEARCH_ALIASES the driver does not know (given to it as a search string)
OWN_ALIASES = frozenset({"lama-wastar5"})

#: the second pass for a long plan (``refine_cost``): the same heuristics in lazy A*
#: (w=1), bounded by the first plan's cost (exclusive); what it finds replaces the first
#: plan only when cheaper. No ``max_time``: a search cut off by the clock gives another
#: plan on a loaded machine (issue 28); the runner's time limit is the safety net, and
#: running into it raises :class:`PlannerTimeoutError` rather than keeping the first plan
REFINE_SEARCH = (
    "let(hlm, eval_modify_costs(landmark_sum(lm_factory=lm_reasonable_orders_hps(lm_rhw()),pref=false),"
    "cost_type=plusone),let(hff, eval_modify_costs(ff(),cost_type=plusone),"
    "lazy_wastar([hff,hlm],preferred=[hff,hlm],w=1,bound={bound})))")

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


_POOLS: dict[int, ThreadPoolExecutor] = {}
_POOLS_LOCK = threading.Lock()


def _pool(workers: int) -> ThreadPoolExecutor:
    """One long-lived thread pool per size: starting threads per call cost more than a
    small search (the pool's threads only wait on Fast Downward processes or ground)."""
    with _POOLS_LOCK:
        pool = _POOLS.get(workers)
        if pool is None:
            pool = _POOLS[workers] = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="emboteam-fd")
        return pool


@cache
def search_path() -> Path:
    """Fast Downward's compiled search binary inside the installed package."""
    candidate = driver_path().parent / "builds" / "release" / "bin" / "downward"
    if not candidate.is_file() or not os.access(candidate, os.X_OK):
        raise PlannerInputError(f"Fast Downward's search binary is missing at {candidate}: "
                                "reinstall up-fast-downward")
    return candidate


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
                 memory_limit_mb: int = 2048, cache: PlanCache | None = None,
                 planner_input: PlannerInput = "sas", action_costs: bool = False,
                 refine_cost: int | None = None) -> None:
        if time_limit <= 0 or memory_limit_mb <= 0:
            raise PlannerInputError("planner time and memory limits must be positive")
        if planner_input not in PLANNER_INPUTS:
            raise PlannerInputError(f"planner input must be 'sas' or 'pddl', not {planner_input!r}")
        self.planner_input = planner_input
        #: SAS input only: operators cost their durations (:func:`emboteam.pddl.sas.operator_cost`)
        self.action_costs = action_costs
        #: SAS input with action costs: a plan costing this much or more gets a second,
        #: cost-bounded search (:data:`REFINE_SEARCH`)
        self.refine_cost = refine_cost if action_costs else None
        self.alias = alias
        self.time_limit = time_limit
        self.memory_limit_mb = memory_limit_mb
        self.cache = cache
        self._lock = threading.Lock()
        self.calls = 0
        self.cache_hits = 0
        self.seconds = 0.0
        #: time spent grounding and writing SAS tasks (SAS input only)
        self.ground_seconds = 0.0

    @property
    def config(self) -> str:
        costs = "|costs" if self.action_costs and self.planner_input == "sas" else ""
        if self.refine_cost is not None and costs:
            costs += f"|refine>={self.refine_cost}"
        return f"{self.alias}|{self.time_limit}|{self.memory_limit_mb}{costs}"

    def command(self, domain_file: str, problem_file: str) -> list[str]:
        limits = ["--overall-time-limit", f"{max(1, math.ceil(self.time_limit))}s",
                  "--overall-memory-limit", f"{self.memory_limit_mb}M", "--plan-file", "sas_plan"]
        base = [sys.executable, str(driver_path()), *limits]
        if "(" in self.alias:
            return [*base, domain_file, problem_file, "--search", self.alias]
        if self.alias in OWN_ALIASES:
            return [*base, domain_file, problem_file, *SEARCH_ALIASES[self.alias]]
        return [*base, "--alias", self.alias, domain_file, problem_file]

    def search_args(self) -> list[str]:
        """The search binary's configuration for ``alias`` (SAS input)."""
        if "(" in self.alias:
            return ["--search", self.alias]
        if self.alias not in SEARCH_ALIASES:
            raise PlannerInputError(f"unknown alias {self.alias!r} for SAS input (known: "
                                    f"{', '.join(SEARCH_ALIASES)}; or give a search string such as "
                                    "'astar(hmax())', or use PDDL input, which knows all driver aliases)")
        return list(SEARCH_ALIASES[self.alias])

    def _cached(self, key: str) -> SolveResult | None:
        if self.cache is None:
            return None
        hit = self.cache.get(key)
        if hit is None:
            return None
        with self._lock:
            self.cache_hits += 1
        return SolveResult(status=hit.status, plan=hit.plan, exit_code=hit.exit_code, cached=True,
                           message=hit.message)

    def solve(self, domain: str, problem: str) -> SolveResult:
        """Solve one PDDL problem with the driver (translator, then search); raise
        :class:`PlannerLimitError` or :class:`PlannerInputError` when Fast Downward cannot
        answer."""
        key = PlanCache.key(self.config, domain, problem)
        hit = self._cached(key)
        if hit is not None:
            return hit
        result = self._run(domain, problem)
        if self.cache is not None:
            self.cache.put(key, result)
        return result

    def solve_problem(self, problem: Problem) -> SolveResult:
        """Solve a rendered problem with this runner's input (SAS or PDDL)."""
        if self.planner_input == "pddl":
            from emboteam.pddl.domain import domain_pddl

            return self.solve(domain_pddl(), problem.text)
        from emboteam.pddl.sas import EMITTER_VERSION, emit

        key = PlanCache.key(f"{self.config}|{EMITTER_VERSION}", "sas", problem.text)
        hit = self._cached(key)
        if hit is not None:
            return hit
        args = self.search_args()  # an unknown alias fails before any work
        t0 = time.perf_counter()
        task = emit(problem, costs=self.action_costs)
        with self._lock:
            self.ground_seconds += time.perf_counter() - t0
        if task.verdict == "trivial":
            result = SolveResult(status="solved", plan=(), message="the goal holds in every state")
        elif task.verdict == "unreachable":
            result = SolveResult(status="unsolvable", exit_code=10,
                                 message="relaxed reachability proves the goal unreachable")
        else:
            result = self.solve_sas(task.text, args)
            if self.refine_cost is not None and result.solved:
                result = self._refined(task.text, result)
        if self.cache is not None:
            self.cache.put(key, result)
        return result

    def _refined(self, sas: str, first: SolveResult) -> SolveResult:
        """A cheaper plan than ``first`` from :data:`REFINE_SEARCH` when ``first`` is long."""
        from emboteam.pddl.sas import plan_cost

        cost = plan_cost(first.plan)
        if cost < (self.refine_cost or 0):
            return first
        search = REFINE_SEARCH.format(bound=cost)
        try:
            second = self.solve_sas(sas, ["--search", search])
        except PlannerTimeoutError:
            raise  # the safety net: which plan a cut-off search leaves depends on the machine
        except PlanningError:
            return first
        if second.solved and plan_cost(second.plan) < cost:
            return second
        return first

    def solve_problems(self, problems: Sequence[Problem], workers: int = 2,
                       then: Callable[[Problem, SolveResult], None] | None = None
                       ) -> list[SolveResult | PlanningError]:
        """:meth:`solve_problem` for several problems in parallel (grounding of one overlaps
        the search of another); each slot holds the result or the typed error. ``then`` is
        called with each distinct problem and its result, in the worker that solved it:
        the caller's own work on a plan overlaps the searches still running (it must not
        raise, and must give the same answer on whichever thread it runs)."""
        def one(p: Problem) -> SolveResult | PlanningError:
            try:
                result = self.solve_problem(p)
            except PlanningError as exc:
                return exc
            if then is not None:
                then(p, result)
            return result
        # the same problem twice is solved once: two threads missing the cache together
        # would both run it, and the count of calls (a budget of the planner's) would
        # depend on which thread got there first
        distinct = list(dict.fromkeys(p.text for p in problems))
        first = {p.text: p for p in reversed(problems)}
        if len(distinct) <= 1 or workers <= 1:
            solved = [one(first[t]) for t in distinct]
        else:
            solved = list(_pool(workers).map(one, [first[t] for t in distinct]))
        by_text = dict(zip(distinct, solved, strict=True))
        return [by_text[p.text] for p in problems]

    def solve_sas(self, sas: str, args: Sequence[str] | None = None) -> SolveResult:
        """Run the search binary on a SAS task (``output.sas`` text) given on its stdin."""
        cmd = [str(search_path()), *(args if args is not None else self.search_args()),
               "--internal-plan-file", "sas_plan"]
        seconds_limit = max(1, math.ceil(self.time_limit))
        memory = self.memory_limit_mb * 1024 * 1024
        # the limits driver/limits.py sets (CPU: soft = limit, hard = limit + 1; address
        # space), set on the started process from outside: a preexec_fn is unsafe with the
        # threads solve_problems uses, and the search reads its task (stdin, written below)
        # before it allocates or computes anything that matters. (util-linux's prlimit as a
        # wrapper would set them before the exec, at the cost of a second exec per call.)
        work = _workdir()
        _clear_plans(work)
        t0 = time.perf_counter()
        try:
            proc = subprocess.Popen(cmd, cwd=work, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE, text=True)
        except OSError as exc:
            raise PlannerInputError(f"cannot run Fast Downward's search: {exc}") from None
        try:
            resource.prlimit(proc.pid, resource.RLIMIT_CPU, (seconds_limit, seconds_limit + 1))
            resource.prlimit(proc.pid, resource.RLIMIT_AS, (memory, memory))
        except (ProcessLookupError, PermissionError, ValueError, OSError):
            pass  # it already exited (bad options): its exit code says why
        # a wall-clock guard on top of the CPU limit (a search stuck without using CPU).
        # communicate() with a timeout would poll for the exit with sleeps of 0.5 ms and
        # more after the output ends; without one it waits for the exit itself
        killed = threading.Event()

        def kill() -> None:
            killed.set()
            proc.kill()

        guard = threading.Timer(self.time_limit + 30.0, kill)
        guard.daemon = True
        guard.start()
        try:
            out, err = proc.communicate(sas)
        finally:
            guard.cancel()
        if killed.is_set():
            _clear_plans(work)
            raise PlannerTimeoutError(f"Fast Downward did not stop within {self.time_limit:g} s "
                                      "and was killed")
        seconds = time.perf_counter() - t0
        with self._lock:
            self.calls += 1
            self.seconds += seconds
        done = subprocess.CompletedProcess(cmd, proc.returncode, out, err)
        plan = _read_plan(work)
        _clear_plans(work)
        if loader_ran_out(proc.returncode, err or ""):
            # the dynamic loader could not map the binary within the address-space limit
            raise PlannerMemoryError(f"Fast Downward's search cannot even start within {self.memory_limit_mb} MB: "
                                     f"{_excerpt(done)}")
        return interpret(proc.returncode, plan, _excerpt(done), seconds=seconds,
                         time_limit=self.time_limit, memory_limit_mb=self.memory_limit_mb)

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
        return list(_pool(workers).map(one, jobs))

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


#: what glibc's dynamic loader says (exit 127) when the address-space limit leaves it no room
#: to map the binary's libraries or its first thread's TLS: which one a machine hits varies
_LOADER_OUT_OF_MEMORY = ("shared libraries", "cannot allocate TLS")


def loader_ran_out(code: int, stderr: str) -> bool:
    """Did the binary fail to start because the memory limit left the loader no room?"""
    return code == 127 and any(m in stderr for m in _LOADER_OUT_OF_MEMORY)


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


_WORKDIRS = threading.local()


def _workdir() -> Path:
    """This thread's working directory for search processes (their plan files), made
    once per thread and process and kept: creating and removing a directory per call
    cost about 3 ms on the machine this was measured on (ext4 /tmp), a plan file in a
    kept one 0.04 ms. A forked child makes its own (it must not share plan files with
    its parent). Removed at exit by the process that made it (a child that leaves with
    ``os._exit`` leaves its empty directory behind)."""
    pid = os.getpid()
    held: tuple[int, Path] | None = getattr(_WORKDIRS, "held", None)
    if held is not None and held[0] == pid and held[1].is_dir():
        return held[1]
    work = Path(tempfile.mkdtemp(prefix="emboteam-fd-"))
    _WORKDIRS.held = (pid, work)
    atexit.register(_remove_workdir, pid, work)
    return work


def _remove_workdir(pid: int, work: Path) -> None:
    if os.getpid() == pid:
        shutil.rmtree(work, ignore_errors=True)


def _clear_plans(work: Path) -> None:
    """Remove the plan files of a finished call (``sas_plan``, ``sas_plan.N``)."""
    for path in work.glob("sas_plan*"):
        with contextlib.suppress(OSError):
            path.unlink()


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
