"""Dump the plans of every MACE-THOR task and of the quick sweep to JSON, and compare dumps.

The planner must give the same plan for the same input on any machine and under any load
(issue 28): every search budget that shapes a plan is counted in search steps, not
seconds. This script is how that is checked across processes (different hash seeds,
different load), and how a restructuring of the planner is checked to change no plan:

    .venv/bin/python benchmarks/plan_dump.py --out /tmp/a.json           # MACE-THOR + quick sweep
    PYTHONHASHSEED=7 .venv/bin/python benchmarks/plan_dump.py --out /tmp/b.json
    .venv/bin/python benchmarks/plan_dump.py --compare /tmp/a.json /tmp/b.json   # exit 1 on a difference

A plan is dumped as its steps (robot, action, subtask, waits, spots), sync points and
simulated makespan; timings and call counts are left out (they may differ between runs).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Iterator, Sequence
from pathlib import Path

from emboteam.errors import EmboTeamError
from emboteam.hp.goalgen import sweep_cell
from emboteam.hp.plan import MergedPlan
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

#: as benchmarks/plan_latency.py's sweep (profiles cycled; --quick cells)
QUICK_ROBOTS = (2, 8, 32)
QUICK_CONDITIONS = (8, 32, 128)
SCENES = ("FloorPlan1", "FloorPlan201")


def mace_thor_inputs() -> Iterator[tuple[str, TaskSpec, WorldState]]:
    """Every MACE-THOR task as the oracle front end decomposes it."""
    from emboteam.bench.suites import load_suite
    from emboteam.pfg.oracle import OracleFrontend

    for task in load_suite("mace-thor").tasks:
        state = task.initial_state()
        spec = OracleFrontend(task.goal).decompose(task.instruction, load_scene(task.floor_plan), state, task.team())
        yield task.id, spec, state


def sweep_input(scene: str, robots: int, conditions: int, seed: int) -> tuple[str, TaskSpec, WorldState]:
    """One sweep cell, named: a team of ``robots`` and ``conditions`` random consistent goals."""
    spec, state = sweep_cell(scene, robots, conditions, seed)
    return f"{scene} {robots}x{conditions} seed {seed}", spec, state


def sweep_inputs(robots: Sequence[int], conditions: Sequence[int], seeds: Sequence[int]
                 ) -> Iterator[tuple[str, TaskSpec, WorldState]]:
    for seed in seeds:
        for scene in SCENES:
            for n in robots:
                for k in conditions:
                    yield sweep_input(scene, n, k, seed)


def plan_record(plan: MergedPlan) -> dict[str, object]:
    """What must not change: steps, waits, spots, sync points, simulated makespan."""
    return {
        "steps": [[s.id, s.robot, str(s.action), s.subtask, list(s.after), list(s.resources)] for s in plan.steps],
        "sync": [[p.producer, p.consumer] for p in plan.sync],
        "makespan": plan.makespan,
        "joint": plan.joint,
    }


def dump(inputs: Iterator[tuple[str, TaskSpec, WorldState]], config: PlannerConfig) -> dict[str, object]:
    out: dict[str, object] = {}
    for label, spec, state in inputs:
        t0 = time.perf_counter()
        try:
            plan = HybridPlanner(config).plan(spec, state)
        except EmboTeamError as exc:
            out[label] = {"error": f"{type(exc).__name__}: {exc}"}
        else:
            out[label] = plan_record(plan)
        print(f"{label}: {time.perf_counter() - t0:.2f} s", file=sys.stderr)
    return out


def compare(a: dict[str, object], b: dict[str, object]) -> list[str]:
    """Labels whose plans differ (or are in one dump only)."""
    return sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k))


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, help="write the plans here (JSON)")
    ap.add_argument("--seeds", default="0", help="goal seeds of the quick sweep, e.g. 0,1,2")
    ap.add_argument("--no-suite", action="store_true", help="skip the MACE-THOR tasks")
    ap.add_argument("--no-sweep", action="store_true", help="skip the quick sweep")
    ap.add_argument("--compare", nargs=2, type=Path, metavar=("A", "B"), help="compare two dumps; exit 1 if any plan differs")
    args = ap.parse_args(argv)
    if args.compare:
        a, b = (json.loads(p.read_text()) for p in args.compare)
        differ = compare(a, b)
        for label in differ:
            print(f"differs: {label}")
        print(f"{len(set(a) | set(b)) - len(differ)} identical, {len(differ)} differ")
        return 1 if differ else 0
    if args.out is None:
        ap.error("--out is required unless --compare")
    seeds = [int(s) for s in args.seeds.split(",")]
    config = PlannerConfig()
    plans: dict[str, object] = {}
    if not args.no_suite:
        plans.update(dump(mace_thor_inputs(), config))
    if not args.no_sweep:
        plans.update(dump(sweep_inputs(QUICK_ROBOTS, QUICK_CONDITIONS, seeds), config))
    args.out.write_text(json.dumps(plans, indent=0, sort_keys=True))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
