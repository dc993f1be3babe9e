"""Focus recall of the LLM prompts: is every ground-truth goal object listed in detail
(with its place and state) in the scene listing the LLM front end sends?

For every development task with ground truth (``tests/data/blind_r*/dev``,
``tests/data/offline_dev*.jsonl``, MACE-THOR; never a held-out set or the unseen suite)
this builds the listing the ``llm`` front end's first request shows
(:meth:`emboteam.pfg.llm_frontend.LLMFrontend.listed_types`) and checks each type a goal
condition names (subject and receptacle; a slice counts as listed when it or what it is
cut from is; ``Sink`` and ``SinkBasin`` are one place). A task is recalled when every one
of its goal types is listed. No model is called.

    .venv/bin/python benchmarks/focus_recall.py [--data tests/data] [--misses] [--json]
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import Any, cast

from emboteam.bench.dev_corpus import DevTask, development_tasks
from emboteam.llm.client import LLMClient
from emboteam.pfg.focus import condition_types
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.world.catalogue import SAME_PLACE, load_catalogue
from emboteam.world.scene import load_scene

NO_CLIENT = cast(LLMClient, None)  # nothing is sent


def missing_types(dev: DevTask, frontend: LLMFrontend) -> list[str]:
    """The goal types of a task that its listing does not show in detail."""
    task = dev.task
    scene, state, team = load_scene(task.floor_plan), task.initial_state(), task.team()
    listed = frontend.listed_types(task.instruction, scene, state, team)
    if listed is None:
        return []
    cat = load_catalogue()
    missing: set[str] = set()
    for cond in task.goal.conditions:
        for t in condition_types(cond, state):
            forms = set(SAME_PLACE.get(t, frozenset({t})))
            if (source := cat.source_type(t)) is not None:
                forms.add(source)
            if not forms & listed:
                missing.add(t)
    return sorted(missing)


def measure(data: Path) -> dict[str, Any]:
    frontend = LLMFrontend(NO_CLIENT)
    per_set: dict[str, list[int]] = {}
    misses: list[dict[str, Any]] = []
    for dev in development_tasks(data):
        missing = missing_types(dev, frontend)
        per_set.setdefault(dev.set, [0, 0])
        per_set[dev.set][0] += 1
        per_set[dev.set][1] += not missing
        if missing:
            misses.append({"set": dev.set, "task": dev.task.id, "instruction": dev.task.instruction,
                           "missing": missing})
    total = sum(n for n, _ in per_set.values())
    hit = sum(h for _, h in per_set.values())
    return {"tasks": total, "recalled": hit, "recall": round(hit / total, 4),
            "sets": {k: {"tasks": n, "recalled": h} for k, (n, h) in sorted(per_set.items())},
            "missing_types": dict(Counter(t for m in misses for t in m["missing"]).most_common()),
            "misses": misses}


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", type=Path, default=Path(__file__).resolve().parents[1] / "tests" / "data")
    ap.add_argument("--misses", action="store_true", help="print every task with a goal type not listed")
    ap.add_argument("--json", action="store_true", help="one JSON object on stdout")
    args = ap.parse_args(argv)
    result = measure(args.data)
    if args.json:
        print(json.dumps(result))
        return 0
    print(f"focus recall: {result['recalled']}/{result['tasks']} = {result['recall']:.4f}")
    for name, s in result["sets"].items():
        if s["recalled"] < s["tasks"]:
            print(f"  {name}: {s['recalled']}/{s['tasks']}")
    if result["missing_types"]:
        print(f"  types not listed: {result['missing_types']}")
    if args.misses:
        for m in result["misses"]:
            print(f"  MISS {m['set']}/{m['task']}: {m['instruction']!r} -> {m['missing']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
