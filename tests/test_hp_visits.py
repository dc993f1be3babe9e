"""Visit merging: a step the robot drove to do, done on its other visit to the object."""

from __future__ import annotations

from emboteam.hp import HybridPlanner, PlannerConfig
from emboteam.hp.visits import _run, merge_visits
from emboteam.pddl.problem import planning_state
from emboteam.world.actions import Action, Skill
from emboteam.world.checker import check_condition
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


def _a(skill: str, target: str, receptacle: str | None = None) -> tuple[str, Action]:
    return "robot1", Action(skill=Skill[skill], target=target, receptacle=receptacle)


STATE = planning_state(WorldState.from_scene(load_scene("FloorPlan1"), parse_team("1")))
#: lama-first's way to cool the pan with the fridge closed: drive there to open it first
COOL_PAN = [_a("GoToObject", "Fridge_1"), _a("OpenObject", "Fridge_1"), _a("GoToObject", "Pan_1"),
            _a("PickupObject", "Pan_1"), _a("GoToObject", "Fridge_1"), _a("PutObject", "Pan_1", "Fridge_1")]


def test_the_fridge_is_opened_when_the_robot_brings_the_pan() -> None:
    goal = Goal.parse("cold(Pan_1)")
    new = merge_visits(STATE, COOL_PAN, goal.conditions)
    assert [str(a) for _, a in new] == ["PickupObject(Pan_1)", "GoToObject(Fridge_1)", "OpenObject(Fridge_1)",
                                        "PutObject(Pan_1, Fridge_1)"]
    before, after = _run(STATE, COOL_PAN), _run(STATE, new)
    assert before is not None and after is not None
    # two drives saved: 8.5 s on the navigation grid (about 12 s in the Manhattan model)
    assert after[1]["robot1"] < before[1]["robot1"] - 6
    assert all(check_condition(c, after[0]).holds for c in goal.conditions)


def test_nothing_moves_where_no_move_saves_time_or_the_plan_does_not_run() -> None:
    assert merge_visits(STATE, COOL_PAN[:2], []) == COOL_PAN[:2]  # one visit only
    broken = [_a("PutObject", "Pan_1", "Fridge_1"), *COOL_PAN]  # nothing in hand to put
    assert merge_visits(STATE, broken, []) == broken


def test_a_step_needed_where_it_stands_stays_there() -> None:
    # the fridge is opened to take the egg out: opening it on the later visit (where it is
    # closed again) would leave the egg out of reach, and the replay rejects it
    plan = [_a("GoToObject", "Fridge_1"), _a("OpenObject", "Fridge_1"), _a("PickupObject", "Egg_1"),
            _a("GoToObject", "CounterTop_1"), _a("PutObject", "Egg_1", "CounterTop_1"),
            _a("GoToObject", "Fridge_1"), _a("CloseObject", "Fridge_1")]
    assert _run(STATE, plan) is not None
    assert merge_visits(STATE, plan, Goal.parse("inside(Egg_1, CounterTop_1) & closed(Fridge_1)").conditions) == plan


def test_the_planner_merges_visits_by_default_and_can_be_told_not_to() -> None:
    # FloorPlan1, one robot: a cold pan, a hot egg in it (the sweep's egg cluster)
    goal = Goal.parse("cold(Pan_1) & hot(Egg_1) & inside(Egg_1, Pan_1)")
    on = HybridPlanner(PlannerConfig()).plan_goal(goal, STATE)
    off = HybridPlanner(PlannerConfig(merge_visits=False)).plan_goal(goal, STATE)
    assert on.makespan < off.makespan


def test_a_unit_that_waits_for_another_subtask_keeps_its_plan() -> None:
    # the README's instruction: whoever puts the slice in the fridge opens the fridge while
    # the lettuce is cut; doing it on arrival would save a drive and end 0.5 s later
    from emboteam.pfg.taskspec import Subtask, TaskSpec

    spec = TaskSpec(instruction="slice the lettuce, put it in the fridge and switch off the light", subtasks=(
        Subtask(id="s1", description="slice", goal=Goal.parse("sliced(Lettuce)").conditions),
        Subtask(id="s2", description="fridge", goal=Goal.parse("inside(Lettuce, Fridge)").conditions,
                depends_on=("s1",)),
        Subtask(id="s3", description="light", goal=Goal.parse("off(LightSwitch)").conditions)))
    state = planning_state(WorldState.from_scene(load_scene("FloorPlan1"), parse_team("1,2,3")))
    on = HybridPlanner(PlannerConfig()).plan(spec, state)
    off = HybridPlanner(PlannerConfig(merge_visits=False)).plan(spec, state)
    assert [str(s.action) for s in on.steps] == [str(s.action) for s in off.steps]
    assert on.makespan == off.makespan
