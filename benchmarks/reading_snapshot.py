"""The offline reading of every development instruction, dumped to one JSON file, so that a
refactoring of the reader can be checked for an unchanged behaviour with a plain diff.

What is read: every line of every ``FloorPlanN*.json`` under ``tests/data/blind_r*/`` (dev
and heldout folders; the held-out rounds of ``HELD_OUT_ROUNDS`` and rounds still marked unmeasured excluded), ``tests/data/offline_*.jsonl``, MACE-THOR,
and the SMART-LLM peers' tasks under ``/work/shared/data/peers`` (or ``--peers DIR``).
Never ``tests/data/unseen_tasks.json``. For each instruction: the goal conditions, the
full TaskSpec, the notes and the unsure conditions, or the error's class and message.

    .venv/bin/python benchmarks/reading_snapshot.py --out /tmp/before.json
    .venv/bin/python benchmarks/reading_snapshot.py --out /tmp/after.json --diff /tmp/before.json

With ``--diff OLD`` the exit status is 1 when any reading differs from OLD (each
difference printed), 0 when none does.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from emboteam.bench.dev_corpus import HELD_OUT_ROUNDS, is_unmeasured
from emboteam.bench.importers.lenient import read_record
from emboteam.bench.importers.smart_llm import _floor_number, task_files
from emboteam.bench.mace_thor import load_mace_thor
from emboteam.bench.offline_accuracy import initial_state as record_state
from emboteam.bench.offline_accuracy import load_records
from emboteam.errors import EmboTeamError
from emboteam.pfg.offline import OfflineFrontend
from emboteam.task import initial_state
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene, normalize_floor_plan

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
PEERS = Path("/work/shared/data/peers")
EXCLUDED_ROUNDS = set(HELD_OUT_ROUNDS)

#: (key, instruction, floor plan, team, setup records or None)
Item = tuple[str, str, str, str, list[Any]]


def _floor_files(root: Path) -> Iterator[tuple[str, Path]]:
    for file in task_files(root):
        yield file.relative_to(ROOT if ROOT in file.parents else root).as_posix(), file


def _smart_llm(root: Path) -> Iterator[Item]:
    """Every line of the SMART-LLM format files beneath ``root``, ground truth or not."""
    for rel, file in _floor_files(root):
        floor = normalize_floor_plan(_floor_number(file))
        for lineno, line in enumerate(file.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            if not line.strip():
                continue
            try:
                record, _ = read_record(line)
            except EmboTeamError:
                continue
            if not isinstance(record, dict) or not isinstance(record.get("task"), str):
                continue
            robots = ",".join(str(r) for r in record.get("robot list") or [1, 2])
            yield f"{rel}:{lineno}", record["task"], floor, robots, []


def items(peers: Path) -> Iterator[Item]:
    for round_dir in sorted(DATA.glob("blind_r*")):
        if round_dir.name in EXCLUDED_ROUNDS or is_unmeasured(round_dir):
            continue   # held out, or awaiting its one fresh measurement: nobody reads it yet
        for part in ("dev", "heldout"):
            if (round_dir / part).is_dir():
                yield from _smart_llm(round_dir / part)
    for path in sorted(DATA.glob("offline_*.jsonl")):
        for rec in load_records(path):
            yield (f"{path.name}:{rec['id']}", str(rec["instruction"]), str(rec["scene"]),
                   str(rec.get("robots", "1,2,3")), list(rec.get("setup") or []))   # type: ignore[call-overload]
    for task in load_mace_thor():
        yield (f"mace-thor/{task.id}", task.instruction, task.floor_plan, ",".join(task.robots),
               [c.model_dump(mode="json") for c in task.setup])
    if peers.is_dir():
        yield from _smart_llm(peers)


def read(frontend: OfflineFrontend, item: Item) -> dict[str, Any]:
    _key, text, floor, robots, setup = item
    try:
        team = parse_team(robots)
        scene = load_scene(floor)
        if setup:
            state = record_state({"setup": setup}, scene, team)
        else:
            state = initial_state(scene.floor_plan, team)
        reading = frontend.parse(text, scene, state, team)
    except (EmboTeamError, ValueError) as exc:   # a ValueError is a reader bug: recorded, not fatal
        return {"instruction": text, "error": f"{type(exc).__name__}: {exc}"}
    return {"instruction": text,
            "goal": [str(c) for c in reading.spec.goal().conditions],
            "notes": [str(n) for n in reading.notes],
            "unsure": list(reading.unsure),
            "spec": reading.spec.model_dump(mode="json")}


def snapshot(peers: Path) -> dict[str, Any]:
    frontend = OfflineFrontend()
    out: dict[str, Any] = {}
    for item in items(peers):
        key = item[0]
        while key in out:      # the same line read twice (never expected; kept distinct)
            key += "+"
        out[key] = read(frontend, item)
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, required=True, help="where the snapshot is written")
    parser.add_argument("--diff", type=Path, help="an earlier snapshot to compare with")
    parser.add_argument("--peers", type=Path, default=PEERS, help="the SMART-LLM peers' tasks")
    args = parser.parse_args()
    snap = snapshot(args.peers)
    args.out.write_text(json.dumps(snap, indent=1, sort_keys=True))
    errors = sum("error" in v for v in snap.values())
    print(f"{len(snap)} instructions read ({errors} errors) -> {args.out}")
    if args.diff is None:
        return 0
    old = json.loads(args.diff.read_text())
    differ = sorted(k for k in set(old) | set(snap) if old.get(k) != snap.get(k))
    for k in differ:
        print(f"DIFF {k}\n  before: {json.dumps(old.get(k))[:600]}\n  after:  {json.dumps(snap.get(k))[:600]}")
    print(f"{len(differ)} differences against {args.diff}")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
