"""The idle-robot stage (hp/stages/idle.py): a capable robot that ends early, or never
moves, takes jobs from the robot that ends last, wherever it stands; the planner keeps
the result only when the rebuilt plan simulates shorter, and it runs."""

from __future__ import annotations

from emboteam.hp.goalgen import sweep_cell
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.routes import Node, Routes, Stop, Walker
from emboteam.hp.stages.idle import ranked, unload_key
from emboteam.hp.stages.idle_chain import chained
from emboteam.hp.validate import simulate


def _node(name: str, x: float) -> Node:
    """A job at (x, 0): four seconds of work there, for robots A, B and C."""
    return Node(name, (Stop(f"{name}.1", (x, 0.0), 4.0),), ("A", "B", "C"))


def _routes() -> Routes:
    # no floor plan: drives are Manhattan at 1 m/s. A does five jobs near x = 0, B one,
    # C stands idle at x = 12, farther from every job than A's and B's routes
    walker = Walker("", {"A": 1.0, "B": 1.0, "C": 1.0}, {"A": (0.0, 0.0), "B": (1.0, 0.0), "C": (12.0, 0.0)})
    nodes = {n.id: n for n in (_node(f"j{i}", float(i)) for i in range(6))}
    return Routes(walker, nodes, {}, {"A": ["j0", "j2", "j3", "j4", "j5"], "B": ["j1"], "C": []})


def test_an_idle_robot_far_from_every_route_takes_a_job_of_the_last_robot() -> None:
    routes = _routes()
    before = unload_key(routes.ends)
    moves = ranked(routes, 10_000)
    assert moves, "no move to the robots that end early"
    assert any("C" in m for m in moves)  # the idle robot is a receiver, far as it stands
    for m in moves:
        assert set(m) - {"A"} and "A" in m  # each takes a job from the last robot
        assert unload_key(routes.ends_with(m) or {}) < before
    assert ranked(_routes(), 10_000) == moves  # the same moves every time


def test_the_planner_gives_idle_robots_work_and_the_plan_is_shorter_and_runs() -> None:
    # FloorPlan201, 8 robots, 24 goals, seed 2: two robots ended at 0 and 1.0 s of 19.5
    spec, state = sweep_cell("FloorPlan201", 8, 24, 2)
    plain = HybridPlanner(PlannerConfig(idle=False)).plan(spec, state)
    plan = HybridPlanner(PlannerConfig()).plan(spec, state)
    assert plan.makespan < plain.makespan
    assert any("ended early" in n for n in plan.notes)
    ends = {r: max((s.est_end for s in plan.steps if s.robot == r), default=0.0) for r in plan.robots}
    plain_ends = {r: max((s.est_end for s in plain.steps if s.robot == r), default=0.0) for r in plain.robots}
    assert min(ends.values()) > min(plain_ends.values())  # the robot that did nothing works
    assert simulate(plan, state, spec.goal()).ok


def _chain_routes() -> Routes:
    # A does two jobs (ends at 9 s); B, next to it, one (4 s); C stands by B but can only
    # do B's kind of job: A's second job helps only if B takes it and C takes B's
    walker = Walker("", {"A": 1.0, "B": 1.0, "C": 1.0}, {"A": (0.0, 0.0), "B": (2.0, 0.0), "C": (3.0, 0.0)})
    nodes = {"a1": Node("a1", (Stop("a1.1", (0.0, 0.0), 4.0),), ("A", "B")),
             "a2": Node("a2", (Stop("a2.1", (1.0, 0.0), 4.0),), ("A", "B")),
             "b1": Node("b1", (Stop("b1.1", (2.0, 0.0), 4.0),), ("B", "C"))}
    return Routes(walker, nodes, {}, {"A": ["a1", "a2"], "B": ["b1"], "C": []})


def test_when_no_single_move_helps_a_chain_of_two_moves_passes_work_along() -> None:
    routes = _chain_routes()
    before = unload_key(routes.ends)
    assert ranked(routes, 10_000) == []  # no single move shortens the routes
    change = chained(routes, ["B", "C"], 10_000, unload_key)
    assert change is not None
    assert change["A"] == ["a1"] and "a2" in change["B"] and change["C"] == ["b1"]
    ends = routes.ends_with(change)
    assert ends is not None and max(ends.values()) < before[0]
    assert chained(_chain_routes(), ["B", "C"], 10_000, unload_key) == change  # the same every time


def test_the_chain_search_stops_at_its_budget_of_stops() -> None:
    routes = _chain_routes()
    assert chained(routes, ["B", "C"], routes.walked, unload_key) is None  # nothing left to walk
