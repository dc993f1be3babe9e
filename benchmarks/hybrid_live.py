"""The hybrid front end with the local model, live or replayed, on a suite: SR against the
offline reader, scoring calls and seconds per task, and how often the model overturned
the prior (and whether rightly).

For each task the full system runs twice (``RunConfig(mode="full")``, seed 0): offline,
then hybrid (``--llm-when close``: the model scores close readings, no review) with the model, every LLM call recorded into
``benchmarks/llm_local/cassettes/read25_<suite>/``. The scoring calls of a task are the
cassette's ``"kind": "score"`` entries it added (their recorded latency is the scoring
time); an overturn is a hybrid reading with the "(model ranking)" note; it was right
when the hybrid episode succeeded where the offline one failed, wrong the other way.
Rows go to ``benchmarks/llm_local/read25_results.json``; ``--replay`` runs them again
from the cassette (no model) and exits 1 when any metric differs.

Development rounds and MACE-THOR only (never a held-out half or the unseen suite).

    EMBOTEAM_LLAMACPP_THREADS=2 nice .venv/bin/python benchmarks/hybrid_live.py r40 r41 r43 r45 mace
    .venv/bin/python benchmarks/hybrid_live.py --replay r40 r41 mace
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from emboteam.bench.importers.smart_llm import import_smart_llm
from emboteam.bench.mace_thor import load_mace_thor
from emboteam.pipeline import RunConfig, run_episode
from emboteam.task import BenchTask

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "llm_local"
RESULTS = OUT / "read25_results.json"
MODEL = Path("/root/.cache/emboteam/models/qwen2.5-coder-0.5b-instruct.gguf")
SUITES = {"r40": ROOT / "tests" / "data" / "blind_r40" / "dev", "r41": ROOT / "tests" / "data" / "blind_r41" / "dev",
          "r43": ROOT / "tests" / "data" / "blind_r43" / "dev", "r45": ROOT / "tests" / "data" / "blind_r45" / "dev",
          "mace": None}
#: the model only scores close readings: its review of a reading answers "ok" to everything
#: (issue 25) and costs minutes a call on the shared 2-core machine
WHEN = "close"
METRICS = ("success", "gcr", "llm_calls", "tokens", "overturned")


def tasks_of(suite: str) -> list[BenchTask]:
    folder = SUITES[suite]
    return list(load_mace_thor()) if folder is None else list(import_smart_llm(folder).tasks)


def cassette(suite: str) -> Path:
    return OUT / "cassettes" / f"read25_{suite}"


def _scores(folder: Path) -> dict[str, float]:
    """key -> recorded latency of each scoring call in a cassette folder."""
    out: dict[str, float] = {}
    for f in folder.glob("*.json"):
        entry = json.loads(f.read_text())
        if entry.get("kind") == "score":
            out[f.name] = float(entry.get("response", {}).get("latency") or 0.0)
    return out


def run_task(task: BenchTask, llm: str, record: Path | None) -> dict[str, Any]:
    before = _scores(record) if record is not None else {}
    cfg = RunConfig(mode="full", frontend="hybrid", llm=llm, llm_record=str(record) if record else None,
                    llm_timeout=600, llm_when=WHEN)
    ep = run_episode(task, cfg)
    new = {k: v for k, v in _scores(record).items() if k not in before} if record is not None else {}
    return {"success": ep.success, "gcr": round(ep.gcr, 4), "llm_calls": ep.llm_calls, "tokens": ep.tokens,
            "overturned": any("(model ranking)" in n for n in ep.notes),
            "score_calls": len(new), "score_seconds": round(sum(new.values()), 3), "error": ep.error}


def offline_success(task: BenchTask) -> bool:
    return run_episode(task, RunConfig(mode="full", frontend="offline")).success


def summary(rows: dict[str, dict[str, Any]]) -> dict[str, Any]:
    n = len(rows)
    over = [r for r in rows.values() if r["overturned"]]
    return {"tasks": n, "offline_sr": round(sum(r["offline_success"] for r in rows.values()) / n, 3),
            "hybrid_sr": round(sum(r["success"] for r in rows.values()) / n, 3),
            "llm_calls_per_task": round(sum(r["llm_calls"] for r in rows.values()) / n, 3),
            "score_calls_per_task": round(sum(r["score_calls"] for r in rows.values()) / n, 3),
            "score_seconds_per_task": round(sum(r["score_seconds"] for r in rows.values()) / n, 3),
            "overturned": len(over), "overturned_right": sum(r["success"] and not r["offline_success"] for r in over),
            "overturned_wrong": sum(r["offline_success"] and not r["success"] for r in over)}


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("suites", nargs="+", choices=sorted(SUITES))
    ap.add_argument("--replay", action="store_true", help="from the committed cassettes; exit 1 on a difference")
    ap.add_argument("--only", nargs="*", default=[],
                    help="live: record only these task ids into the existing cassette (the other rows and "
                         "entries are kept: for a reader change that changed the candidates of a few tasks)")
    args = ap.parse_args(argv)
    data: dict[str, Any] = json.loads(RESULTS.read_text()) if RESULTS.exists() else {"model": MODEL.name, "runs": {}}
    diffs: list[str] = []
    for suite in args.suites:
        recorded = data["runs"].get(suite, {}).get("rows", {})
        rows: dict[str, dict[str, Any]] = dict(recorded) if args.only else {}
        if not args.replay and not args.only:
            # a live run records afresh: a call the cassette already held would be answered
            # from it and counted as no call at all
            shutil.rmtree(cassette(suite), ignore_errors=True)
            cassette(suite).mkdir(parents=True)
        for task in tasks_of(suite):
            if args.replay:
                want = recorded.get(task.id)
                if want is None:
                    continue
                got = run_task(task, f"replay:{cassette(suite)}", None)
                diffs += [f"{suite} {task.id} {m}: recorded {want[m]!r}, replayed {got[m]!r}"
                          for m in METRICS if got[m] != want[m]]
                continue
            if args.only and task.id not in args.only:
                continue
            row = run_task(task, f"llamacpp:{MODEL}", cassette(suite))
            row["offline_success"] = offline_success(task)
            rows[task.id] = row
            print(f"{suite} {task.id}: {row}", file=sys.stderr, flush=True)
        if not args.replay:
            data["runs"][suite] = {"summary": summary(rows), "rows": rows}
            RESULTS.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
            print(json.dumps({suite: data["runs"][suite]["summary"]}))
    if args.replay:
        print("\n".join(diffs) or "replay: every metric reproduces")
        return 1 if diffs else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
