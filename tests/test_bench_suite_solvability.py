"""MACE-THOR is solvable as designed: every task by its team, no temporal task by any one
member, every condition of a parallel task by one member on its own.

The capability analysis (emboteam.sim.capability) proves the negative claims: a robot
that covers no method of a condition cannot achieve it. The positive claims are proven
by *executing* a witness in the simulator: the analysis' methods, bound to team members,
run step by step (GoToObject before each interaction) until the goal holds.
"""

from __future__ import annotations

from collections.abc import Sequence

import pytest

from emboteam.bench.mace_thor import load_mace_thor
from emboteam.sim.capability import analyse_condition, analyse_goal
from emboteam.sim.simulator import Simulator
from emboteam.task import BenchTask
from emboteam.world.actions import Skill
from emboteam.world.catalogue import load_catalogue
from emboteam.world.checker import check_condition, check_goal
from emboteam.world.goals import Condition, Goal, Predicate
from emboteam.world.robots import RobotProfile, parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
from witness import WitnessFailed, release, run_method

TASKS = load_mace_thor()
TEMPORAL = [t for t in TASKS if t.category == "temporal"]
PARALLEL = [t for t in TASKS if t.category == "parallel"]

#: the witness reaches conditions in this order: enabling state changes first, switching
#: off and closing last (they undo what the others need), holding something at the very end
_PHASE = {
    Predicate.sliced: 0, Predicate.broken: 0, Predicate.open: 0,
    Predicate.switched_on: 2, Predicate.switched_off: 3, Predicate.closed: 3, Predicate.held: 4,
}


def run_witness(task: BenchTask, conditions: Sequence[Condition], actors: Sequence[RobotProfile]) -> Simulator:
    """Reach ``conditions`` one after the other with ``actors`` (a subset of the team)."""
    state = task.initial_state()
    sim = Simulator(load_scene(task.floor_plan), task.team(), state=state)
    for cond in sorted(conditions, key=lambda c: _PHASE.get(c.predicate, 1)):
        for k in range(1, cond.count + 1):  # one more instance at a time
            partial = cond.model_copy(update={"count": k})
            for robot in actors:  # free hands first: what one robot holds, others cannot take
                if sim.state.robots[robot.name].holding is not None and (
                        robot.can(Skill.DropHandObject) or robot.can(Skill.PutObject)):
                    release(sim, robot.name)
            analysis = analyse_condition(partial, sim.state)
            if analysis.holds:
                continue
            method = analysis.team_method(actors)
            if method is None:
                raise WitnessFailed(f"{task.id}: no method for {partial} with "
                                    f"{[a.name for a in actors]} at t={sim.now:.1f}")
            run_method(sim, method, actors)
            if not check_condition(partial, sim.state).holds:
                raise WitnessFailed(f"{task.id}: {method} ran but {partial} does not hold")
    return sim


# ---- the claims ---------------------------------------------------------------------------


@pytest.mark.parametrize("task", TASKS, ids=lambda t: t.id)
def test_team_reaches_the_goal_in_the_simulator(task: BenchTask) -> None:
    team = task.team()
    assert analyse_goal(task.goal, task.initial_state()).team_can(team)
    sim = run_witness(task, task.goal.conditions, team)
    report = check_goal(task.goal, sim.state)
    assert report.success, [str(r) for r in report.results]
    assert sim.state.invariant_violations() == []
    used = {o.robot for o in sim.outcomes}
    if task.category == "temporal":  # the witness needed more than one robot
        assert len(used) >= 2, used


@pytest.mark.parametrize("task", TEMPORAL, ids=lambda t: t.id)
def test_no_single_member_can_do_a_temporal_task(task: BenchTask) -> None:
    analysis = analyse_goal(task.goal, task.initial_state())
    for robot in task.team():
        assert not analysis.robot_can(robot), f"{robot.name} could do {task.id} alone"
        assert analysis.gaps(robot), robot.name
        with pytest.raises(WitnessFailed):
            run_witness(task, task.goal.conditions, [robot])


@pytest.mark.parametrize("task", PARALLEL, ids=lambda t: t.id)
def test_each_condition_of_a_parallel_task_is_one_robots_job(task: BenchTask) -> None:
    """Sub-tasks without dependencies: each condition, on its own, is reached by one
    member acting alone (executed, not just covered)."""
    assert len(task.goal.conditions) >= 2
    team = task.team()
    state = task.initial_state()
    for cond in task.goal.conditions:
        analysis = analyse_condition(cond, state)
        solo = [r for r in team if analysis.solo_method(r) is not None]
        assert solo, f"{cond}: no single member can do it"
        sim = run_witness(task, [cond], [solo[0]])
        assert check_condition(cond, sim.state).holds
        assert {o.robot for o in sim.outcomes} <= {solo[0].name}


@pytest.mark.parametrize("task", TASKS, ids=lambda t: t.id)
def test_goal_does_not_hold_at_the_start(task: BenchTask) -> None:
    """Every task asks for work; conditions true at the start are only "leave it so"
    ones (a tap that must end up off, a drawer that must end up closed)."""
    report = check_goal(task.goal, task.initial_state())
    assert not report.success
    for r in report.results:
        if r.holds:
            assert r.condition.predicate in (Predicate.switched_off, Predicate.closed), str(r.condition)


# ---- the analysis itself ------------------------------------------------------------------


def _state(fp: str, team: str) -> tuple[WorldState, tuple[RobotProfile, ...]]:
    profiles = parse_team(team)
    return WorldState.from_scene(load_scene(fp), profiles), profiles


def test_fridge_needs_an_opener_and_a_carrier() -> None:
    state, team = _state("FloorPlan1", "23,25")
    a = analyse_condition(Condition.parse("inside(Apple, Fridge)"), state)
    for m in a.methods:
        skills = m.skills
        assert {Skill.OpenObject, Skill.PickupObject, Skill.PutObject} <= skills, str(m)
    opener, carrier = team
    assert a.team_method(team) is not None
    assert a.solo_method(opener) is None and a.solo_method(carrier) is None
    assert "PickupObject" in a.why_not(opener) and "OpenObject" in a.why_not(carrier)


def test_slicing_needs_knife_and_slice_on_one_robot() -> None:
    state, _ = _state("FloorPlan6", "1")
    a = analyse_condition(Condition.parse("sliced(Tomato)"), state)
    for m in a.methods:
        slicer = next(r for r in m.roles if Skill.SliceObject in r.skills)
        assert Skill.PickupObject in slicer.skills  # the knife is held by the slicer
    # robot16 has Slice but no Pickup (cannot hold a knife); robot26 has both
    assert a.solo_method(parse_team("16")[0]) is None
    assert a.solo_method(parse_team("26")[0]) is not None


def test_mass_capacity_decides_who_can_carry() -> None:
    state, _ = _state("FloorPlan1", "1")
    a = analyse_condition(Condition.parse("inside(Mug, CoffeeMachine)"), state)
    heavy = [r for m in a.methods for r in m.roles if r.lift > 0]
    assert heavy and min(r.lift for r in heavy) == pytest.approx(1.0)  # the mug's mass
    assert a.solo_method(parse_team("5")[0]) is not None  # lifts 1.0 kg
    assert a.solo_method(parse_team("28")[0]) is None  # lifts 0.9 kg


def test_a_slice_is_lighter_than_its_whole() -> None:
    """Cutting the apple lets a weak robot move part of it (inside(Apple, ..) counts slices)."""
    state, _ = _state("FloorPlan1", "1")
    weak = parse_team("7")[0]  # all skills, 0.08 kg: lifts a butter knife and an apple slice
    a = analyse_condition(Condition.parse("inside(Apple, Plate)"), state)
    method = a.solo_method(weak)
    assert method is not None
    assert any(s.action.skill is Skill.SliceObject for s in method.steps)


def test_throwing_reaches_the_bin_whatever_the_placement_rules() -> None:
    state, _ = _state("FloorPlan15", "1")
    assert not load_catalogue().can_place("Mug", "GarbageCan")
    a = analyse_condition(Condition.parse("inside(Mug, GarbageCan)"), state)
    assert [m for m in a.methods if any(s.action.skill is Skill.ThrowObject for s in m.steps)]
    assert all(Skill.ThrowObject in m.skills for m in a.methods)


def test_no_method_when_the_rules_forbid_it() -> None:
    state, team = _state("FloorPlan209", "1")
    a = analyse_condition(Condition.parse("inside(Vase, Sofa)"), state)  # vases never go on sofas
    assert a.methods == ()
    assert not analyse_goal(Goal.parse(["inside(Vase, Sofa)"]), state).team_can(team)
    assert "no way" in a.why_not(team[0])


def test_microwave_door_and_power_interlock() -> None:
    state, _ = _state("FloorPlan6", "1")
    a = analyse_condition(Condition.parse("cooked(Potato)"), state)
    micro = next(m for m in a.methods if m.label.startswith("microwave"))
    order = [s.action.skill for s in micro.steps]
    assert order.index(Skill.CloseObject) < order.index(Skill.SwitchOn)
    assert order.index(Skill.PutObject) < order.index(Skill.CloseObject)


def test_running_water_reaches_what_sits_in_the_sink_already() -> None:
    """FloorPlan6's mug sits in the sink: switching the faucet on is all it takes."""
    state, _ = _state("FloorPlan6", "24")
    state.objects["Mug_1"].is_dirty = True
    a = analyse_condition(Condition.parse("clean(Mug)"), state)
    switcher = parse_team("24")[0]  # GoTo and switches only
    method = a.solo_method(switcher)
    assert method is not None and [s.action.skill for s in method.steps] == [Skill.SwitchOn]
    assert a.solo_method(parse_team("25")[0]) is None  # a carrier cannot run the tap
