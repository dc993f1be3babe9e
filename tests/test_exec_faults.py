"""Success rate under faults: the behavior tree (alone, and with the hybrid planner as
replanner) against the no-BTC (linear) ablation, with the ground-truth goals, on
hand-written sample plans and on the hybrid planner's own plans for the same kind of goals.

Targets (issue 4): SR = 1.0 without faults; SR >= 0.9 at ``FaultConfig.level(0.2)``
(20 % of actions fail, 10 % of approaches occluded) and at least 0.2 above the ablation.

The tests run a few seeds; for the full table::

    .venv/bin/python tests/test_exec_faults.py --seeds 50
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from emboteam.exec.executor import Executor
from emboteam.exec.linear import run_linear
from emboteam.hp.plan import MergedPlan
from emboteam.sim import FaultConfig, Simulator
from emboteam.world.goals import Goal
from test_btc_plans import PLANNED, SCENARIOS, planned, real_replanner, team_sim

MODES = ("bt", "bt+replan", "linear")

Case = tuple[str, MergedPlan, Goal, str, str]


def hand_written(names: Sequence[str] | None = None) -> list[Case]:
    out = []
    for scenario, floor_plan, team in SCENARIOS:
        if names is None or scenario.__name__ in names:
            plan, goal = scenario()
            out.append((scenario.__name__, plan, goal, floor_plan, team))
    return out


def planner_made() -> list[Case]:
    out = []
    for floor_plan, team, goal_text in PLANNED:
        plan, goal = planned(floor_plan, team, goal_text)
        out.append((f"hp:{floor_plan}/{len(goal.conditions)}c", plan, goal, floor_plan, team))
    return out


def success_rates(level: float, seeds: range, cases: Sequence[Case]) -> dict[str, float]:
    wins = dict.fromkeys(MODES, 0)
    n = 0
    for _, plan, goal, floor_plan, team in cases:
        for seed in seeds:
            n += 1

            def sim(floor_plan: str = floor_plan, team: str = team, seed: int = seed) -> Simulator:
                return team_sim(floor_plan, team, seed=seed, faults=FaultConfig.level(level))

            wins["bt"] += Executor(sim(), plan, goal).run().success
            wins["bt+replan"] += Executor(sim(), plan, goal, replanner=real_replanner()).run().success
            wins["linear"] += run_linear(sim(), plan, goal).success
    return {m: wins[m] / n for m in MODES}


def test_no_faults_everything_succeeds() -> None:
    sr = success_rates(0.0, range(1), hand_written() + planner_made())
    assert sr["bt"] == sr["bt+replan"] == 1.0
    # the linear ablation has no spot protocol: three robots rushing to one counter top
    # collide (spot busy) unless the plan serialises them itself; the others succeed. (The
    # planner's plans are not in this list: two robots putting things in one fridge may
    # meet there, which only the spot protocol sorts out.)
    others = [c for c in hand_written() if c[0] != "counter_rush"]
    assert success_rates(0.0, range(1), others)["linear"] == 1.0
    assert success_rates(0.0, range(1), hand_written(["counter_rush"]))["linear"] == 0.0


def test_tree_meets_the_target_at_level_0_2() -> None:
    sr = success_rates(0.2, range(1, 7), hand_written() + planner_made())
    assert sr["bt"] >= 0.9
    assert sr["bt+replan"] >= sr["bt"]
    assert sr["bt"] - sr["linear"] >= 0.2


def test_tree_degrades_gracefully_at_level_0_4() -> None:
    sr = success_rates(0.4, range(3), planner_made())
    assert sr["bt+replan"] >= 0.8 and sr["bt+replan"] > sr["linear"]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=50)
    ap.add_argument("--levels", type=float, nargs="*", default=[0.0, 0.1, 0.2, 0.3, 0.4])
    args = ap.parse_args()
    cases = hand_written() + planner_made()
    print(f"SR x {args.seeds} seeds per plan")
    print(f"{'plan':>18} {'faults':>6} " + " ".join(f"{m:>10}" for m in MODES))
    for level in args.levels:
        total = dict.fromkeys(MODES, 0.0)
        for case in cases:
            sr = success_rates(level, range(args.seeds), [case])
            print(f"{case[0]:>18} {level:>6.2f} " + " ".join(f"{sr[m]:>10.3f}" for m in MODES))
            for m in MODES:
                total[m] += sr[m] / len(cases)
        print(f"{'all':>18} {level:>6.2f} " + " ".join(f"{total[m]:>10.3f}" for m in MODES), flush=True)


if __name__ == "__main__":
    main()
