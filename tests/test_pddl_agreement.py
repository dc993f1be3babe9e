"""The planner's domain agrees with the simulator.

(a) every plan Fast Downward returns for a (scene, team, goal) runs in the ``Simulator``
    without a failure and reaches the goal (``check_goal``);
(b) single robot steps in sequence: each step's ``pre`` literals hold (``vocabulary.evaluate``)
    in the simulator state just before it, and its observable ``post`` literals just after.

Cases: hand-written ones covering each rule the domain mirrors, random goals on the eight
benchmark floor plans with random teams, and (once ``emboteam.bench.suites`` exists) the
MACE-THOR suite. To add a case, append a :class:`Case` to ``CASES``.
"""

from __future__ import annotations

import importlib
import random
from dataclasses import dataclass

import pytest

from emboteam.hp.goalgen import random_conditions
from emboteam.pddl import vocabulary
from emboteam.pddl.domain import domain_pddl, step_literals
from emboteam.pddl.problem import build_problem
from emboteam.pddl.runner import FastDownward, PlanCache
from emboteam.sim import Simulator
from emboteam.sim.setup import StateChange, apply_changes
from emboteam.world.checker import check_goal
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

BENCHMARK_SCENES = ("FloorPlan1", "FloorPlan6", "FloorPlan15", "FloorPlan21", "FloorPlan201",
                    "FloorPlan209", "FloorPlan303", "FloorPlan414")


@dataclass(frozen=True)
class Case:
    scene: str
    team: str
    goal: str
    setup: tuple[StateChange, ...] = ()
    why: str = ""

    @property
    def id(self) -> str:
        return f"{self.scene}[{self.team}]:{self.goal}"


CASES: list[Case] = [
    Case("FloorPlan1", "1", "inside(Apple, Fridge)", why="must-open receptacle, cooling"),
    Case("FloorPlan1", "1", "sliced(Bread) & cooked(Bread)", why="knife, pieces declared ahead, toaster whitelist"),
    Case("FloorPlan1", "1", "hot(Potato) & closed(Microwave)", why="microwave door/power interlock"),
    Case("FloorPlan6", "2", "cooked(Potato) & inside(Potato, Plate)", why="cooking persists when moved"),
    Case("FloorPlan15", "2", "filled(Mug, coffee)", why="coffee machine whitelist and brewing"),
    Case("FloorPlan402", "25", "inside(ToiletPaper, ToiletPaperHanger)",
         why="a closed toilet lid hides nothing: no OpenObject needed (robot25 cannot open)"),
    Case("FloorPlan21", "3", "filled(Cup, water) & switched_off(Faucet)", why="running water fills"),
    Case("FloorPlan1", "1", "clean(Mug)", (StateChange(object="Mug_1", is_dirty=True),),
         why="running water cleans (no robot has CleanObject)"),
    Case("FloorPlan1", "4", "inside(Tomato, GarbageCan)", why="throw or put into the garbage can"),
    Case("FloorPlan1", "1", "hot(Egg) & sliced(Apple) & cold(Apple)", why="slices inherit and settle"),
    Case("FloorPlan6", "27,2", "sliced(Egg)", why="cracking an egg by breaking it"),
    Case("FloorPlan201", "1", "inside(2 of Book|Pen|Pencil|CreditCard|KeyChain, Sofa)", why="N of types"),
    Case("FloorPlan414", "1", "inside(ToiletPaper, ToiletPaperHanger) & open(Cabinet_3)", why="holder whitelist"),
    Case("FloorPlan303", "1", "switched_on(DeskLamp) & inside(CD, Box) & closed(Box)", why="pickupable container"),
    Case("FloorPlan209", "23,25", "inside(RemoteControl, Box)", why="one robot opens, another carries"),
    Case("FloorPlan1", "5,6", "inside(Pan, StoveBurner) & switched_on(StoveKnob)", why="mass limits, knob"),
    Case("FloorPlan1", "2", "held(Apple) & sliced(Lettuce)", why="held goal: no release"),
    Case("FloorPlan201", "1", "broken(Vase) & switched_off(Television)", why="breaking"),
    Case("FloorPlan1", "1", "inside(Potato, Sink)", why="Sink means Sink or SinkBasin"),
]


def _generated(per_scene: int = 1, seed: int = 7) -> list[Case]:
    """Random consistent goals with random teams that include a capable robot."""
    rng = random.Random(seed)
    out: list[Case] = []
    for scene in BENCHMARK_SCENES:
        for _ in range(per_scene):
            team = [rng.choice([1, 2, 3, 4]), *rng.sample(range(5, 29), rng.randint(0, 2))]
            state = WorldState.from_scene(load_scene(scene), parse_team(team))
            conds = random_conditions(state, rng.randint(3, 6), rng)
            out.append(Case(scene, ",".join(map(str, team)), " & ".join(map(str, conds)), why="random"))
    return out


def _suite() -> list[Case]:
    """MACE-THOR tasks, when the benchmark suite module exists."""
    try:
        suites = importlib.import_module("emboteam.bench.suites")
    except ImportError:
        return []
    return [Case(t.floor_plan, ",".join(t.robots), str(t.goal), tuple(t.setup), why=t.key)
            for t in suites.load_suite("mace-thor").tasks]


ALL = CASES + _generated() + _suite()


@pytest.fixture(scope="module")
def planner() -> FastDownward:
    return FastDownward(time_limit=60, cache=PlanCache())


@pytest.mark.parametrize("case", ALL, ids=[c.id for c in ALL])
def test_fast_downward_plans_run_in_the_simulator(case: Case, planner: FastDownward) -> None:
    scene = load_scene(case.scene)
    state = WorldState.from_scene(scene, parse_team(case.team))
    apply_changes(state, case.setup)
    goal = Goal.parse(case.goal)
    problem = build_problem(state, goal.conditions, list(state.robots), name="agreement")
    result = planner.solve(domain_pddl(), problem.text)
    assert result.solved, f"no plan for {case.id} ({case.why}): {result.message}"
    sim = Simulator(scene, [], state=state)
    for robot, action in problem.decode(result.plan):
        pre, post = step_literals(robot, action, sim.state)
        unmet = [str(lit) for lit in pre if not vocabulary.evaluate(lit, sim.state)]
        assert not unmet, f"{robot} {action}: preconditions {unmet} do not hold in the simulator"
        outcome = sim.execute(robot, action)
        assert outcome.success, f"{case.id}: {outcome}"
        wrong = [str(lit) for lit in post if vocabulary.observable(lit) and not vocabulary.evaluate(lit, sim.state)]
        assert not wrong, f"{robot} {action}: effects {wrong} do not hold after it"
    report = check_goal(goal, sim.state)
    assert report.success, f"{case.id}: {[str(r) for r in report.results]}"
