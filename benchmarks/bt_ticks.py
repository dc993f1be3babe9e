"""Tick cost of compiled behavior trees: N robots x M actions in one kitchen.

Each robot carries its own object back and forth between two counter tops (GoTo, Pickup,
GoTo, Put, ...), so the robots contend for the counter tops' interaction spots and the
lock protocol is exercised; consecutive robots also hand over through sync points (robot
k+1's first put waits for robot k's first put). Literals come from the planner's domain
(``emboteam.pddl.domain.step_literals``).

    .venv/bin/python benchmarks/bt_ticks.py                 # 10 robots x 50 actions
    .venv/bin/python benchmarks/bt_ticks.py --robots 4 --actions 20 --seeds 3

Prints one row per fault level: compile time, ticks per episode, wall time per tick,
episode wall time, simulated makespan, and success.
"""

from __future__ import annotations

import argparse
import statistics
import time

from emboteam.btc.compiler import compile_plan
from emboteam.btc.runtime import Runtime
from emboteam.exec.executor import Executor, ExecutorSettings
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.pddl.domain import step_literals
from emboteam.sim import FaultConfig, Simulator
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.actions import Action, Skill
from emboteam.world.checker import check_goal
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

FLOOR_PLAN = "FloorPlan1"
#: pickupable objects on open surfaces of FloorPlan1, one per robot
OBJECTS = ["Apple_1", "Bread_1", "CreditCard_1", "Tomato_1", "Lettuce_1", "Mug_1", "Potato_1",
           "SaltShaker_1", "PepperShaker_1", "Spatula_1", "SoapBottle_1", "PaperTowelRoll_1"]
COUNTERS = ["CounterTop_1", "CounterTop_2", "CounterTop_3"]


def build(n_robots: int, n_actions: int) -> tuple[MergedPlan, Goal, str]:
    if n_robots > len(OBJECTS):
        raise SystemExit(f"at most {len(OBJECTS)} robots")
    team = ",".join(["1"] * n_robots)
    profiles = parse_team(team)
    world = WorldState.from_scene(load_scene(FLOOR_PLAN), profiles)
    actions: dict[str, list[Action]] = {}
    for i, p in enumerate(profiles):
        obj = OBJECTS[i]
        here = world.objects[obj].parent
        seq: list[Action] = []
        k = i
        while len(seq) + 4 <= n_actions:
            dest = next(c for c in COUNTERS[k % 3:] + COUNTERS[: k % 3] if c != here)
            seq += [Action(skill=Skill.GoToObject, target=obj), Action(skill=Skill.PickupObject, target=obj),
                    Action(skill=Skill.GoToObject, target=dest),
                    Action(skill=Skill.PutObject, target=obj, receptacle=dest)]
            here, k = dest, k + 1
        while len(seq) < n_actions:
            seq.append(Action(skill=Skill.GoToObject, target=COUNTERS[len(seq) % 3]))
        actions[p.name] = seq
    names = [p.name for p in profiles]
    after = {f"{names[i + 1]}.4": (f"{names[i]}.4",) for i in range(n_robots - 1) if n_actions >= 4}
    order: list[tuple[str, int]] = []
    idx = dict.fromkeys(names, 0)
    done: set[str] = set()
    while len(order) < n_robots * n_actions:
        for r in names:
            while idx[r] < n_actions and all(p in done for p in after.get(f"{r}.{idx[r] + 1}", ())):
                idx[r] += 1
                order.append((r, idx[r]))
                done.add(f"{r}.{idx[r]}")
    steps = []
    for r, i in order:
        a = actions[r][i - 1]
        pre, post = step_literals(r, a, world)
        steps.append(PlanStep(id=f"{r}.{i}", robot=r, action=a, subtask="s1",
                              after=after.get(f"{r}.{i}", ()), pre=pre, post=post))
        if check_action(world, r, a) is None:
            apply_action(world, r, a)
    goal_conditions = [f"inside({OBJECTS[i]}, {world.objects[OBJECTS[i]].parent})" for i in range(n_robots)]
    return MergedPlan(robots=tuple(names), steps=tuple(steps)), Goal.parse(goal_conditions), team


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--robots", type=int, default=10)
    ap.add_argument("--actions", type=int, default=50)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--faults", type=float, nargs="*", default=[0.0, 0.2])
    args = ap.parse_args()
    plan, goal, team = build(args.robots, args.actions)
    scene = load_scene(FLOOR_PLAN)
    t0 = time.perf_counter()
    compiled = compile_plan(plan, Runtime(Simulator(scene, parse_team(team))))
    compile_s = time.perf_counter() - t0
    n_nodes = sum(1 for _ in compiled.nodes())
    compiled.close()
    print(f"{args.robots} robots x {args.actions} actions = {len(plan.steps)} steps, {n_nodes} tree nodes, "
          f"compile {compile_s * 1000:.0f} ms")
    header = f"{'faults':>6} {'seed':>4} {'ticks':>6} {'ms/tick':>8} {'wall s':>7} {'makespan':>9} {'recov':>6} {'ok':>3}"
    print(header)
    print("-" * len(header))
    for p in args.faults:
        per_tick = []
        for seed in range(args.seeds):
            sim = Simulator(scene, parse_team(team), seed=seed, faults=FaultConfig.level(p))
            ex = Executor(sim, plan, goal, settings=ExecutorSettings(time_limit=3600.0))
            t0 = time.perf_counter()
            res = ex.run()
            wall = time.perf_counter() - t0
            per_tick.append(wall / max(res.ticks, 1) * 1000)
            ok = check_goal(goal, sim.observe()).success
            print(f"{p:>6.2f} {seed:>4} {res.ticks:>6} {per_tick[-1]:>8.3f} {wall:>7.2f} {res.makespan:>9.1f} "
                  f"{res.recoveries:>6} {'yes' if ok else 'no':>3}")
        print(f"{p:>6.2f} mean ms/tick {statistics.mean(per_tick):.3f}")


if __name__ == "__main__":
    main()
