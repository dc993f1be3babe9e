"""MACE-THOR through the real hybrid planner (an integration test: Fast Downward runs).

Every task must plan with its full team, and the merged plan, executed in the simulator
step by step in its topological order, must reach the goal. Every temporal task must
*fail* to plan with each single member of its team, with a typed planning error: the
cross-robot dependency is real, not an artefact of the capability analysis
(tests/test_bench_suite_solvability.py proves the same claims by construction).
"""

from __future__ import annotations

import pytest

planner = pytest.importorskip("emboteam.hp.planner")

from emboteam.bench.mace_thor import load_mace_thor  # noqa: E402
from emboteam.pddl.errors import PlanningError  # noqa: E402
from emboteam.sim.setup import apply_changes  # noqa: E402
from emboteam.sim.simulator import Simulator  # noqa: E402
from emboteam.task import BenchTask  # noqa: E402
from emboteam.world.checker import check_goal  # noqa: E402
from emboteam.world.scene import load_scene  # noqa: E402
from emboteam.world.state import WorldState  # noqa: E402

TASKS = load_mace_thor()
TEMPORAL = [t for t in TASKS if t.category == "temporal"]


@pytest.mark.parametrize("task", TASKS, ids=lambda t: t.id)
def test_full_team_plans_and_the_plan_reaches_the_goal(task: BenchTask) -> None:
    state = task.initial_state()
    plan = planner.HybridPlanner().plan_goal(task.goal, state)
    assert plan.steps, f"{task.id}: empty plan"
    sim = Simulator(load_scene(task.floor_plan), task.team(), state=state)
    for step in plan.steps:  # a topological order of the partial order
        outcome = sim.execute(step.robot, step.action)
        assert outcome.success, f"{task.id}: {step} failed: {outcome.reason} {outcome.message}"
    report = check_goal(task.goal, sim.state)
    assert report.success, [str(r) for r in report.results]


@pytest.mark.parametrize("task", TEMPORAL, ids=lambda t: t.id)
def test_no_single_member_can_plan_a_temporal_task(task: BenchTask) -> None:
    scene = load_scene(task.floor_plan)
    for robot in task.team():
        alone = WorldState.from_scene(scene, (robot,))
        apply_changes(alone, task.setup)
        with pytest.raises(PlanningError):
            planner.HybridPlanner().plan_goal(task.goal, alone)
