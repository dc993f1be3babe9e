"""The development tasks with ground truth, in one list: what the LLM front end's focus,
answer checks and worked examples are measured and chosen against.

- ``tests/data/blind_r*/dev``: the blind development rounds (SMART-LLM / MAT-THOR format);
- ``tests/data/offline_dev*.jsonl``: the offline parser's development sets (records with
  an expected error have no goal and are left out);
- MACE-THOR (package data).

Held-out sets (``blind_r*/heldout``, ``offline_heldout.jsonl``) and the unseen suite are
never read here, nor a development round whose ``ABOUT.md`` still says it is not yet measured
(:data:`UNMEASURED_MARKER`): the lead measures such a round fresh once, then removes the line. Each task carries the name of its set, so a caller can keep a task's
own set out of what it learns from (``DevTask.set``).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from emboteam.bench.importers.smart_llm import import_smart_llm
from emboteam.bench.mace_thor import load_mace_thor
from emboteam.task import BenchTask

#: blind rounds written to be held out and not yet read: no development script reads them
#: (their ``heldout`` folders are outside :func:`development_tasks` anyway; the benchmark
#: scripts that take any folder check this list). docs/unseen_suite.md says what each is for.
HELD_OUT_ROUNDS = ("blind_r42", "blind_r44", "blind_r46", "blind_r48", "blind_r50", "blind_r52",
                   "blind_r54", "blind_r56", "blind_r58", "blind_r60", "blind_r62", "blind_r64",
                   "blind_r66", "blind_r68")

#: a line of a round's ``ABOUT.md`` saying its ``dev`` tasks await their one fresh measurement;
#: until the lead removes it, no fitting or failure-listing script may read the round's words
UNMEASURED_MARKER = "Status: not yet measured"

#: the team a record without one is read with (the offline sets' default)
DEFAULT_ROBOTS = ("1", "2", "3")


@dataclass(frozen=True)
class DevTask:
    """A development task and the set it belongs to (``blind_r20``, ``offline_dev``, ``mace-thor``)."""

    set: str
    task: BenchTask


def _jsonl_tasks(path: Path) -> list[DevTask]:
    out: list[DevTask] = []
    name = path.stem
    for line in path.read_text(encoding="utf-8").splitlines():
        if not line.strip():
            continue
        rec = json.loads(line)
        if "error" in rec or not rec.get("goal"):
            continue
        robots = tuple(str(r).strip() for r in str(rec.get("robots", ",".join(DEFAULT_ROBOTS))).split(","))
        task = BenchTask(id=str(rec["id"]), suite=name, floor_plan=str(rec["scene"]), robots=robots,
                         category="imported", instruction=str(rec["instruction"]), goal=rec["goal"],
                         setup=tuple(rec.get("setup") or ()))
        out.append(DevTask(name, task))
    return out


def is_unmeasured(round_dir: Path) -> bool:
    """True when the round's ``ABOUT.md`` holds the line :data:`UNMEASURED_MARKER`."""
    about = round_dir / "ABOUT.md"
    if not about.is_file():
        return False
    return any(line.strip() == UNMEASURED_MARKER
               for line in about.read_text(encoding="utf-8").splitlines())


def development_tasks(data_dir: Path, *, mace_thor: bool = True) -> list[DevTask]:
    """Every development task with a ground-truth goal under ``data_dir`` (``tests/data``),
    in a fixed order (sets by name, tasks as their files list them). Rounds not yet
    measured (:func:`is_unmeasured`) and the held-out rounds (:data:`HELD_OUT_ROUNDS`, by
    name, should one ever get a ``dev`` folder) are skipped."""
    out: list[DevTask] = []
    for round_dir in sorted(data_dir.glob("blind_r*/dev")):
        if round_dir.parent.name in HELD_OUT_ROUNDS or is_unmeasured(round_dir.parent):
            continue
        name = round_dir.parent.name
        suite = import_smart_llm(round_dir, suite=name)
        out += [DevTask(name, t) for t in suite.tasks if t.goal.conditions]
    for path in sorted(data_dir.glob("offline_dev*.jsonl")):
        out += _jsonl_tasks(path)
    if mace_thor:
        out += [DevTask("mace-thor", t) for t in load_mace_thor()]
    return out
