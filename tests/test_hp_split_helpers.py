"""Who helps with a long cluster (hp/stages/split.py ``near_helpers``): each part goes to
the able robot that could be at its first thing earliest (its end in the plan, then the
drive), not to the robot that merely ends first, which may stand across the room."""

from __future__ import annotations

from emboteam.hp.goalgen import sweep_cell
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.requirements import need_of
from emboteam.hp.stages.context import Context, Draft, Record
from emboteam.hp.stages.split import near_helpers
from emboteam.hp.validate import simulate
from emboteam.sim.durations import navigation_seconds
from emboteam.world.actions import Action, Skill
from emboteam.world.state import WorldState


def _context(state: WorldState, subtasks: dict[str, str]) -> Context:
    from emboteam.pfg.taskspec import Subtask, TaskSpec
    from emboteam.world.goals import Condition

    team = sorted(state.robots)
    spec = TaskSpec(instruction="put things in the box", subtasks=[Subtask(id=k, description=g, goal=(Condition.parse(g),)) for k, g in subtasks.items()])
    needs = {t.id: [need_of(c, state, team) for c in t.goal] for t in spec.subtasks}
    return Context(PlannerConfig(), None, spec, state, team, needs)  # type: ignore[arg-type]


def _drive(state: WorldState, robot: str, oid: str) -> float:
    r, o = state.robots[robot], state.objects[oid]
    return navigation_seconds(r.position, (o.position[0], o.position[2]), r.profile.speed, state.floor_plan)


def _busy(robot: str, seconds: float) -> PlanStep:
    return PlanStep(id=f"{robot}.1", robot=robot, action=Action(skill=Skill.BreakObject, target="Vase_1"),
                    subtask="other", est_start=0.0, est_end=seconds)


def test_a_part_goes_to_the_robot_that_gets_to_its_thing_first() -> None:
    _, state = sweep_cell("FloorPlan201", 8, 8, 1)
    ctx = _context(state, {"p": "inside(Pencil_1, Box_1)", "s": "inside(Statue_1, Box_1)"})
    able = sorted(state.robots)
    nearest = sorted(able, key=lambda r: (_drive(state, r, "Pencil_1"), r))
    empty = Draft(MergedPlan(robots=tuple(able), steps=()), Record())
    assert near_helpers(ctx, empty, able, [("p",)]) == [nearest[0]]
    # the nearest robot busy for a minute: the next nearest, although it ends later than
    # robots standing far away that end at once
    busy = Draft(MergedPlan(robots=tuple(able), steps=(_busy(nearest[0], 60.0),)), Record())
    assert near_helpers(ctx, busy, able, [("p",)]) == [nearest[1]]
    # one robot per part, in order
    two = near_helpers(ctx, empty, able, [("p",), ("s",)])
    assert len(set(two)) == 2 and two[0] == nearest[0]


def test_the_box_on_thirty_two_robots_is_helped_by_robots_near_its_things() -> None:
    # FloorPlan201, 32 robots x 32 goals, seed 1: the helpers that ended first stood
    # across the room (one drove 9.75 s to its first thing): 15.75 s; nearer ones: 14.0 s
    spec, state = sweep_cell("FloorPlan201", 32, 32, 1)
    plan = HybridPlanner(PlannerConfig()).plan(spec, state)
    assert any(": parted among " in n for n in plan.notes)
    assert plan.makespan <= 14.0
    timing = simulate(plan, state, spec.goal())
    assert timing.ok, timing.failure
