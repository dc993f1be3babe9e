"""The carry term of the resource-aware bound (hp/carry_bound.py): a box carried and put
down, then things put into it at its new place."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from emboteam.hp.carry_bound import carries
from emboteam.hp.optimal import reference
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.validate import simulate
from emboteam.pddl.problem import planning_state
from emboteam.world.actions import Action, Skill

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))  # benchmarks/ is no package
from plan_dump import sweep_input


def _step(k: int, robot: str, skill: Skill, target: str, receptacle: str | None = None) -> PlanStep:
    return PlanStep(id=f"{robot}.{k}", robot=robot, action=Action(skill=skill, target=target, receptacle=receptacle),
                    subtask=f"t{k}")


def test_a_carry_and_the_work_into_the_box_after_its_put_down_until_its_next_pickup() -> None:
    steps = (
        _step(1, "r2", Skill.PutObject, "Pen", "Box"),  # before the carry: not after it
        _step(2, "r1", Skill.GoToObject, "Box"),
        _step(3, "r1", Skill.PickupObject, "Box"),
        _step(4, "r1", Skill.GoToObject, "Table"),
        _step(5, "r1", Skill.PutObject, "Box", "Table"),
        _step(6, "r2", Skill.PutObject, "Book", "Box"),
        _step(7, "r2", Skill.GoToObject, "Box"),  # a drive to the box is no work at it
        _step(8, "r1", Skill.CloseObject, "Box"),
        _step(9, "r2", Skill.PickupObject, "Box"),  # the next carry: what follows is not at the table
        _step(10, "r1", Skill.PutObject, "Cup", "Box"),
    )
    found = carries(MergedPlan(robots=("r1", "r2"), steps=steps))
    assert len(found) == 1
    c = found[0]
    assert c.obj == "Box" and c.drive == 1 and c.steps == [2, 3, 4]
    assert [steps[k].id for k in c.after] == ["r2.6", "r1.8"]


def test_a_put_down_with_nothing_done_at_the_box_after_it_is_no_carry() -> None:
    steps = (_step(1, "r1", Skill.PickupObject, "Box"), _step(2, "r1", Skill.PutObject, "Box", "Table"),
             _step(3, "r2", Skill.PutObject, "Pen", "Shelf"))
    assert carries(MergedPlan(robots=("r1", "r2"), steps=steps)) == []


def test_the_box_cell_bound_is_its_optimum_through_the_carry_term() -> None:
    """FloorPlan201, 4 robots, 8 goals, goal seed 1: Box_1 is carried to a side table, then
    the statue, the pencil and the book go into it. The other terms say 15.5 (the carrier's
    job); the box is down at 15.0 at the earliest (the nearest able robot's drive to it, the
    carry), then three puts of 1 s at its spot: 18.0, the proven optimum (docs/planning.md,
    "Operations on a carried box"). Fails without the carry term."""
    _, spec, state = sweep_input("FloorPlan201", 4, 8, 1)
    plan = HybridPlanner(PlannerConfig()).plan(spec, state)
    timing = simulate(plan, planning_state(state), spec.goal())
    b = timing.resources
    others = max(b.work, b.subtask, b.spot, b.spot_window, b.object, b.object_window)
    assert others == pytest.approx(15.5)
    assert b.carry_name == "Box_1" and b.carry == pytest.approx(18.0)
    assert b.value == pytest.approx(18.0) and plan.resource_bound == pytest.approx(18.0)
    ref = reference(plan, spec, planning_state(state), limit=10.0)
    assert ref is not None and ref.optimal and b.value <= ref.makespan + 1e-6


@pytest.mark.parametrize("cell", [("FloorPlan201", 8, 24, 1), ("FloorPlan201", 8, 8, 1), ("FloorPlan201", 8, 16, 1)],
                         ids=lambda c: f"{c[0]} {c[1]}x{c[2]} seed {c[3]}")
def test_the_carry_term_is_never_above_the_proven_optimum(cell: tuple[str, int, int, int]) -> None:
    """Cells where the term sets the bound (19.5, 18.0 and 18.0 s; the other terms 15.0)."""
    _, spec, state = sweep_input(*cell)
    plan = HybridPlanner(PlannerConfig()).plan(spec, state)
    b = simulate(plan, planning_state(state), spec.goal()).resources
    assert b.carry > max(b.work, b.subtask, b.spot_window, b.object_window) and b.value == b.carry
    ref = reference(plan, spec, planning_state(state), limit=10.0)
    assert ref is not None and ref.optimal
    assert 0 < plan.resource_bound == b.value <= ref.makespan + 1e-6
