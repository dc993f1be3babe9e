"""Robots on the grid: collisions, waits, re-plans and the price of not colliding
(docs/navigation.md).

Runs a suite (``congestion`` by default) with the oracle front end twice: with avoidance
(mode ``full``) and without (mode ``no-avoidance``), seed 0, no faults, and reports per
mode SR, the collisions the independent trace checker counts, waits and re-plans, and

- ``worst_vs_planned``: the largest ratio of an episode's makespan to its plan's makespan
  (the issue's "every congestion task ends within 3x its planned makespan");
- ``makespan_price``: mean over tasks solved in both modes of makespan(full) /
  makespan(no-avoidance) (target <= 1.2);
- ``path_share_max``: the largest share of an episode's wall time spent planning paths.

    PYTHONPATH=src .venv/bin/python benchmarks/navigation.py --suite congestion --out /tmp/nav
    PYTHONPATH=src .venv/bin/python benchmarks/navigation.py --suite mace-thor --modes full

Writes ``OUT/navigation.json`` and prints the same JSON object.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

from emboteam.bench.suites import load_suite
from emboteam.config import RunConfig
from emboteam.exec.episode import Episode
from emboteam.pipeline import run_episode


def run(suite: str, mode: str) -> list[Episode]:
    cfg = RunConfig(mode=mode, frontend="oracle")  # type: ignore[arg-type]
    return [run_episode(task, cfg) for task in load_suite(suite).tasks]


def summary(eps: list[Episode]) -> dict[str, object]:
    planned = [e.makespan / e.plan.makespan for e in eps if e.plan is not None and e.plan.makespan > 0]
    shares = [e.path_seconds / e.wall_seconds for e in eps if e.wall_seconds > 0]
    return {
        "n": len(eps), "sr": round(sum(e.success for e in eps) / len(eps), 4) if eps else 0.0,
        "collisions": sum(e.collisions for e in eps), "nav_waits": sum(e.nav_waits for e in eps),
        "nav_replans": sum(e.nav_replans for e in eps),
        "episodes_with_collisions": sum(1 for e in eps if e.collisions),
        "worst_vs_planned": round(max(planned), 3) if planned else None,
        "path_share_max": round(max(shares), 3) if shares else None,
        "path_share_median": round(statistics.median(shares), 3) if shares else None,
        "makespan_mean": round(statistics.mean([e.makespan for e in eps if e.success]), 3)
        if any(e.success for e in eps) else None,
        "failed": [f"{e.task}: {e.error}" for e in eps if not e.success],
    }


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--suite", default="congestion")
    ap.add_argument("--modes", default="full,no-avoidance")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args(argv)
    began = time.perf_counter()
    by_mode = {m: run(args.suite, m) for m in args.modes.split(",")}
    result: dict[str, object] = {"suite": args.suite, **{m: summary(eps) for m, eps in by_mode.items()}}
    if "full" in by_mode and "no-avoidance" in by_mode:
        free = {e.task: e for e in by_mode["no-avoidance"] if e.success}
        ratios = [e.makespan / free[e.task].makespan for e in by_mode["full"]
                  if e.success and e.task in free and free[e.task].makespan > 0]
        result["makespan_price"] = round(statistics.mean(ratios), 4) if ratios else None
        result["makespan_price_max"] = round(max(ratios), 4) if ratios else None
    result["wall_seconds"] = round(time.perf_counter() - began, 1)
    text = json.dumps(result, indent=1)
    if args.out is not None:
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "navigation.json").write_text(text + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
