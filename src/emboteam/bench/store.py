"""The results store of a benchmark run: ``DIR/results.sqlite``, one row per episode.

Each row holds the job's key columns, the summary metrics as plain columns (so the store
can be queried with any SQLite client), and the whole :class:`Episode` as JSON (without
its trace, which lives in ``DIR/episodes/<job dir>/trace.jsonl``).

Why SQLite: every finished episode is committed on its own transaction before the next
one is taken, so killing the run loses nothing that finished; a job's key is the primary
key, so nothing is stored twice. Only the runner's main process writes; readers (the
report, a second terminal) may read while it runs (WAL journal).

Tables: ``episodes`` (the results), ``attempts`` (a row each time a job is handed to a
worker, so a resumed run can say which jobs the kill interrupted), ``meta`` (schema
version, the configuration of the last run).
"""

from __future__ import annotations

import json
import sqlite3
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path
from types import TracebackType

from pydantic import ValidationError

from emboteam.bench.jobs import Job
from emboteam.errors import EmboTeamError
from emboteam.exec.episode import Episode

SCHEMA_VERSION = 1

_SCHEMA = """
CREATE TABLE IF NOT EXISTS episodes (
    key            TEXT PRIMARY KEY,
    suite          TEXT NOT NULL,
    task_id        TEXT NOT NULL,
    category       TEXT NOT NULL,
    mode           TEXT NOT NULL,
    frontend       TEXT NOT NULL,
    llm            TEXT,
    seed           INTEGER NOT NULL,
    fault_level    REAL NOT NULL,
    success        INTEGER NOT NULL,
    gcr            REAL NOT NULL,
    exec           REAL NOT NULL,
    makespan       REAL NOT NULL,
    actions        INTEGER NOT NULL,
    failed_actions INTEGER NOT NULL,
    replans        INTEGER NOT NULL,
    llm_calls      INTEGER NOT NULL,
    tokens         INTEGER NOT NULL,
    plan_seconds   REAL NOT NULL,
    wall_seconds   REAL NOT NULL,
    error          TEXT,
    crashed        INTEGER NOT NULL,
    traceback      TEXT,
    episode_dir    TEXT NOT NULL,
    job_json       TEXT NOT NULL,
    episode_json   TEXT NOT NULL,
    finished_at    TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS episodes_mode ON episodes (mode, frontend, fault_level);
CREATE TABLE IF NOT EXISTS attempts (
    key        TEXT NOT NULL,
    started_at TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS attempts_key ON attempts (key);
CREATE TABLE IF NOT EXISTS meta (
    name  TEXT PRIMARY KEY,
    value TEXT NOT NULL
);
"""

_FILTERS = ("suite", "task_id", "category", "mode", "frontend", "llm", "seed", "fault_level")


class ResultStoreError(EmboTeamError):
    """The results store cannot be opened or does not hold what is asked for."""


@dataclass(frozen=True)
class StoredResult:
    """One row of the store, for listings and the report: the episode plus where its
    trace lives and, for an episode whose function raised, the traceback."""

    key: str
    episode: Episode
    episode_dir: str
    crashed: bool
    traceback: str | None
    finished_at: str


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")


class ResultStore:
    """``ResultStore(DIR / "results.sqlite")``; use as a context manager or call :meth:`close`."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._db = sqlite3.connect(self.path)
            self._db.execute("PRAGMA journal_mode=WAL")
            # FULL: a committed episode survives a power cut too, not only a killed process
            self._db.execute("PRAGMA synchronous=FULL")
            self._db.executescript(_SCHEMA)
            self._check_version()
        except (sqlite3.Error, OSError) as exc:
            raise ResultStoreError(f"cannot open the results store {self.path}: {exc}") from None

    def _check_version(self) -> None:
        row = self._db.execute("SELECT value FROM meta WHERE name = 'schema_version'").fetchone()
        if row is None:
            with self._db:
                self._db.execute("INSERT INTO meta VALUES ('schema_version', ?)", (str(SCHEMA_VERSION),))
        elif int(row[0]) != SCHEMA_VERSION:
            raise ResultStoreError(f"{self.path} has results schema {row[0]}, this EmboTeam reads "
                                   f"schema {SCHEMA_VERSION}")

    # -- lifecycle
    def close(self) -> None:
        self._db.close()

    def __enter__(self) -> ResultStore:
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.close()

    # -- writing
    def add(self, job: Job, episode: Episode, *, episode_dir: str = "",
            traceback: str | None = None) -> None:
        """Record one finished episode and commit at once. A key already stored is an error:
        the runner never runs a job twice, so a duplicate means a bug upstream."""
        ep = episode
        try:
            with self._db:
                self._db.execute(
                    "INSERT INTO episodes VALUES (" + ",".join("?" * 27) + ")",
                    (job.key, job.suite, job.task_id, job.task.category, job.mode, job.frontend,
                     job.llm, job.seed, float(job.fault_level), int(ep.success), ep.gcr, ep.exec,
                     ep.makespan, ep.actions, ep.failed_actions, ep.replans, ep.llm_calls, ep.tokens,
                     ep.plan_seconds, ep.wall_seconds, ep.error, int(traceback is not None), traceback,
                     episode_dir, job.model_dump_json(), ep.model_dump_json(), _now()),
                )
        except sqlite3.IntegrityError:
            raise ResultStoreError(f"job {job.key} is already in {self.path}") from None

    def mark_started(self, job: Job) -> None:
        """Note that a job went to a worker (committed, so it survives a kill)."""
        with self._db:
            self._db.execute("INSERT INTO attempts VALUES (?, ?)", (job.key, _now()))

    def set_meta(self, name: str, value: str) -> None:
        with self._db:
            self._db.execute("INSERT OR REPLACE INTO meta VALUES (?, ?)", (name, value))

    # -- reading
    def meta(self, name: str) -> str | None:
        row = self._db.execute("SELECT value FROM meta WHERE name = ?", (name,)).fetchone()
        return None if row is None else str(row[0])

    def __len__(self) -> int:
        return int(self._db.execute("SELECT COUNT(*) FROM episodes").fetchone()[0])

    def done_keys(self) -> set[str]:
        return {str(r[0]) for r in self._db.execute("SELECT key FROM episodes")}

    def llm_specs(self) -> set[str | None]:
        return {r[0] for r in self._db.execute("SELECT DISTINCT llm FROM episodes")}

    def interrupted_keys(self) -> set[str]:
        """Jobs handed to a worker that never came back (the run was killed meanwhile)."""
        rows = self._db.execute(
            "SELECT DISTINCT key FROM attempts WHERE key NOT IN (SELECT key FROM episodes)")
        return {str(r[0]) for r in rows}

    def attempts(self, key: str) -> int:
        return int(self._db.execute("SELECT COUNT(*) FROM attempts WHERE key = ?", (key,)).fetchone()[0])

    def results(self, *, keys: Iterable[str] | None = None, **where: str | int | float | None
                ) -> list[StoredResult]:
        """Stored rows in the order they finished, filtered by equality on key columns
        (``suite, task_id, category, mode, frontend, llm, seed, fault_level``)."""
        return list(self._select(keys, where))

    def episodes(self, *, keys: Iterable[str] | None = None, **where: str | int | float | None
                 ) -> list[Episode]:
        """Stored episodes (without traces), filtered like :meth:`results`."""
        return [r.episode for r in self._select(keys, where)]

    def jobs(self) -> list[Job]:
        """The jobs of every stored row (their tasks included), in finishing order."""
        rows = self._db.execute("SELECT job_json FROM episodes ORDER BY rowid")
        return [Job.model_validate_json(r[0]) for r in rows]

    def _select(self, keys: Iterable[str] | None, where: dict[str, str | int | float | None]
                ) -> Iterator[StoredResult]:
        clauses: list[str] = []
        params: list[str | int | float | None] = []
        for column, value in where.items():
            if column not in _FILTERS:
                raise ResultStoreError(f"cannot filter results by {column!r}; use one of {', '.join(_FILTERS)}")
            if value is None:
                clauses.append(f"{column} IS NULL")
            else:
                clauses.append(f"{column} = ?")
                params.append(value)
        wanted = None if keys is None else set(keys)
        sql = ("SELECT key, episode_json, episode_dir, crashed, traceback, finished_at FROM episodes"
               + (" WHERE " + " AND ".join(clauses) if clauses else "") + " ORDER BY rowid")
        for key, episode_json, episode_dir, crashed, tb, finished_at in self._db.execute(sql, params):
            if wanted is not None and key not in wanted:
                continue
            try:
                episode = Episode.model_validate(json.loads(episode_json))
            except (ValidationError, ValueError) as exc:
                raise ResultStoreError(f"{self.path}: the stored episode {key} is unreadable: {exc}") from None
            yield StoredResult(key=key, episode=episode, episode_dir=episode_dir, crashed=bool(crashed),
                               traceback=tb, finished_at=finished_at)
