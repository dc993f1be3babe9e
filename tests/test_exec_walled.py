"""A broken robot in the only way to what the goal needs: the replanner and the ceiling say
so with a typed error (before: the planner, whose drive costs ignore robots, found a plan,
the team drove at the wall until the replan budget ran out and the episode ended 'failed'
with no error while the ceiling called it savable; fp201-tv-corner seeds 1 and 2)."""

from __future__ import annotations

import pytest

from emboteam.bench.suites import get_task
from emboteam.exec.ceiling import _ceiling
from emboteam.exec.replan import PlannerReplanner
from emboteam.exec.walled import WalledOffError, check_not_walled_off
from emboteam.mode_table import planner_for
from emboteam.pipeline import RunConfig, run_episode
from emboteam.sim.disturbances import Disturbances
from emboteam.world.navgrid import NavGrid
from emboteam.world.state import WorldState

TASK = "mace-thor/fp201-tv-corner"
#: FloorPlan201: the cell where the one-cell corridor to the corner by the window begins
#: (the task's pillow and remote lie on the floor in that corner), and a cell by the sofa
CORRIDOR, BY_SOFA = (-13, 2), (-14, 18)


def _state(*, broken: bool) -> WorldState:
    state = get_task(TASK).initial_state()
    state.robots["robot25"].position = NavGrid.point(CORRIDOR)
    state.robots["robot25"].down = broken
    state.robots["robot15"].position = NavGrid.point(BY_SOFA)
    return state


def test_a_broken_robot_in_the_only_corridor_walls_the_goal_off() -> None:
    goal = get_task(TASK).goal
    with pytest.raises(WalledOffError, match=r"robot25 broke down.*Pillow_1.*RemoteControl_1"):
        check_not_walled_off(goal, _state(broken=True), ["robot15"])
    check_not_walled_off(goal, _state(broken=False), ["robot15"])  # a working robot makes way


def test_the_other_side_of_the_wall_misses_the_receptacles() -> None:
    state = _state(broken=True)
    state.robots["robot15"].position = NavGrid.point((CORRIDOR[0] + 4, CORRIDOR[1]))  # in the corridor
    with pytest.raises(WalledOffError, match="Sofa_1"):
        check_not_walled_off(get_task(TASK).goal, state, ["robot15"])


def test_the_replanner_and_the_ceiling_refuse_with_a_typed_error() -> None:
    task, planner = get_task(TASK), planner_for("full")
    with pytest.raises(WalledOffError):
        PlannerReplanner(planner)(_state(broken=True), task.goal, ["robot15"])
    savable, why, left = _ceiling(task.goal, _state(broken=True), planner)
    assert savable is False and why.startswith("UnsavableTaskError: WalledOffError") and left == ("robot15",)


@pytest.mark.parametrize("seed", [1, 2])
def test_the_episode_ends_unsavable_at_once_with_a_typed_error(seed: int) -> None:
    cfg = RunConfig(mode="full", frontend="oracle", fault_level=0.2, seed=seed,
                    disturbance=Disturbances.parse(breakdown=["random@0.3"]))
    ep = run_episode(get_task(TASK), cfg)
    d = ep.disturbance
    assert d is not None and d.events and d.events[0].kind == "breakdown"
    assert not ep.success and ep.error and ep.error.startswith("UnsavableTaskError")
    assert d.stop_reason == "unsavable" and d.savable is False
    assert ep.makespan < 2 * d.nominal_makespan  # it stops, rather than driving at the wall
