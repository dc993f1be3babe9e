"""Re-allocation from measured plans (hp/rebalance.py) and the planner's second pass."""

from __future__ import annotations

import random

from emboteam.hp.goalgen import random_conditions
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.rebalance import Job, cp_sat, lpt, rebalance
from emboteam.hp.validate import simulate
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

TEAM = ("robot1", "robot2")


def _jobs(*seconds: float, team: tuple[str, ...] = TEAM) -> list[Job]:
    return [Job(f"j{i}", (team[0],), s, team) for i, s in enumerate(seconds)]


def test_cp_sat_beats_greedy_where_greedy_falls_short_and_is_deterministic() -> None:
    # LPT puts 3 and 3 on different robots, then 2, 2, 2: 7 against the optimum 6 (3+3 | 2+2+2)
    jobs = _jobs(3, 3, 2, 2, 2)
    greedy, worst = lpt(jobs, TEAM)
    assert worst == 7
    answers = [cp_sat(jobs, TEAM, greedy) for _ in range(3)]
    assert all(a is not None and a[1] == 6 for a in answers)
    assert answers[0] == answers[1] == answers[2]  # one worker, fixed seed, deterministic limit
    chosen = rebalance(jobs, TEAM, busiest=7.5)
    assert chosen is not None
    load = {r: sum(j.seconds for j in jobs if chosen[j.id] == r) for r in TEAM}
    assert max(load.values()) == 6


def test_rebalancing_is_never_worse_than_greedy_and_respects_who_can() -> None:
    rng = random.Random(3)
    team = ("a", "b", "c")
    for _ in range(20):
        jobs = [Job(f"j{i}", ("a",), rng.randint(1, 30), tuple(sorted(rng.sample(team, rng.randint(1, 3)))))
                for i in range(rng.randint(4, 9))]
        # a team job keeps its robots
        jobs.append(Job("team", ("a", "b"), 10.0, ()))
        _, greedy = lpt(jobs, team)
        chosen = rebalance(jobs, team, busiest=1e9)
        assert chosen is not None and "team" not in chosen
        assert all(chosen[j.id] in j.candidates for j in jobs if j.candidates)
        load = {r: 0.0 for r in team}
        load["a"] += 5.0
        load["b"] += 5.0
        for j in jobs:
            if j.candidates:
                load[chosen[j.id]] += j.seconds
        assert max(load.values()) <= greedy + 1e-9


def test_no_second_pass_for_small_gains_or_few_clusters() -> None:
    assert rebalance(_jobs(5, 5, 5, 5), TEAM, busiest=10.0) is None  # already balanced
    assert rebalance(_jobs(9, 1), TEAM, busiest=10.0) is None  # two clusters: not worth a pass


def _cell(robots: int, conditions: int) -> tuple[TaskSpec, WorldState]:
    team = parse_team(["1", "2", "3", "4"][:robots])
    state = WorldState.from_scene(load_scene("FloorPlan1"), team)
    conds = random_conditions(state, conditions, random.Random(0))
    spec = TaskSpec(instruction=str(Goal(conditions=tuple(conds))), subtasks=tuple(
        Subtask(id=f"c{i}", description=str(c), goal=(c,)) for i, c in enumerate(conds, 1)))
    return spec, state


def test_the_rebalanced_plan_is_valid_deterministic_and_not_longer() -> None:
    # FloorPlan1, 4 robots x 24 random conditions: the estimates put 60 s on one robot; the
    # clusters' measured seconds re-allocated, the second pass is about 43 s
    spec, state = _cell(4, 24)
    off = HybridPlanner(PlannerConfig(rebalance="off")).plan(spec, state)
    on = [HybridPlanner(PlannerConfig(rebalance="cp-sat")).plan(spec, state) for _ in range(2)]
    assert on[0].makespan == on[1].makespan and [s.id for s in on[0].steps] == [s.id for s in on[1].steps]
    assert on[0].makespan < 0.9 * off.makespan
    assert any(n.startswith("re-allocated from the measured plans") for n in on[0].notes)
    timing = simulate(on[0], state, spec.goal())
    assert timing.ok, timing.failure
