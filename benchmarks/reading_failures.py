"""Why the offline reader loses tasks on development rounds: a failure table.

For every task of the given development rounds (SMART-LLM folders; never a held-out
half, never ``tests/data/unseen_tasks.json``) the offline reader reads the instruction
and each task gets one class:

- ``ok``: the first candidate meets the ground truth (``fit_reading_priors.Case.right``)
  and, when ``--episodes`` gives a bench run, the episode succeeded;
- ``error``: the reader raised (nothing actionable, an unknown word, ...);
- ``ranking``: a candidate meets the ground truth, but not the first;
- ``generation``: no candidate meets it (the right reading was never proposed);
- ``planner``: the first candidate meets it but the bench episode failed (the planner
  rejected the goal or the run failed).

    PYTHONPATH=src .venv/bin/python benchmarks/reading_failures.py tests/data/blind_r40/dev tests/data/blind_r41/dev
    ... --episodes /tmp/bench-out/episodes -v     # with a bench run's episodes; -v lists each failure
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from emboteam.bench.importers.smart_llm import import_smart_llm
from emboteam.errors import EmboTeamError
from emboteam.pfg.offline import OfflineFrontend

CLASSES = ("ok", "error", "generation", "ranking", "planner")


def _episode_success(episodes: Path | None) -> dict[str, bool]:
    """task instruction -> whether the bench episode succeeded."""
    if episodes is None:
        return {}
    out: dict[str, bool] = {}
    for f in sorted(episodes.glob("*/episode.json")):
        ep = json.loads(f.read_text(encoding="utf-8"))
        out[str(ep["instruction"])] = bool(ep["success"])
    return out


def classify(folder: Path, episodes: dict[str, bool]) -> list[dict[str, Any]]:
    """One row per task with ground truth: its class and what the reader gave."""
    from fit_reading_priors import task_case  # a script beside this one (benchmarks/ is on sys.path)
    reader = OfflineFrontend()
    rows: list[dict[str, Any]] = []
    for task in import_smart_llm(folder).tasks:
        if task.ground_truth is None:
            continue
        case = task_case(folder.name, task)
        scene = case.scene
        row: dict[str, Any] = {"task": task.id, "instruction": task.instruction,
                               "truth": [str(c) for c in task.ground_truth.conditions]}
        try:
            reading = reader.parse(task.instruction, scene, case.state, case.team)
        except (EmboTeamError, ValueError) as exc:   # a ValueError (e.g. a bad Condition) is a reader bug: list it, do not stop
            rows.append({**row, "class": "error", "why": f"{type(exc).__name__}: {exc}"})
            continue
        cands = reading.candidates
        right = [case.right(c.goals) for c in cands]
        row |= {"read": [str(c) for c in reading.spec.goal().conditions], "right_at": right.index(True)
                if any(right) else None, "candidates": len(cands), "unexplained": list(reading.unexplained)}
        if right and right[0]:
            row["class"] = "planner" if episodes.get(task.instruction) is False else "ok"
        else:
            row["class"] = "ranking" if any(right) else "generation"
        rows.append(row)
    return rows


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("rounds", type=Path, nargs="+", help="development round folders (SMART-LLM format)")
    ap.add_argument("--episodes", type=Path, nargs="*", default=[], help="bench episodes folders (optional)")
    ap.add_argument("--json", type=Path, help="write the rows here")
    ap.add_argument("-v", action="store_true", help="list every failure")
    args = ap.parse_args(argv)
    if any("unseen" in str(r) or "heldout" in str(r) for r in args.rounds):
        print("error: development rounds only (no held-out half, no unseen suite)", file=sys.stderr)
        return 2
    success: dict[str, bool] = {}
    for e in args.episodes:
        success |= _episode_success(e)
    all_rows: dict[str, list[dict[str, Any]]] = {}
    print(f"{'round':28} {'tasks':>5} " + " ".join(f"{c:>10}" for c in CLASSES))
    for folder in args.rounds:
        rows = classify(folder, success)
        all_rows[str(folder)] = rows
        n = Counter(r["class"] for r in rows)
        print(f"{folder!s:28} {len(rows):5} " + " ".join(f"{n[c]:10d}" for c in CLASSES))
        if args.v:
            for r in rows:
                if r["class"] != "ok":
                    print(f"  [{r['class']}] {r['task']}: {r['instruction']}\n"
                          f"      truth {r['truth']}\n      read  {r.get('read', r.get('why'))}"
                          f"  right_at={r.get('right_at')} unexplained={r.get('unexplained')}")
    if args.json:
        args.json.write_text(json.dumps(all_rows, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
