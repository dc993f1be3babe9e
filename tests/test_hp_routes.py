"""Routes over a plan's jobs (hp/routes.py) and the route stage (hp/stages/route.py):
the search never prices routes longer than it started from, keeps what a job waits for,
gives the same routes every time; the stage never makes a plan longer, and the plans it
makes run in the simulator."""

from __future__ import annotations

from emboteam.hp.dependencies import Footprint
from emboteam.hp.goalgen import sweep_cell
from emboteam.hp.plan import MergedPlan
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.routes import Node, Routes, Stop, Walker, improve, timetable
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.route import conflicts, reroute
from emboteam.hp.validate import simulate
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.state import WorldState


def _node(name: str, x: float, robots: tuple[str, ...] = ("A", "B")) -> Node:
    """A job at (x, 0): one second of work there."""
    return Node(name, (Stop(f"{name}.1", (x, 0.0), 1.0),), robots)


def _routes(order: dict[str, list[str]], waits: dict[str, frozenset[str]] | None = None) -> Routes:
    # no floor plan: drives are Manhattan at 1 m/s
    walker = Walker("", {"A": 1.0, "B": 1.0}, {"A": (0.0, 0.0), "B": (20.0, 0.0)})
    nodes = {n.id: n for n in (_node("n2", 2), _node("n4", 4), _node("n16", 16), _node("n18", 18))}
    return Routes(walker, nodes, waits or {}, order)


def test_the_search_gives_each_robot_the_jobs_near_it_and_never_prices_longer() -> None:
    routes = _routes({"A": ["n18", "n2", "n16", "n4"], "B": []})
    before = routes.cost()
    improve(routes)
    assert routes.cost()[0] < before[0] and routes.cost()[1] <= before[1]
    assert sorted(routes.order["A"]) == ["n2", "n4"] and sorted(routes.order["B"]) == ["n16", "n18"]
    assert routes.order["A"] == ["n2", "n4"] and routes.order["B"] == ["n18", "n16"]
    again = _routes({"A": ["n18", "n2", "n16", "n4"], "B": []})
    improve(again)
    assert again.order == routes.order and again.walked == routes.walked  # a count, not a clock


def test_a_job_that_waits_for_another_starts_after_it_ends_on_any_robot() -> None:
    # n2's step (near A) needs n18's step (near B) done first
    routes = _routes({"A": ["n18", "n2"], "B": ["n4", "n16"]}, {"n2.1": frozenset({"n18.1"})})
    improve(routes)
    found = timetable(routes.walker, routes.nodes, routes.order, routes.waits)
    assert found is not None
    times, ends, _ = found
    assert times["n2.1"] >= times["n18.1"] + 1.0
    assert max(ends.values()) == routes.cost()[0]
    # n2 waits for n16, n16 for n4, which A does after n2: no timetable
    waits = {"n2.1": frozenset({"n16.1"}), "n16.1": frozenset({"n4.1"})}
    assert timetable(routes.walker, routes.nodes, {"A": ["n2", "n4"], "B": ["n16"]}, waits) is None
    assert timetable(routes.walker, routes.nodes, {"A": ["n4", "n2"], "B": ["n16"]}, waits) is not None


def test_one_robot_at_a_time_at_a_spot_the_first_to_arrive_first() -> None:
    walker = Walker("", {"A": 1.0, "B": 1.0}, {"A": (0.0, 0.0), "B": (5.0, 0.0)})
    nodes = {"a": Node("a", (Stop("a.1", (3.0, 0.0), 4.0, spot="Sink_1"),), ("A",)),
             "b": Node("b", (Stop("b.1", (3.0, 0.0), 4.0, spot="Sink_1"),), ("B",))}
    found = timetable(walker, nodes, {"A": ["a"], "B": ["b"]}, {})
    assert found is not None
    times, ends, _ = found
    assert times["b.1"] == 2.0 and times["a.1"] == 6.0  # B arrives at 2 s, A at 3 s and waits
    assert ends == {"A": 10.0, "B": 6.0}


def test_jobs_that_switch_one_thing_keep_their_order_and_two_puts_into_one_box_commute() -> None:
    on = Footprint(reads=frozenset({"on:Microwave_1"}), writes=frozenset({"on:Microwave_1"}))
    put = Footprint(reads=frozenset(), writes=frozenset({"loc:Apple_1"}), updates=frozenset({"contents:Box_1"}))
    put2 = Footprint(reads=frozenset(), writes=frozenset({"loc:Pen_1"}), updates=frozenset({"contents:Box_1"}))
    look = Footprint(reads=frozenset({"contents:Box_1"}), writes=frozenset())
    mine = Footprint(reads=frozenset({"pose:r1", "hand:r1"}), writes=frozenset({"pose:r1"}))
    got = conflicts([("a", on), ("b", put), ("c", on), ("d", put2), ("e", look), ("f", mine), ("g", mine)])
    assert ("a", "c") in got
    assert ("b", "d") not in got and ("d", "b") not in got  # set updates commute
    assert {("b", "e"), ("d", "e")} <= got  # reading the whole set waits for both
    assert ("f", "g") not in got  # a robot's pose is its own


def _watched(config: PlannerConfig) -> tuple[HybridPlanner, list[tuple[float, float, MergedPlan]]]:
    """A planner whose route stage records (makespan in, makespan out, plan out)."""
    seen: list[tuple[float, float, MergedPlan]] = []

    def route(ctx: Context, draft: Draft) -> Draft:
        out = reroute(ctx, draft)
        seen.append((draft.plan.makespan, out.plan.makespan, out.plan))
        return out

    planner = HybridPlanner(config)
    stages = list(planner.stages)
    stages.insert(len(stages) - 1, route)  # before the CP-SAT stage, as improvements() puts it
    planner.stages = tuple(stages)
    return planner, seen


def _cells() -> list[tuple[TaskSpec, WorldState]]:
    return [sweep_cell("FloorPlan201", 32, 8, 1), sweep_cell("FloorPlan201", 2, 8, 4),
            sweep_cell("FloorPlan1", 2, 8, 0)]


def test_the_route_stage_never_makes_a_plan_longer_and_its_plans_run_in_the_simulator() -> None:
    shorter = 0
    for spec, state in _cells():
        planner, seen = _watched(PlannerConfig(route=False, split_critical=False))  # one pass of the stages
        plan = planner.plan(spec, state)
        [(before, after, out)] = seen
        assert after <= before
        shorter += after < before
        assert simulate(out, state, spec.goal()).ok
        assert simulate(plan, state, spec.goal()).ok
    assert shorter >= 1  # FloorPlan201 32x8, seed 1: 20.5 -> 12.75 s


def test_the_default_planner_reroutes_a_cell_where_an_idle_robot_stands_by_the_work() -> None:
    spec, state = sweep_cell("FloorPlan201", 32, 8, 1)
    # the idle stage off too, as the other stage-isolating tests do: its ejection chains
    # alone reach 10.75 s here on the plan the route stage did not touch
    plain = HybridPlanner(PlannerConfig(route=False, idle=False)).plan(spec, state)
    plan = HybridPlanner(PlannerConfig()).plan(spec, state)
    assert any("rerouted" in n for n in plan.notes)
    assert plan.makespan < plain.makespan
    again = HybridPlanner(PlannerConfig()).plan(spec, state)
    assert [(s.id, s.robot, str(s.action), s.after, s.est_start, s.est_end) for s in again.steps] == [
        (s.id, s.robot, str(s.action), s.after, s.est_start, s.est_end) for s in plan.steps]
    assert simulate(plan, state, spec.goal()).ok
