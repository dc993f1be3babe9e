"""Routing ceilings of the LLM front-end modes, with a perfect-model stand-in (issue 29).

The model is :mod:`emboteam.bench.standin`: a loopback OpenAI-compatible server that knows
every task's ground-truth goal. **It measures routing, never model quality**: with it, a
mode's SR is its ceiling, what it reaches when the model never errs, given where the mode
asks the model and what it lets the model change.

Per development round and per mode (``llm``; ``hybrid`` with ``--llm-when doubt`` and
``always``), seed 0, no faults, the full pipeline (``emboteam.pipeline.run_episode``):

- SR, and LLM calls per task (every call the episode made: PFG, review, HP review, repairs);
- silent failures: the parser's reading was wrong (the offline front end fails a task that
  the oracle front end, the ground truth, solves) and the mode did not ask the model.

Then the doubt detector (:mod:`emboteam.pfg.doubt`, what ``--llm-when doubt`` asks on),
against the offline reading's right/wrong label: the share of wrong readings it flags and
of right readings it flags, per round, beside the parser's own notes (``Reading.doubtful``).
Rounds the detector's weights were fitted on are marked; the others measure it.

Rounds: ``tests/data/blind_r*/dev``, the held-out halves that became development data
(:data:`READ_HELDOUT`), ``offline_dev*.jsonl`` and MACE-THOR; extra rounds with
``--round-dir NAME=PATH``. Never the unseen suite, never a held-out round (:data:`HELD_OUT`).

    nice .venv/bin/python benchmarks/frontend_routing.py --out /tmp/routing          # everything
    nice .venv/bin/python benchmarks/frontend_routing.py --round blind_r39 --round mace-thor
    .venv/bin/python benchmarks/frontend_routing.py --from /tmp/routing/rows.jsonl --markdown

``--out DIR`` writes ``rows.jsonl`` (one line per task: features, labels, per-mode outcome)
and ``summary.json``; ``--from`` rebuilds the tables from a ``rows.jsonl`` (e.g. after
changing the detector: its flags are recomputed from the recorded features).
"""

from __future__ import annotations

import argparse
import json
import logging
import sys
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from emboteam.bench.dev_corpus import HELD_OUT_ROUNDS, is_unmeasured
from emboteam.bench.importers.smart_llm import import_smart_llm
from emboteam.bench.mace_thor import load_mace_thor
from emboteam.bench.standin import DISCLAIMER, StandInServer, known_tasks
from emboteam.errors import EmboTeamError
from emboteam.pfg.doubt import FITTED_ON, doubt_features, flags
from emboteam.pipeline import RunConfig, run_episode
from emboteam.task import BenchTask
from emboteam.world.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
#: held-out halves that were measured, then read and tuned on (docs/unseen_suite.md,
#: "measured held-out sets become development data" and "rounds 13 and 14 read")
READ_HELDOUT = ("blind_r8", "blind_r9", "blind_r12", "blind_r13", "blind_r14")
#: held-out rounds this script refuses to read, even when given by --round-dir
HELD_OUT = HELD_OUT_ROUNDS
#: the modes measured: name -> (front end, --llm-when)
MODES: dict[str, tuple[str, str]] = {"llm": ("llm", "doubt"), "hybrid-doubt": ("hybrid", "doubt"),
                                     "hybrid-always": ("hybrid", "always")}
#: the front end that labels a reading right or wrong (no LLM)
OFFLINE = "offline"


class RoundError(EmboTeamError):
    """A round that does not load, or one that is held out."""


@dataclass(frozen=True)
class Round:
    name: str
    tasks: tuple[BenchTask, ...]


def _jsonl_round(path: Path) -> Round:
    tasks: list[BenchTask] = []
    for line in path.read_text(encoding="utf-8").splitlines():
        if not line.strip():
            continue
        rec = json.loads(line)
        if "error" in rec or not rec.get("goal"):  # records that expect a parse error have no goal
            continue
        robots = tuple(r.strip() for r in str(rec.get("robots", "1,2,3")).split(","))
        tasks.append(BenchTask(id=str(rec["id"]), suite=path.stem, floor_plan=str(rec["scene"]), robots=robots,
                               category="imported", instruction=str(rec["instruction"]), goal=rec["goal"],
                               setup=tuple(rec.get("setup") or ())))
    return Round(path.stem, tuple(tasks))


def _dir_round(name: str, path: Path) -> Round:
    if name in HELD_OUT or any(h in str(path) for h in HELD_OUT):
        raise RoundError(f"{name} ({path}) is held out: this script never reads it")
    suite = import_smart_llm(path, suite=name)
    return Round(name, tuple(t for t in suite.tasks if t.goal.conditions))


def development_rounds(data: Path = DATA, extra: Sequence[tuple[str, Path]] = ()) -> list[Round]:
    """Every development round, in a fixed order (blind rounds by number, then the rest)."""
    def number(p: Path) -> int:
        return int(p.parent.name.removeprefix("blind_r"))

    out = [_dir_round(p.parent.name, p) for p in sorted(data.glob("blind_r*/dev"), key=number)
           if p.parent.name not in HELD_OUT and not is_unmeasured(p.parent)]
    out += [_dir_round(f"{name}-heldout", data / name / "heldout") for name in READ_HELDOUT
            if (data / name / "heldout").is_dir()]
    out += [_dir_round(name, path) for name, path in extra]
    out += [_jsonl_round(p) for p in sorted(data.glob("offline_dev*.jsonl"))]
    out.append(Round("mace-thor", tuple(load_mace_thor())))
    return out


# ---- one task ------------------------------------------------------------------------------
@dataclass
class Row:
    """One task: the offline reading's features and label, and each mode's outcome."""

    round: str
    id: str
    oracle_success: bool
    offline_success: bool
    offline_error: str | None
    features: dict[str, Any]
    modes: dict[str, dict[str, Any]] = field(default_factory=dict)

    @property
    def reachable(self) -> bool:
        """The ground truth itself succeeds (the oracle front end)."""
        return self.oracle_success

    @property
    def wrong_reading(self) -> bool:
        return self.reachable and not self.offline_success


def reading_features(task: BenchTask) -> dict[str, Any]:
    """The doubt detector's features of the offline reading of ``task``."""
    from emboteam.pfg.parser import offline_frontend

    scene = load_scene(task.floor_plan)
    state, team = task.initial_state(), task.team()
    try:
        reading = offline_frontend().parse(task.instruction, scene, state, team)
    except EmboTeamError as exc:  # no reading: every mode asks the model
        return doubt_features(None, task.instruction, state, error=f"{type(exc).__name__}: {exc}")
    return doubt_features(reading, task.instruction, state)


def refeature(rows: Sequence[Row], rounds: Sequence[Round]) -> list[Row]:
    """``rows`` with their features computed again (the episodes' outcomes kept): for a
    changed detector, seconds instead of a new run."""
    tasks = {(r.name, t.id): t for r in rounds for t in r.tasks}
    return [Row(**{**r.__dict__, "features": reading_features(tasks[(r.round, r.id)])}) for r in rows]


def run_task(rnd: str, task: BenchTask, server: StandInServer) -> Row:
    features = reading_features(task)
    offline = run_episode(task, RunConfig(mode="full", frontend=OFFLINE))
    if offline.success and offline.taskspec is not None:
        # a reading that reaches the ground truth is right, however it is worded: the
        # stand-in answers "ok" to it, as a perfect model would
        server.model.accept(task.instruction, task.floor_plan, offline.taskspec.goal().conditions)
    oracle = run_episode(task, RunConfig(mode="full", frontend="oracle"))
    row = Row(rnd, task.id, oracle.success, offline.success, offline.error, features)
    for mode, (frontend, when) in MODES.items():
        ep = run_episode(task, RunConfig(mode="full", frontend=frontend, llm=server.spec, llm_when=when))
        row.modes[mode] = {"success": ep.success, "calls": ep.llm_calls, "error": ep.error}
    return row


def run_rounds(rounds: Iterable[Round], out: Path | None, *, progress: bool = True) -> list[Row]:
    rounds = list(rounds)
    rows: list[Row] = []
    sink = None
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        sink = (out / "rows.jsonl").open("w", encoding="utf-8")
    with StandInServer(known_tasks(t for r in rounds for t in r.tasks)) as server:
        for rnd in rounds:
            started = time.monotonic()
            for task in rnd.tasks:
                row = run_task(rnd.name, task, server)
                rows.append(row)
                if sink is not None:
                    sink.write(json.dumps(row.__dict__) + "\n")
                    sink.flush()
            if progress:
                print(f"  {rnd.name}: {len(rnd.tasks)} tasks in {time.monotonic() - started:.0f} s",
                      file=sys.stderr, flush=True)
        counts = dict(server.model.counts)
    if sink is not None:
        sink.close()
        (out / "standin_counts.json").write_text(json.dumps(counts, indent=1))  # type: ignore[operator]
    return rows


def derive_doubt(rows: Sequence[Row]) -> list[Row]:
    """``hybrid-doubt`` from the recorded runs and the current detector: a flagged reading
    goes to the same review as ``hybrid-always`` (the same request, the same answer), an
    unflagged one is the offline reading with no call (``HybridFrontend.read``). Exact by
    construction; a new run checks it (``--round``)."""
    out = []
    for r in rows:
        flagged = flags(r.features)["detector"]
        doubt = dict(r.modes["hybrid-always"]) if flagged else {"success": r.offline_success, "calls": 0,
                                                                  "error": r.offline_error}
        out.append(Row(**{**r.__dict__, "modes": {**r.modes, "hybrid-doubt": doubt}}))
    return out


def load_rows(path: Path) -> list[Row]:
    return [Row(**json.loads(line)) for line in path.read_text(encoding="utf-8").splitlines() if line.strip()]


# ---- tables --------------------------------------------------------------------------------
def _share(n: int, d: int) -> str:
    return f"{n}/{d} ({n / d:.0%})" if d else "-"


def summarize(rows: Sequence[Row]) -> dict[str, Any]:
    """Per round: tasks, and per mode SR, calls per task, silent failures; the detector's
    flags on wrong and right readings (the notes, and the fitted detector)."""
    by_round: dict[str, list[Row]] = {}
    for r in rows:
        by_round.setdefault(r.round, []).append(r)
    by_round["ALL"] = list(rows)
    out: dict[str, Any] = {}
    for name, rs in by_round.items():
        entry: dict[str, Any] = {"tasks": len(rs), "oracle_sr": sum(r.oracle_success for r in rs) / len(rs),
                                 "offline_sr": sum(r.offline_success for r in rs) / len(rs),
                                 "fitted": name in FITTED_ON, "modes": {}}
        for mode in MODES:
            done = [r.modes[mode] for r in rs]
            silent = sum(1 for r in rs if r.wrong_reading and r.modes[mode]["calls"] == 0)
            entry["modes"][mode] = {"sr": sum(d["success"] for d in done) / len(rs),
                                    "calls_per_task": sum(d["calls"] for d in done) / len(rs),
                                    "silent_failures": silent}
        labelled = [r for r in rs if r.reachable]
        wrong = [r for r in labelled if not r.offline_success]
        right = [r for r in labelled if r.offline_success]
        for detector in ("notes", "detector"):
            flagged_wrong = sum(flags(r.features)[detector] for r in wrong)
            flagged_right = sum(flags(r.features)[detector] for r in right)
            entry[detector] = {"wrong": len(wrong), "wrong_flagged": flagged_wrong,
                               "right": len(right), "right_flagged": flagged_right}
        out[name] = entry
    return out


def render(summary: dict[str, Any], *, markdown: bool) -> str:
    lines = [f"NOTE: {DISCLAIMER}.", ""]
    head = ["round", "tasks", "oracle SR", "offline SR"]
    for mode in MODES:
        head += [f"{mode} SR", f"{mode} calls/task", f"{mode} silent"]
    head += ["notes: wrong flagged", "notes: right flagged", "detector: wrong flagged", "detector: right flagged"]
    rows = []
    for name, e in summary.items():
        cells = [name + (" (fit)" if e["fitted"] else ""), str(e["tasks"]), f"{e['oracle_sr']:.3f}",
                 f"{e['offline_sr']:.3f}"]
        for mode in MODES:
            m = e["modes"][mode]
            cells += [f"{m['sr']:.3f}", f"{m['calls_per_task']:.2f}", str(m["silent_failures"])]
        for d in ("notes", "detector"):
            cells += [_share(e[d]["wrong_flagged"], e[d]["wrong"]), _share(e[d]["right_flagged"], e[d]["right"])]
        rows.append(cells)
    if markdown:
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "|".join("---" if i == 0 else "---:" for i in range(len(head))) + "|")
        lines += ["| " + " | ".join(c) + " |" for c in rows]
    else:
        widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(head)]
        lines.append("  ".join(h.ljust(w) for h, w in zip(head, widths, strict=True)))
        lines += ["  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)) for r in rows]
    held = [n for n, e in summary.items() if n != "ALL" and not e["fitted"]]
    if held:
        agg = {d: [sum(summary[n][d][k] for n in held) for k in ("wrong_flagged", "wrong", "right_flagged", "right")]
               for d in ("notes", "detector")}
        lines += ["", f"detector on the {len(held)} rounds it was not fitted on: wrong readings flagged "
                  f"{_share(agg['detector'][0], agg['detector'][1])}, right readings flagged "
                  f"{_share(agg['detector'][2], agg['detector'][3])} (notes alone: "
                  f"{_share(agg['notes'][0], agg['notes'][1])}, {_share(agg['notes'][2], agg['notes'][3])})"]
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--round", action="append", default=[], help="only these rounds (repeatable)")
    ap.add_argument("--round-dir", action="append", default=[], metavar="NAME=PATH",
                    help="an extra development round in the SMART-LLM format (repeatable)")
    ap.add_argument("--limit", type=int, default=None, help="at most N tasks per round (a quick look)")
    ap.add_argument("--out", type=Path, default=None, help="write rows.jsonl and summary.json here")
    ap.add_argument("--from", dest="source", type=Path, action="append", default=None,
                    help="tables from a recorded rows.jsonl (repeatable)")
    ap.add_argument("--refeature", action="store_true",
                    help="with --from: compute the readings' features again (a changed detector)")
    ap.add_argument("--derive-doubt", action="store_true",
                    help="with --from: hybrid-doubt from the recorded offline and hybrid-always outcomes and "
                         "the current detector (derive_doubt)")
    ap.add_argument("--markdown", action="store_true", help="the table in Markdown (for docs/llm.md)")
    ap.add_argument("--json", action="store_true", help="one JSON object on stdout")
    args = ap.parse_args(argv)
    # a rejected correction is a measured outcome here, not a warning to print per task
    logging.getLogger("emboteam.pfg.hybrid").setLevel(logging.ERROR)
    try:
        extra = [(s.partition("=")[0], Path(s.partition("=")[2])) for s in args.round_dir]
        if args.source is not None:
            rows = [r for src in args.source for r in load_rows(src)]
            if args.round:
                rows = [r for r in rows if r.round in args.round]
            if args.refeature:
                rows = refeature(rows, development_rounds(DATA, extra))
            if args.derive_doubt:
                rows = derive_doubt(rows)
        else:
            rounds = development_rounds(DATA, extra)
            if args.round:
                rounds = [r for r in rounds if r.name in args.round]
            if args.limit is not None:
                rounds = [Round(r.name, r.tasks[: args.limit]) for r in rounds]
            rows = run_rounds(rounds, args.out)
    except (EmboTeamError, OSError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    summary = summarize(rows)
    if args.out is not None:
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "summary.json").write_text(json.dumps({"note": DISCLAIMER, "rounds": summary}, indent=1))
    if args.json:
        print(json.dumps({"note": DISCLAIMER, "rounds": summary}))
    else:
        print(render(summary, markdown=args.markdown))
    return 0


if __name__ == "__main__":
    sys.exit(main())
