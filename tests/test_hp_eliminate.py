"""Action elimination (hp/eliminate.py): shorter plans that still run, reach the same
goals, leave the same hands and never cost a robot more seconds; and the planner's plans
with it still validate in the simulator."""

from __future__ import annotations

import random

import pytest

from emboteam.hp.eliminate import eliminate, eliminate_steps
from emboteam.hp.goalgen import random_conditions
from emboteam.hp.merge import SeqStep, assemble, ground_sequence, nominal_seconds, order
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.stages.trim import trimmed
from emboteam.hp.validate import simulate
from emboteam.pddl.domain import Universe
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.sim.rules import apply_action
from emboteam.world.actions import Action, Skill
from emboteam.world.checker import check_condition
from emboteam.world.goals import Condition, Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

S = Skill
C = Condition.parse
Plan = list[tuple[str, Action]]


def fresh(team: str = "1,2") -> WorldState:
    return WorldState.from_scene(load_scene("FloorPlan1"), parse_team(team))


def act(robot: str, skill: Skill, target: str, receptacle: str | None = None) -> tuple[str, Action]:
    return robot, Action(skill=skill, target=target, receptacle=receptacle)


def heat_egg(robot: str = "robot1") -> Plan:
    """Take the egg from the fridge, heat it in the microwave and take it out."""
    return [
        act(robot, S.GoToObject, "Fridge_1"), act(robot, S.OpenObject, "Fridge_1"),
        act(robot, S.PickupObject, "Egg_1"), act(robot, S.GoToObject, "Microwave_1"),
        act(robot, S.OpenObject, "Microwave_1"), *microwave_run(robot),
    ]


def microwave_run(robot: str) -> Plan:
    return [
        act(robot, S.PutObject, "Egg_1", "Microwave_1"), act(robot, S.CloseObject, "Microwave_1"),
        act(robot, S.SwitchOn, "Microwave_1"), act(robot, S.SwitchOff, "Microwave_1"),
        act(robot, S.OpenObject, "Microwave_1"), act(robot, S.PickupObject, "Egg_1"),
    ]


def seconds(state: WorldState, plan: Plan) -> dict[str, float]:
    s = state.copy()
    out: dict[str, float] = {}
    for robot, a in plan:
        out[robot] = out.get(robot, 0.0) + nominal_seconds(s, robot, a)
        apply_action(s, robot, a)
    return out


def runs(state: WorldState, plan: Plan) -> WorldState:
    """Replay with every PDDL precondition checked (raises StepFailure otherwise)."""
    return ground_sequence(state, [SeqStep(r, a, "t") for r, a in plan])[1]


def is_subsequence(short: Plan, long: Plan) -> bool:
    it = iter(long)
    return all(any(x == y for y in it) for x in short)


def test_a_second_microwave_run_is_dropped() -> None:
    state = fresh()
    plan = heat_egg() + microwave_run("robot1")
    goal = [C("hot(Egg_1)")]
    out = eliminate(state, plan, goal)
    assert len(out) == len(plan) - 6
    assert is_subsequence(out, plan)
    end = runs(state, out)
    assert check_condition(goal[0], end).holds
    assert end.robots["robot1"].holding == "Egg_1"  # hands as the original leaves them
    assert seconds(state, out)["robot1"] < seconds(state, plan)["robot1"]


def test_a_redundant_drive_is_dropped_and_needed_steps_stay() -> None:
    state = fresh()
    plan = heat_egg()
    # a drive to where the robot stands already, just before it acts there
    plan.insert(5, act("robot1", S.GoToObject, "Microwave_1"))
    out = eliminate(state, plan, [C("hot(Egg_1)")])
    assert out == heat_egg()
    # nothing of the plain plan can go: every step is needed for the hot egg in hand
    assert eliminate(state, heat_egg(), [C("hot(Egg_1)")]) == heat_egg()


def test_goals_reached_by_the_original_are_kept() -> None:
    """Closing the fridge and opening it again at the end is a cycle: it goes, with the
    drive to the fridge, whether or not the fridge must end open."""
    state = fresh()
    plan = [*heat_egg(), act("robot1", S.GoToObject, "Fridge_1"), act("robot1", S.CloseObject, "Fridge_1"),
            act("robot1", S.OpenObject, "Fridge_1")]
    kept = eliminate(state, plan, [C("hot(Egg_1)"), C("open(Fridge_1)")])
    assert check_condition(C("open(Fridge_1)"), runs(state, kept)).holds
    assert len(kept) == len(heat_egg())  # closing and opening again go together
    dropped = eliminate(state, plan, [C("hot(Egg_1)")])
    assert len(dropped) == len(heat_egg())


def test_two_robots_heat_in_one_run() -> None:
    """robot2 switches the microwave on again for nothing once robot1's egg is hot."""
    state = fresh()
    plan = [*heat_egg("robot1"), act("robot2", S.GoToObject, "Microwave_1"),
            act("robot2", S.CloseObject, "Microwave_1"), act("robot2", S.SwitchOn, "Microwave_1"),
            act("robot2", S.SwitchOff, "Microwave_1"), act("robot2", S.OpenObject, "Microwave_1")]
    out = eliminate(state, plan, [C("hot(Egg_1)")])
    assert out == heat_egg("robot1")
    assert check_condition(C("hot(Egg_1)"), runs(state, out)).holds
    before, after = seconds(state, plan), seconds(state, out)
    assert all(after.get(r, 0.0) <= before[r] + 1e-9 for r in before)


def test_the_state_given_and_its_robots_are_left_as_they_were() -> None:
    """The search keeps the states it passes with the robots' records shared among them
    (a step copies its own robot's record before writing it): none of the caller's
    records may move, whichever robot acts."""
    state = fresh()
    robots = dict(state.robots)
    before = state.copy()
    plan = [*heat_egg("robot1"), act("robot2", S.GoToObject, "Microwave_1"),
            act("robot2", S.CloseObject, "Microwave_1"), act("robot2", S.SwitchOn, "Microwave_1"),
            act("robot2", S.SwitchOff, "Microwave_1"), act("robot2", S.OpenObject, "Microwave_1")]
    assert eliminate(state, plan, [C("hot(Egg_1)")]) == heat_egg("robot1")
    assert state == before
    assert all(state.robots[r] is robots[r] and robots[r] == before.robots[r] for r in robots)


def test_a_window_too_short_to_rejoin_keeps_the_plan() -> None:
    state = fresh()
    plan = heat_egg() + microwave_run("robot1")
    assert eliminate(state, plan, [C("hot(Egg_1)")], window=1) == plan
    assert len(eliminate(state, plan, [C("hot(Egg_1)")], window=40)) < len(plan)


def test_a_plan_that_does_not_run_is_returned_as_is() -> None:
    state = fresh()
    plan = heat_egg()[2:]  # picks up the egg from a closed fridge, out of reach
    assert eliminate(state, plan, [C("hot(Egg_1)")]) == plan


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_plans_with_elimination_validate_and_are_shorter(seed: int) -> None:
    """Random goals in FloorPlan1 (as the benchmark's sweep makes them): the planner's
    plan with elimination validates in the simulator, has no more steps than without it,
    and never a longer busiest robot's work by more than noise of who does what."""
    team = parse_team([1, 2, 3, 4])
    state = WorldState.from_scene(load_scene("FloorPlan1"), team)
    conds = random_conditions(state, 12, random.Random(seed))
    spec = TaskSpec(instruction="x", subtasks=tuple(
        Subtask(id=f"c{i}", description=str(c), goal=(c,)) for i, c in enumerate(conds, 1)))
    plans = {e: HybridPlanner(PlannerConfig(eliminate=e, rebalance="off", route=False)).plan(spec, state)
             for e in ("off", "whole")}
    for plan in plans.values():
        timing = simulate(plan, state, Goal(conditions=tuple(conds)))
        assert timing.ok, timing.failure
    assert len(plans["whole"].steps) <= len(plans["off"].steps)


def test_steps_not_reported_moved_start_from_the_same_state() -> None:
    """What the planner reuses without grounding again: every kept step outside the
    reported ones grounds exactly as it did in the original sequence."""
    state = fresh()
    plan = [*heat_egg("robot1"), act("robot2", S.GoToObject, "Microwave_1"),
            act("robot2", S.CloseObject, "Microwave_1"), act("robot2", S.SwitchOn, "Microwave_1"),
            act("robot2", S.SwitchOff, "Microwave_1"), act("robot2", S.OpenObject, "Microwave_1"),
            act("robot1", S.GoToObject, "Fridge_1"), act("robot1", S.GoToObject, "LightSwitch_1"),
            act("robot1", S.SwitchOff, "LightSwitch_1")]
    plan.insert(5, act("robot1", S.GoToObject, "Microwave_1"))
    kept, moved = eliminate_steps(state, plan, [C("hot(Egg_1)"), C("off(LightSwitch_1)")], window=40)
    assert len(kept) < len(plan)
    before = ground_sequence(state, [SeqStep(r, a, "t") for r, a in plan])[0]
    after = ground_sequence(state, [SeqStep(*plan[k], "t") for k in kept])[0]
    same = [(before[k], g) for k, g in zip(kept, after, strict=True) if k not in moved]
    assert same
    assert all(b == g for b, g in same)


def test_the_whole_sequence_loses_a_second_run_and_keeps_the_other_groundings() -> None:
    """The planner's pass over the whole accepted sequence: robot2's run of the microwave
    after robot1's goes; the steps before it keep their grounded objects; the result
    merges into a plan the simulator runs to the goal."""
    state = fresh()
    seq = [*heat_egg("robot1"), act("robot2", S.GoToObject, "Microwave_1"),
           act("robot2", S.CloseObject, "Microwave_1"), act("robot2", S.SwitchOn, "Microwave_1"),
           act("robot2", S.SwitchOff, "Microwave_1"), act("robot2", S.OpenObject, "Microwave_1")]
    accepted, _ = ground_sequence(state, [SeqStep(r, a, "c1", "u1") for r, a in seq])
    spec = TaskSpec(instruction="heat the egg", subtasks=(Subtask(id="c1", description="x", goal=(C("hot(Egg_1)"),)),))
    shorter = trimmed(accepted, spec, state, Universe(state))
    assert shorter is not None and len(shorter) == len(heat_egg("robot1"))
    assert all(g is a for g, a in zip(shorter, accepted, strict=False))
    plan = assemble(shorter, order(shorter, {}), ["robot1", "robot2"], {})
    timing = simulate(plan, state, spec.goal())
    assert timing.ok, timing.failure
