"""End-to-end success of a front end on the unseen suite (docs/unseen_suite.md).

The unseen suite (``tests/data/unseen_tasks.json``) holds 60 household tasks written apart
from MACE-THOR and from the offline parser's own data. This script runs each task through
the full system (``RunConfig(mode="full", frontend=F)``: front end -> hybrid planner ->
behavior trees -> simulator, no faults, seed 0) and scores the final state against the
task's ground-truth goal.

To tell a front end that could not read an instruction from one that read it wrongly, the
front end (the PFG stage, :func:`emboteam.modes.understand`) is also run on its own first.
The outcome of a task is then

- ``ok``               the ground-truth goal holds at the end;
- ``parse-error``      the front end raised a typed error (no TaskSpec);
- ``front-end-crash``  the front end raised an exception that is not a typed error (a bug:
                       the pipeline would crash on it too, so the episode is not run);
- ``plan-error``       the front end produced a TaskSpec, but planning or execution ended
                       with a typed error;
- ``crash``            an untyped exception after the front end;
- ``failed``           the episode ran to its end and the ground-truth goal does not hold
                       (a wrong or partial reading, or an execution failure).

*Parse errors* in the summary count ``parse-error`` and ``front-end-crash``: every task
where the front end gave no TaskSpec. A task that did not run scores the GCR of its
initial state, as :func:`emboteam.pipeline.run_episode` scores a failed episode.

    .venv/bin/python benchmarks/unseen_offline.py                    # offline front end
    .venv/bin/python benchmarks/unseen_offline.py --frontend oracle  # sanity check: 60/60
    .venv/bin/python benchmarks/unseen_offline.py --json             # one JSON object on stdout

Exit status 0 when the run completed (whatever the SR); 2 with a one-line error for a
suite file that does not load.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Literal

from emboteam.bench.metrics import bootstrap_ci
from emboteam.errors import EmboTeamError
from emboteam.exec.episode import score
from emboteam.modes import EpisodeContext, understand
from emboteam.pipeline import RunConfig, run_episode
from emboteam.task import BenchTask
from emboteam.world.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]
SUITE_FILE = ROOT / "tests" / "data" / "unseen_tasks.json"
SUITE = "unseen"
Outcome = Literal["ok", "parse-error", "front-end-crash", "plan-error", "crash", "failed"]
OUTCOMES: tuple[Outcome, ...] = ("ok", "parse-error", "front-end-crash", "plan-error", "crash", "failed")
ROOMS = ("kitchen", "living_room", "bedroom", "bathroom")


class SuiteFileError(EmboTeamError):
    """The unseen suite file is missing, not JSON, or has a task that does not validate."""


@dataclass(frozen=True)
class TaskResult:
    """One task's result: what the table and the JSON report show."""

    id: str
    floor_plan: str
    room: str
    category: str
    outcome: Outcome
    success: bool
    gcr: float
    understood: int | None  # conditions in the front end's goal (None: no TaskSpec)
    error: str | None


def load_suite_file(path: Path) -> tuple[BenchTask, ...]:
    """The tasks of ``{"suite": "unseen", "tasks": [...]}``, each validated as a BenchTask
    and checked against its scene (floor plan, team, setup, goal); ids unique."""
    try:
        doc: Any = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as exc:
        raise SuiteFileError(f"{path}: {exc}") from None
    if not isinstance(doc, dict) or set(doc) != {"suite", "tasks"} or doc["suite"] != SUITE:
        raise SuiteFileError(f"{path}: expected {{'suite': '{SUITE}', 'tasks': [...]}}")
    tasks: list[BenchTask] = []
    for i, entry in enumerate(doc["tasks"], start=1):
        try:
            task = BenchTask.model_validate(entry)
            task.check()
        except (ValueError, EmboTeamError) as exc:  # pydantic's ValidationError is a ValueError
            raise SuiteFileError(f"{path}: task #{i}: {_first_line(exc)}") from None
        tasks.append(task)
    ids = [t.id for t in tasks]
    if len(set(ids)) != len(ids):
        raise SuiteFileError(f"{path}: duplicate task ids")
    return tuple(tasks)


def _first_line(exc: BaseException) -> str:
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    return " ".join(lines[:2])


def _crash(exc: BaseException) -> str:
    return f"{type(exc).__name__} (untyped): {_first_line(exc)}"


def front_end_error(task: BenchTask, cfg: RunConfig) -> tuple[str | None, bool]:
    """The front end's error on this task (None if it produced a TaskSpec), and whether
    that error was a crash (an exception that is not a typed EmboTeamError)."""
    try:
        understand(EpisodeContext(task=task, cfg=cfg, scene=load_scene(task.floor_plan), state=task.initial_state(),
                                  team=task.team(), llm=None))
    except EmboTeamError as exc:
        return f"{type(exc).__name__}: {exc}", False
    except Exception as exc:  # a crash is a result to report, not a reason to lose the run
        return _crash(exc), True
    return None, False


def _start_gcr(task: BenchTask) -> float:
    return round(score(task.goal, task.initial_state())[1], 4)


def run_task(task: BenchTask, cfg: RunConfig) -> TaskResult:
    """Run one task end to end and classify its outcome."""
    fields: dict[str, Any] = dict(id=task.id, floor_plan=task.floor_plan,
                                  room=load_scene(task.floor_plan).room, category=task.category)
    perror, crashed = front_end_error(task, cfg)
    if crashed:
        return TaskResult(**fields, outcome="front-end-crash", success=False, gcr=_start_gcr(task),
                          understood=None, error=perror)
    try:
        episode = run_episode(task, cfg)
    except Exception as exc:  # untyped, after the front end: recorded, the run goes on
        return TaskResult(**fields, outcome="crash", success=False, gcr=_start_gcr(task),
                          understood=None, error=_crash(exc))
    outcome: Outcome
    if episode.success:
        outcome = "ok"
    elif perror is not None:
        outcome = "parse-error"
    elif episode.error is not None:
        outcome = "plan-error"
    else:
        outcome = "failed"
    understood = len(episode.taskspec.goal().conditions) if episode.taskspec is not None else None
    return TaskResult(**fields, outcome=outcome, success=episode.success, gcr=round(episode.gcr, 4),
                      understood=understood, error=perror or episode.error)


def _rates(results: Sequence[TaskResult]) -> dict[str, Any]:
    n = len(results)
    return {"n": n,
            "sr": round(sum(r.success for r in results) / n, 4) if n else 0.0,
            "gcr": round(sum(r.gcr for r in results) / n, 4) if n else 0.0}


def report(results: Sequence[TaskResult], frontend: str) -> dict[str, Any]:
    """The JSON report: SR and GCR (with the bootstrap CI of SR that ``emboteam bench``
    reports), parse errors, outcome counts, per category and per room, and every task."""
    counts = {o: sum(r.outcome == o for r in results) for o in OUTCOMES}
    return {
        "suite": SUITE, "frontend": frontend, **_rates(results),
        "sr_ci": bootstrap_ci([[1.0 if r.success else 0.0] for r in results]),
        "parse_errors": counts["parse-error"] + counts["front-end-crash"],
        "outcomes": counts,
        "by_category": {c: _rates([r for r in results if r.category == c]) for c in ("parallel", "temporal")},
        "by_room": {room: _rates([r for r in results if r.room == room]) for room in ROOMS},
        "tasks": [asdict(r) for r in results],
    }


def print_table(data: dict[str, Any]) -> None:
    """A Markdown table (pasted as is into docs/unseen_suite.md) and the summary."""
    print("| task | room | category | outcome | GCR | conditions understood | error |")
    print("|---|---|---|---|---:|---:|---|")
    for r in data["tasks"]:
        err = (r["error"] or "").replace("|", "/")
        err = err if len(err) <= 100 else err[:97] + "..."
        understood = "-" if r["understood"] is None else str(r["understood"])
        print(f"| {r['id']} | {r['room']} | {r['category']} | {r['outcome']} | {r['gcr']:.2f} "
              f"| {understood} | {err} |")
    lo, hi = data["sr_ci"]
    print()
    print(f"frontend={data['frontend']}  n={data['n']}  SR={data['sr']:.3f} (95% CI {lo:.3f}-{hi:.3f})  "
          f"GCR={data['gcr']:.3f}  parse errors={data['parse_errors']}")
    print("outcomes: " + ", ".join(f"{k}={v}" for k, v in data["outcomes"].items()))
    for key in ("by_category", "by_room"):
        for name, g in data[key].items():
            print(f"  {name:12s} n={g['n']:2d}  SR={g['sr']:.3f}  GCR={g['gcr']:.3f}")


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description="End-to-end SR of a front end on the unseen suite.")
    ap.add_argument("--suite-file", type=Path, default=SUITE_FILE)
    ap.add_argument("--frontend", choices=("offline", "oracle"), default="offline")
    ap.add_argument("--json", action="store_true", help="one JSON object on stdout instead of the table")
    args = ap.parse_args(argv)
    try:
        tasks = load_suite_file(args.suite_file)
    except SuiteFileError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    cfg = RunConfig(mode="full", frontend=args.frontend)
    results: list[TaskResult] = []
    for i, task in enumerate(tasks, start=1):
        results.append(run_task(task, cfg))
        print(f"[{i}/{len(tasks)}] {task.id}: {results[-1].outcome}", file=sys.stderr, flush=True)
    data = report(results, args.frontend)
    if args.json:
        print(json.dumps(data, indent=2))
    else:
        print_table(data)
    return 0


if __name__ == "__main__":
    sys.exit(main())
