"""Our schedules against CP-SAT's exact reference (emboteam.hp.optimal, issue 28).

For every MACE-THOR task and every cell of the quick sweep (benchmarks/plan_latency.py's
cells, goal seeds given by --seeds), plan with the hybrid planner (``--schedule fast``, the
default, or ``optimal``), then give the plan's actions to the CP-SAT model of the whole
schedule (allocation of the jobs to capable robots, their order, dependencies, one robot
per spot, drives between places) with a deterministic time limit. Reported per input: our
makespan, CP-SAT's best makespan and bound, whether it proved optimality, our makespan /
proven optimum (or / best bound), and the makespan / resource-aware bound.

    .venv/bin/python benchmarks/plan_optimal.py --seeds 0,1,2,3,4 --out /tmp/optimal.json
    .venv/bin/python benchmarks/plan_optimal.py --no-sweep          # MACE-THOR only
    .venv/bin/python benchmarks/plan_optimal.py --no-suite --schedule optimal --robots 2,4,8 --conditions 8,16,24
    .venv/bin/python benchmarks/plan_optimal.py --no-suite --cells FloorPlan1:2x24:3,FloorPlan201:4x24:4
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from collections.abc import Iterator, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path

from plan_dump import QUICK_CONDITIONS, QUICK_ROBOTS, mace_thor_inputs, sweep_input, sweep_inputs

from emboteam.errors import EmboTeamError
from emboteam.hp.optimal import PORTFOLIO, REFERENCE_LIMIT, Portfolio, ScheduleTimeoutError, reference
from emboteam.hp.plan import MergedPlan
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.stages import schedule as schedule_stage
from emboteam.hp.validate import simulate
from emboteam.pddl.problem import planning_state
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.state import WorldState


@dataclass
class Row:
    label: str
    robots: int
    conditions: int
    seconds: float
    makespan: float
    resource_bound: float
    #: the resource-aware bound's carry term (hp.carry_bound), and the bound without it
    carry: float = 0.0
    without_carry: float = 0.0
    status: str = "not modelled"
    best: float = 0.0
    bound: float = 0.0
    solve_seconds: float = 0.0
    #: CP-SAT's deterministic seconds (what its limit counts; the same on any machine)
    solve_deterministic: float = 0.0
    error: str = ""

    @property
    def ratio(self) -> float | None:
        """Our makespan / proven optimum (optimal) or / CP-SAT's best bound."""
        ref = self.best if self.status == "optimal" else self.bound
        return self.makespan / ref if ref > 0 else None


def run(inputs: Iterator[tuple[str, TaskSpec, WorldState]], config: PlannerConfig, limit: float,
        bound_limit: float = 0.0, check_limit: float = 0.0, portfolio: Portfolio = PORTFOLIO) -> list[Row]:
    rows: list[Row] = []
    for label, spec, state in inputs:
        t0 = time.perf_counter()
        try:
            plan = HybridPlanner(config).plan(spec, state)
        except EmboTeamError as exc:
            rows.append(Row(label, len(state.robots), len(spec.subtasks), time.perf_counter() - t0, 0.0, 0.0,
                            error=f"{type(exc).__name__}: {exc}"[:120]))
            continue
        row = Row(label, len(state.robots), len(spec.subtasks), time.perf_counter() - t0, plan.makespan,
                  plan.resource_bound)
        row.carry, row.without_carry = _carry(plan, spec, state)
        t1 = time.perf_counter()
        try:
            ref = (reference(plan, spec, planning_state(state), limit, bound_limit=bound_limit,
                             check_limit=check_limit, portfolio=portfolio)
                   if limit > 0 else None)
        except ScheduleTimeoutError as exc:  # the wall-clock safety net: no answer
            ref, row.error = None, str(exc)[:120]
        row.solve_seconds = time.perf_counter() - t1
        if ref is not None:
            row.status, row.best, row.bound, row.solve_deterministic = ref.status, ref.makespan, ref.bound, ref.deterministic
        rows.append(row)
        r = row.ratio
        print(f"{label}: makespan {row.makespan:.1f}, CP-SAT {row.status} {row.best:.1f} (bound {row.bound:.1f}), "
              f"ratio {'-' if r is None else f'{r:.3f}'}, {row.solve_seconds:.1f} s ({row.solve_deterministic:.1f} "
              "deterministic)", file=sys.stderr)
    return rows


def _carry(plan: MergedPlan, spec: TaskSpec, state: WorldState) -> tuple[float, float]:
    """The plan's resource-aware bound's carry term and its value without that term (the
    plan simulated again: the plan keeps only the value)."""
    b = simulate(plan, planning_state(state), spec.goal()).resources
    return b.carry, max(b.work, b.subtask, b.spot, b.spot_window, b.object, b.object_window)


def cell_inputs(cells: str) -> Iterator[tuple[str, TaskSpec, WorldState]]:
    """The sweep cells named ``scene:ROBOTSxGOALS:seed`` (comma-separated), in that order:
    to rerun only the cells a change is about."""
    for name in cells.split(","):
        try:
            scene, size, seed = name.split(":")
            robots, goals = size.split("x")
            yield sweep_input(scene, int(robots), int(goals), int(seed))
        except ValueError:
            raise SystemExit(f"plan_optimal.py: bad cell {name!r} (want scene:ROBOTSxGOALS:seed)") from None


def summary(rows: Sequence[Row], what: str) -> list[str]:
    modelled = [r for r in rows if r.ratio is not None]
    proven = [r for r in rows if r.status == "optimal"]
    lines = [f"- {what}: {len(rows)} inputs, {len(modelled)} with a CP-SAT reference, optimality proven on "
             f"{len(proven)} ({len(proven) / max(len(rows), 1):.0%})."]
    if modelled:
        ratios = [r.ratio for r in modelled if r.ratio is not None]
        lines.append(f"  makespan / (proven optimum or best bound): mean {statistics.mean(ratios):.3f}, "
                     f"max {max(ratios):.3f}; above 1.10 on {sum(x > 1.10 for x in ratios)}.")
    if proven:
        pr = [r.makespan / r.best for r in proven if r.best > 0]
        lines.append(f"  where proven: makespan / optimum mean {statistics.mean(pr):.3f}, max {max(pr):.3f}.")
    aware = [r.makespan / r.resource_bound for r in rows if r.resource_bound > 0]
    if aware:
        plain = [r.makespan / r.without_carry for r in rows if r.without_carry > 0]
        lines.append(f"  makespan / resource-aware bound: mean {statistics.mean(aware):.3f} over {len(aware)} inputs "
                     f"(without its carry term: {statistics.mean(plain):.3f}; the term sets it on "
                     f"{sum(r.carry > r.without_carry for r in rows)}).")
    return lines


def table(rows: Sequence[Row]) -> str:
    head = ("| input | robots | cond. | ours s | makespan | CP-SAT | best | bound | ours / ref | CP-SAT s | "
            "CP-SAT det. s |")
    out = [head, "|" + "---|" * 11]
    for r in rows:
        ratio = r.ratio
        out.append(f"| {r.label} | {r.robots} | {r.conditions} | {r.seconds:.2f} | {r.makespan:.1f} | {r.status} | "
                   f"{r.best:.1f} | {r.bound:.1f} | {'-' if ratio is None else f'{ratio:.3f}'} | {r.solve_seconds:.1f} | "
                   f"{r.solve_deterministic:.1f} |")
    return "\n".join(out)


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", default="0", help="goal seeds of the quick sweep")
    ap.add_argument("--robots", default=",".join(map(str, QUICK_ROBOTS)), help="team sizes of the sweep")
    ap.add_argument("--conditions", default=",".join(map(str, QUICK_CONDITIONS)), help="goals per sweep cell")
    ap.add_argument("--cells", help="only these sweep cells, scene:ROBOTSxGOALS:seed, comma-separated "
                    "(e.g. FloorPlan1:2x24:3); --seeds, --robots and --conditions are then ignored")
    ap.add_argument("--no-suite", action="store_true")
    ap.add_argument("--no-sweep", action="store_true")
    ap.add_argument("--schedule", choices=("fast", "optimal", "heuristic"), default="fast",
                    help="heuristic: fast without its CP-SAT stage (what the heuristics alone make)")
    ap.add_argument("--limit", type=float, default=REFERENCE_LIMIT,
                    help="CP-SAT deterministic seconds per input (0: no CP-SAT, the plans and the resource-aware ratio only)")
    ap.add_argument("--bound-limit", type=float, default=0.0,
                    help="where CP-SAT ends unproven, this many more deterministic seconds on the route relaxation "
                    "(emboteam.hp.optimal_bound) for a higher bound; 0: none")
    ap.add_argument("--check-limit", type=float, default=0.0,
                    help="where the bound is still below the best schedule, this many more deterministic seconds of "
                    "branch-and-check, one cap at a time (emboteam.hp.optimal_check); 0: none")
    ap.add_argument("--searches", default=",".join(PORTFOLIO.searches),
                    help="CP-SAT's full-problem searches, one worker each, comma-separated (emboteam.hp.optimal."
                    "Portfolio; default: the reference's own)")
    ap.add_argument("--out", type=Path, help="write the rows here (JSON)")
    args = ap.parse_args(argv)
    portfolio = Portfolio(tuple(args.searches.split(",")))
    if args.schedule == "heuristic":
        schedule_stage.FAST_STEPS = 0  # no plan is small enough: the stage never runs
    config = PlannerConfig(schedule="optimal" if args.schedule == "optimal" else "fast")
    load0 = os.getloadavg()[0]
    started = time.strftime("%Y-%m-%d %H:%M")
    suite = [] if args.no_suite else run(mace_thor_inputs(), config, args.limit, args.bound_limit, args.check_limit,
                                           portfolio)
    seeds = [int(s) for s in args.seeds.split(",")]
    cells: dict[int, list[Row]] = {}
    if args.cells and not args.no_sweep:
        cells[-1] = run(cell_inputs(args.cells), config, args.limit, args.bound_limit, args.check_limit, portfolio)
    elif not args.no_sweep:
        for seed in seeds:
            cells[seed] = run(sweep_inputs([int(x) for x in args.robots.split(",")],
                                           [int(x) for x in args.conditions.split(",")], [seed]), config, args.limit,
                               args.bound_limit, args.check_limit, portfolio)
    lines = [f"{started}, load {load0:.1f} before, {os.cpu_count()} cores; schedule {args.schedule}, CP-SAT limit "
             f"{args.limit:g} deterministic s, route bound {args.bound_limit:g} s, "
             f"branch-and-check {args.check_limit:g} s, searches {','.join(portfolio.searches)} "
             f"({portfolio.workers} workers, batches of {portfolio.batch})"]
    if suite:
        lines += summary(suite, "MACE-THOR")
    for seed, rows in cells.items():
        lines += summary(rows, "the cells given" if seed < 0 else f"quick sweep, seed {seed}")
    print("\n".join(lines))
    for name, rows in [("MACE-THOR", suite), *((f"cells {args.cells}" if s < 0 else f"quick sweep, seed {s}", r)
                                                    for s, r in cells.items())]:
        if rows:
            print(f"\n### {name}\n\n{table(rows)}")
    if args.out:
        args.out.write_text(json.dumps({"summary": lines, "suite": [asdict(r) for r in suite],
                                        "sweep": {str(s): [asdict(r) for r in rows] for s, rows in cells.items()}},
                                       indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
