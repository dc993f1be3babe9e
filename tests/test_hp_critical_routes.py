"""The route stage on large plans (hp/critical_routes.py, hp/stages/route.py, issue 28):
only the jobs of the robots that end last move, within a budget counted in stops walked;
a plan of more than 160 steps, whose long clusters one robot did while others stood by,
comes out shorter, runs in the simulator and is the same plan every time."""

from __future__ import annotations

import pytest

from emboteam.hp import planner as planner_module
from emboteam.hp.critical_routes import improve_late
from emboteam.hp.goalgen import sweep_cell
from emboteam.hp.plan import MergedPlan
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.routes import Node, Routes, Stop, Walker
from emboteam.hp.stages import route as route_stage
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.validate import simulate


def _routes() -> Routes:
    """A holds four jobs, two by B's start and one it must do before another (no floor
    plan: drives are Manhattan at 1 m/s); C, far away, is idle."""
    walker = Walker("", {"A": 1.0, "B": 1.0, "C": 1.0}, {"A": (0.0, 0.0), "B": (20.0, 0.0), "C": (60.0, 0.0)})
    nodes = {n: Node(n, (Stop(f"{n}.1", (x, 0.0), 1.0),), ("A", "B", "C"))
             for n, x in (("a2", 2.0), ("a4", 4.0), ("b18", 18.0), ("b21", 21.0))}
    waits = {"b21.1": frozenset({"a4.1"})}  # b21 needs a4 done first
    return Routes(walker, nodes, waits, {"A": ["a2", "a4", "b18", "b21"], "B": [], "C": []})


def test_the_late_robots_jobs_go_to_the_robot_by_them_and_waits_are_kept() -> None:
    routes = _routes()
    before = routes.cost()
    improve_late(routes, budget=10_000)
    assert routes.cost()[0] < before[0]
    assert set(routes.order["B"]) == {"b18", "b21"} and routes.order["A"] == ["a2", "a4"]
    assert routes.order["C"] == []  # far away: nothing to gain there
    again = _routes()
    improve_late(again, budget=10_000)
    assert again.order == routes.order and again.walked == routes.walked  # a count, not a clock


def test_the_budget_counts_stops_walked() -> None:
    routes = _routes()
    improve_late(routes, budget=1)
    assert routes.order["A"] == ["a2", "a4", "b18", "b21"]  # walking the routes once used it up
    cheap = _routes()
    improve_late(cheap, budget=30)
    full = _routes()
    improve_late(full, budget=10_000)
    assert cheap.walked < full.walked and cheap.cost()[0] >= full.cost()[0]


def _watched(monkeypatch: pytest.MonkeyPatch) -> tuple[HybridPlanner, list[tuple[Draft, Draft]]]:
    """The default planner with its own route stage recorded (what it got and gave), in
    its place in the pipeline: watching changes nothing, so its plan is the default
    planner's (a stage inserted elsewhere would see, and make, other plans)."""
    seen: list[tuple[Draft, Draft]] = []

    def route(ctx: Context, draft: Draft) -> Draft:
        out = route_stage.reroute(ctx, draft)
        seen.append((draft, out))
        return out

    monkeypatch.setattr(planner_module, "reroute", route)  # improvements() reads it
    return HybridPlanner(PlannerConfig()), seen


def _record(plan: MergedPlan) -> list[tuple[str, str, str, tuple[str, ...]]]:
    return [(s.id, s.robot, str(s.action), tuple(s.after)) for s in plan.steps]


def test_a_plan_of_more_than_160_steps_comes_out_shorter_runs_and_is_the_same_every_time(
        monkeypatch: pytest.MonkeyPatch) -> None:
    spec, state = sweep_cell("FloorPlan1", 32, 96, 0)
    planner, seen = _watched(monkeypatch)
    plan = planner.plan(spec, state)
    [(draft, out)] = seen
    assert len(draft.plan.steps) > route_stage.ROUTE_STEPS
    assert out.plan.makespan < draft.plan.makespan  # 48.75 -> 42.75 s
    assert simulate(out.plan, state, spec.goal()).ok
    assert simulate(plan, state, spec.goal()).ok
    assert plan.makespan <= out.plan.makespan  # the later stages keep only shorter plans
    assert any("late robots" in n for n in plan.notes)
    monkeypatch.undo()
    again = HybridPlanner(PlannerConfig()).plan(spec, state)
    assert _record(again) == _record(plan) and again.makespan == plan.makespan
