"""Benchmark jobs: what one episode of a benchmark run is, and how a run expands into them.

A :class:`Job` is (suite, task id, mode, front end, LLM spec or None, seed, fault level);
its :attr:`Job.key` is a stable string built from exactly those seven values, so the
results store can tell which jobs a killed run already finished. The job also carries the
whole :class:`BenchTask`, so a worker (a local process or a Ray node) can run it without
loading the suite again.

This module is what a worker imports: it does not pull in rich, matplotlib or SQLite.
"""

from __future__ import annotations

import hashlib
import importlib
import os
import re
import time
import traceback
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Literal, TypeAlias

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from emboteam.config import ABLATIONS, BASELINES, LLM_FRONTENDS, EnvName, Frontend, LLMWhen, Mode, RunConfig
from emboteam.errors import EmboTeamError
from emboteam.exec.episode import Episode, episode_header
from emboteam.pddl.runner import PlannerInput
from emboteam.sim.disturbances import Disturbances
from emboteam.task import BenchTask
from emboteam.world.robots import parse_team

ExecutorName = Literal["local", "ray", "inline"]

#: an episode function: a module-level callable, or its import path ``package.module:function``
EpisodeFn: TypeAlias = "Callable[[Job], Episode] | str"


class BenchConfigError(EmboTeamError):
    """A benchmark configuration that cannot run (bad mode, fault level, episode function)."""


class Job(RunConfig):
    """One episode of a benchmark run: its task and its episode configuration (a job *is*
    the :class:`RunConfig` the pipeline runs, so no option is lost between the two)."""

    model_config = ConfigDict(frozen=True)

    task: BenchTask
    seed: int = Field(0, ge=0)
    llm_timeout: float = Field(60.0, gt=0)

    @model_validator(mode="after")
    def _llm_needs_spec(self) -> Job:
        if self.frontend in LLM_FRONTENDS and not self.llm:
            raise ValueError(f"the {self.frontend} front end needs an LLM spec (--llm PROVIDER:MODEL)")
        return self

    @property
    def suite(self) -> str:
        return self.task.suite

    @property
    def task_id(self) -> str:
        return self.task.id

    @property
    def key(self) -> str:
        """``SUITE/ID|mode|frontend|llm|seed=N|faults=P``: stable across runs and machines
        (``repr`` of a float round-trips, so two different fault levels never share a key)."""
        parts = [self.task.key, self.mode, self.frontend, self.llm or "-",
                 f"seed={self.seed}", f"faults={float(self.fault_level)!r}"]
        if self.llm_when != "doubt":  # keys of the configurations that existed before stay as they were
            parts.append(f"llm-when={self.llm_when}")
        if self.planner_input != "sas":
            parts.append(f"planner-input={self.planner_input}")
        if self.schedule != "fast":
            parts.append(f"schedule={self.schedule}")
        if not self.close_after_use:
            parts.append("leave-open")
        if self.disturbance.any:  # likewise: undisturbed keys stay as they were
            parts.append(f"disturb={self.disturbance.label}")
        if self.env != "sim":  # likewise: simulator keys stay as they were
            parts.append(f"env={self.env}")
        return "|".join(parts)

    @property
    def dirname(self) -> str:
        """The key as one safe directory name, unique per key.

        Suites and LLM specs may hold ``/``, ``:`` or ``@``; those become ``_`` and a
        short hash of the exact key keeps two keys that differ only there apart."""
        safe = re.sub(r"[^A-Za-z0-9._=-]+", "_", self.key.replace("|", "__")).strip("._")
        digest = hashlib.sha1(self.key.encode()).hexdigest()[:8]
        return f"{safe[:150]}-{digest}"


class BenchConfig(BaseModel):
    """A benchmark run: which modes, front ends, seeds and fault levels, and where and how
    to run them (the options of ``emboteam bench``)."""

    model_config = ConfigDict(frozen=True)

    suite: str
    modes: tuple[Mode, ...] = ("full",)
    frontends: tuple[Frontend, ...] = ("offline",)
    llm: str | None = None
    seeds: int = Field(1, ge=1, description="seeds 0..N-1")
    fault_levels: tuple[float, ...] = (0.0,)
    workers: int = Field(default_factory=lambda: max(1, os.cpu_count() or 1), ge=1)
    executor: ExecutorName = "local"
    ray_address: str | None = Field(None, description="ray.init address; None starts Ray locally")
    env: EnvName = "sim"
    out_dir: Path = Path("bench-out")
    resume: bool = False
    planner_input: PlannerInput = "sas"
    schedule: Literal["fast", "optimal"] = "fast"
    close_after_use: bool = True
    llm_timeout: float = Field(60.0, gt=0)
    llm_when: LLMWhen = "doubt"

    disturbance: Disturbances = Field(default_factory=Disturbances)

    @field_validator("modes", "frontends", "fault_levels")
    @classmethod
    def _non_empty_unique(cls, value: tuple[object, ...]) -> tuple[object, ...]:
        if not value:
            raise ValueError("must not be empty")
        return tuple(dict.fromkeys(value))

    @field_validator("fault_levels")
    @classmethod
    def _probabilities(cls, value: tuple[float, ...]) -> tuple[float, ...]:
        for p in value:
            if not 0.0 <= p <= 1.0:
                raise ValueError(f"fault level {p} is not a probability in [0, 1]")
        return value

    @model_validator(mode="after")
    def _llm_needs_spec(self) -> BenchConfig:
        needs = [f for f in self.frontends if f in LLM_FRONTENDS]
        if needs and not self.llm:
            raise ValueError(f"the {needs[0]} front end needs an LLM spec (--llm PROVIDER:MODEL)")
        return self

    @classmethod
    def build(cls, **fields: object) -> BenchConfig:
        """Like the constructor, but a bad option is a :class:`BenchConfigError` (one line
        for the CLI) rather than a pydantic traceback."""
        try:
            return cls.model_validate(fields)
        except ValidationError as exc:
            raise BenchConfigError(_one_line(exc)) from None


def _one_line(exc: ValidationError) -> str:
    parts = []
    for err in exc.errors():
        where = ".".join(str(p) for p in err["loc"]) or "config"
        parts.append(f"{where}: {err['msg']}")
    return "invalid benchmark configuration: " + "; ".join(parts)


def modes_from_options(ablations: Sequence[str] = (), baselines: Sequence[str] = ()) -> tuple[Mode, ...]:
    """The modes of ``--ablation A`` (repeatable; default ``full``) and ``--baseline B``
    (repeatable): ``--baseline smart-llm`` runs EmboTeam and SMART-LLM, ``--ablation no-hp``
    runs only no-hp (add ``--ablation full`` for Table 2's reference row)."""
    chosen: list[Mode] = []
    for name in ablations or ("full",):
        if name not in ABLATIONS:
            hint = " (a baseline: use --baseline)" if name in BASELINES else ""
            raise BenchConfigError(f"unknown ablation {name!r}{hint}; use one of {', '.join(ABLATIONS)}")
        chosen.append(name)
    for name in baselines:
        if name not in BASELINES:
            hint = " (an ablation: use --ablation)" if name in ABLATIONS else ""
            raise BenchConfigError(f"unknown baseline {name!r}{hint}; use one of {', '.join(BASELINES)}")
        chosen.append(name)
    return tuple(dict.fromkeys(chosen))


def parse_fault_levels(values: Iterable[str | float]) -> tuple[float, ...]:
    """``--faults`` values, each a number or a comma-separated list: ``["0", "0.1,0.2"]``."""
    levels: list[float] = []
    for value in values:
        items = value.split(",") if isinstance(value, str) else [value]
        for item in items:
            if isinstance(item, str) and not item.strip():
                continue
            try:
                p = float(item)
            except ValueError:
                raise BenchConfigError(f"--faults takes probabilities like 0.1, not {item!r}") from None
            if not 0.0 <= p <= 1.0:
                raise BenchConfigError(f"--faults {p:g} is not a probability in [0, 1]")
            levels.append(p)
    return tuple(dict.fromkeys(levels))


def expand_jobs(config: BenchConfig, tasks: Sequence[BenchTask]) -> list[Job]:
    """Every (mode, front end, fault level, seed, task) combination of a run, modes outermost,
    tasks innermost, so an interrupted run has whole configurations rather than whole tasks."""
    if not tasks:
        raise BenchConfigError(f"suite {config.suite!r} has no tasks")
    seen: set[str] = set()
    for task in tasks:
        if task.key in seen:
            raise BenchConfigError(f"task {task.key} appears twice in the suite")
        seen.add(task.key)
    return [
        Job(task=task, mode=mode, frontend=frontend, llm=config.llm, seed=seed, disturbance=config.disturbance,
            planner_input=config.planner_input, schedule=config.schedule,
            close_after_use=config.close_after_use, env=config.env,
            fault_level=level, llm_timeout=config.llm_timeout, llm_when=config.llm_when)
        for mode in config.modes
        for frontend in config.frontends
        for level in config.fault_levels
        for seed in range(config.seeds)
        for task in tasks
    ]


# --------------------------------------------------------------------------- worker side

class JobResult(BaseModel):
    """What a worker sends back: the episode, and the traceback if the episode function
    raised (the episode is then a failed one carrying the error)."""

    model_config = ConfigDict(frozen=True)

    key: str
    episode: Episode
    traceback: str | None = None
    pid: int = 0


def resolve_episode_fn(ref: EpisodeFn) -> Callable[[Job], Episode]:
    """The callable behind an import path ``package.module:function`` (or the callable itself)."""
    if not isinstance(ref, str):
        return ref
    module_name, sep, attr = ref.partition(":")
    if not sep or not module_name or not attr:
        raise BenchConfigError(f"an episode function is given as package.module:function, not {ref!r}")
    try:
        module = importlib.import_module(module_name)
    except ImportError as exc:
        raise BenchConfigError(f"cannot import the episode function's module {module_name!r}: {exc}") from None
    fn = module
    for part in attr.split("."):
        try:
            fn = getattr(fn, part)
        except AttributeError:
            raise BenchConfigError(f"module {module_name!r} has no {attr!r}") from None
    if not callable(fn):
        raise BenchConfigError(f"{ref!r} is not callable")
    return fn


def failed_episode(job: Job, error: str) -> Episode:
    """A recorded failed episode for a job whose episode function raised or whose worker died."""
    header = episode_header(job.task, job, _team_names(job.task.robots))
    return Episode.model_validate({**header, "success": False, "error": error})


def _team_names(robots: Sequence[str]) -> tuple[str, ...]:
    """Team member names as the pipeline gives them; the raw profile keys if they are bad
    (a failed episode must be recordable whatever made it fail)."""
    try:
        return tuple(p.name for p in parse_team(list(robots)))
    except EmboTeamError:
        return tuple(robots)


def execute_job(episode_fn: EpisodeFn, job: Job) -> JobResult:
    """Run one job in the current process. Any exception of the episode function (a bug, a
    planner crash) becomes a failed episode with the error: one bad task never stops a run."""
    started = time.perf_counter()
    try:
        fn = resolve_episode_fn(episode_fn)
        episode = fn(job)
        if not isinstance(episode, Episode):
            raise TypeError(f"the episode function returned {type(episode).__name__}, not an Episode")
        return JobResult(key=job.key, episode=episode, pid=os.getpid())
    except Exception as exc:
        episode = failed_episode(job, f"{type(exc).__name__}: {exc}")
        episode = episode.model_copy(update={"wall_seconds": round(time.perf_counter() - started, 4)})
        return JobResult(key=job.key, episode=episode, traceback=traceback.format_exc(), pid=os.getpid())
