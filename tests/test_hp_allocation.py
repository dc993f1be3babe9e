"""Roles, team checks and allocation (no planner calls)."""

from __future__ import annotations

import pytest

from emboteam.hp.allocation import allocate
from emboteam.hp.decompose import decompose_goal, group_conditions
from emboteam.hp.requirements import check_team, covers, need_of
from emboteam.pddl.errors import ImpossibleGoalError, MissingSkillError
from emboteam.pfg.taskspec import Subtask
from emboteam.world.goals import Condition, Goal
from emboteam.world.robots import parse_team, robot_profile
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

C = Condition.parse


def fresh(team: str, fp: str = "FloorPlan1") -> WorldState:
    return WorldState.from_scene(load_scene(fp), parse_team(team))


def test_fridge_needs_a_carrier_and_an_opener() -> None:
    s = fresh("1")
    need = need_of(C("inside(Apple, Fridge)"), s, ["robot1"])
    (roles,) = need.alternatives
    names = {r.name for r in roles}
    assert "carry Apple_1" in names and "open Fridge_1" in names
    opener, carrier, both = robot_profile(23), robot_profile(25), robot_profile(1)
    assert not covers([opener], need) and not covers([carrier], need)
    assert covers([opener, carrier], need) and covers([both], need)


def test_satisfied_conditions_need_nobody() -> None:
    s = fresh("1")
    need = need_of(C("closed(Fridge)"), s, ["robot1"])
    assert need.satisfied and covers([], need)


def test_team_checks_name_the_missing_skill_or_the_weight() -> None:
    s = fresh("24,23")
    needs = [need_of(C("sliced(Apple)"), s, list(s.robots))]
    with pytest.raises(MissingSkillError, match="SliceObject"):
        check_team(needs, [robot_profile(24), robot_profile(23)])
    heavy = fresh("10")  # robot10 lifts 0.02 kg
    with pytest.raises(ImpossibleGoalError, match="weighs"):
        check_team([need_of(C("inside(Apple, Fridge)"), heavy, ["robot10"])], [robot_profile(10)])


def test_allocation_balances_identical_robots() -> None:
    s = fresh("1,2")
    subtasks = [Subtask(id=f"s{i}", description=g, goal=(C(g),))
                for i, g in enumerate(["inside(Apple, Fridge)", "inside(Tomato, Fridge)",
                                       "sliced(Bread)", "sliced(Lettuce)"])]
    needs = {t.id: [need_of(c, s, ["robot1", "robot2"]) for c in t.goal] for t in subtasks}
    load: dict[str, float] = {}
    out = allocate(subtasks, needs, s, ["robot1", "robot2"], load)
    per_robot = {r: sum(1 for a in out if a.robots == (r,)) for r in ("robot1", "robot2")}
    assert per_robot == {"robot1": 2, "robot2": 2}
    assert abs(load["robot1"] - load["robot2"]) < max(load.values())


def test_allocation_keeps_a_capable_robot_and_builds_teams() -> None:
    s = fresh("23,25,1")
    fixed = Subtask(id="a", description="x", robot="robot25", goal=(C("inside(Apple, CounterTop_1)"),))
    shared = Subtask(id="b", description="y", goal=(C("inside(Tomato, Fridge)"),))
    needs = {t.id: [need_of(c, s, list(s.robots)) for c in t.goal] for t in (fixed, shared)}
    out = {a.subtask: a for a in allocate([fixed, shared], needs, s, ["robot23", "robot25"], {})}
    assert out["a"].robots == ("robot25",) and out["a"].note == "as specified"
    assert set(out["b"].robots) == {"robot23", "robot25"}


def test_related_conditions_stay_together() -> None:
    s = fresh("1")
    goal = Goal.parse("sliced(Apple) & inside(Apple, Fridge) & switched_off(LightSwitch) & cold(Tomato)")
    groups = group_conditions(goal.conditions, s, ["robot1"])
    assert [len(g) for g in groups] == [2, 1, 1]
    spec = decompose_goal(goal, s)
    assert [t.id for t in spec.subtasks] == ["g1", "g2", "g3"] and spec.goal() == goal
