"""Drives ahead to where a thing is brought (hp/drive_ahead.py, hp/stages/drive_ahead.py):
a robot that is to put something into a box another robot carries drives to where the box
goes while it is carried, instead of waiting for it and then driving; the stage never makes
a plan longer, its plans run in the simulator, the same every time."""

from __future__ import annotations

from dataclasses import replace

from emboteam.hp.drive_ahead import driven_ahead, retargets, waited
from emboteam.hp.goalgen import sweep_cell
from emboteam.hp.merge import GroundedStep
from emboteam.hp.plan import MergedPlan
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.drive_ahead import drive_ahead
from emboteam.hp.stages.replay import replay_to_goal
from emboteam.hp.validate import simulate
from emboteam.pddl.problem import planning_state
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.actions import Skill
from emboteam.world.state import WorldState


def _waiting_drives(plan: MergedPlan) -> list[str]:
    """Drives that waited for another robot's step that put their object somewhere."""
    puts = {s.id: s for s in plan.steps if s.action.skill is Skill.PutObject}
    out = []
    for i in waited(plan):
        s = plan.steps[i]
        if s.action.skill is Skill.GoToObject and any(
                p in puts and puts[p].action.target == s.action.target for p in s.after):
            out.append(s.id)
    return out


def _watched(config: PlannerConfig) -> tuple[HybridPlanner, list[tuple[Draft, Draft, dict[int, str]]]]:
    """A planner whose drive-ahead stage records (draft in, draft out, the drives it
    found to retarget)."""
    seen: list[tuple[Draft, Draft, dict[int, str]]] = []

    def stage(ctx: Context, draft: Draft) -> Draft:
        found = retargets(draft.record.sequence, waited(draft.plan))
        before = Draft(draft.plan, replace(draft.record, sequence=list(draft.record.sequence)))
        out = drive_ahead(ctx, draft)
        seen.append((before, out, found))
        return out

    planner = HybridPlanner(config)
    stages = list(planner.stages)
    stages.insert(len(stages) - 1, stage)  # before the CP-SAT stage, as improvements() puts it
    planner.stages = tuple(stages)
    return planner, seen


def test_drives_that_waited_for_a_carried_box_go_to_where_it_is_brought() -> None:
    # FloorPlan201, 8 robots x 8 goals, seed 1: a box carried to a side table, three
    # helpers put a pencil, a book and a statue in it; they drive to the box once it is
    # there (22.0 s with the helpers that end first, 18.25 with the nearest); driving to
    # the side table while it is carried: 18.0 s (the box arrives at 15.0, three puts)
    spec, state = sweep_cell("FloorPlan201", 8, 8, 1)
    config = PlannerConfig(route=False, drive_ahead=False)
    planner, seen = _watched(config)
    plan = planner.plan(spec, state)
    [(before, after, found)] = seen
    assert found, "the helpers' drives to the box waited for it"
    sequence = before.record.sequence
    assert all(sequence[i].action.skill is Skill.GoToObject for i in found)
    assert set(found.values()) == {"SideTable_3"}
    assert _waiting_drives(before.plan)
    assert after.plan.makespan < before.plan.makespan
    assert after.plan.makespan <= 18.0
    assert not _waiting_drives(after.plan)
    assert any("went ahead" in n for n in plan.notes)
    timing = simulate(plan, state, spec.goal())
    assert timing.ok, timing.failure
    assert abs(timing.makespan - plan.makespan) < 1e-6


def test_the_stage_never_makes_a_plan_longer_and_gives_the_same_plan_again() -> None:
    for cell in (("FloorPlan201", 32, 8, 1), ("FloorPlan1", 8, 8, 0), ("FloorPlan201", 2, 8, 4)):
        spec, state = sweep_cell(*cell)
        planner, seen = _watched(PlannerConfig(drive_ahead=False))
        plan = planner.plan(spec, state)
        for before, after, _ in seen:
            assert after.plan.makespan <= before.plan.makespan
        assert simulate(plan, state, spec.goal()).ok
    spec, state = sweep_cell("FloorPlan201", 32, 8, 1)
    one = HybridPlanner(PlannerConfig()).plan(spec, state)
    two = HybridPlanner(PlannerConfig()).plan(spec, state)
    assert [(s.id, s.robot, str(s.action), s.after, s.est_end) for s in one.steps] == [
        (s.id, s.robot, str(s.action), s.after, s.est_end) for s in two.steps]
    assert not _waiting_drives(one)
    # the book's robot waited for the box, then drove 5 s: 14.5 s before drives went ahead
    # (now in the container split's candidates, then the route stage keeps them)
    assert one.makespan <= 11.5


def _retargets_on_8x8() -> tuple[TaskSpec, WorldState, list[GroundedStep], dict[int, str]]:
    """FloorPlan201, 8 robots x 8 goals, seed 1, planned with drives left as they are: the
    task, its start, the grounded sequence the drive-ahead stage got and what it retargets."""
    spec, state = sweep_cell("FloorPlan201", 8, 8, 1)
    planner, seen = _watched(PlannerConfig(route=False, drive_ahead=False))
    planner.plan(spec, state)
    [(before, _, found)] = seen
    return spec, state, before.record.sequence, found


def test_a_drive_is_retargeted_only_when_another_robot_put_its_object_and_it_waited() -> None:
    _, _, sequence, found = _retargets_on_8x8()
    assert retargets(sequence, set()) == {}  # nothing waited: nothing to retarget
    for i, place in found.items():
        put = max(j for j, g in enumerate(sequence[:i]) if g.action.skill is Skill.PutObject
                  and g.action.target == sequence[i].action.target)
        assert sequence[put].robot != sequence[i].robot
        assert sequence[put].action.receptacle == place


def test_replaying_from_the_first_moved_drive_grounds_as_the_whole_replay() -> None:
    # the stage replays only from its first retargeted drive, the steps before it kept as
    # grounded (a replay of a replay's own steps grounds them as they are): the same
    # grounded sequence as replaying the whole plan from the start
    spec, state, sequence, found = _retargets_on_8x8()
    start, steps = planning_state(state), driven_ahead(sequence, found)
    whole, why = replay_to_goal(start, steps, spec.goal())
    assert why is None and len(whole) == len(sequence)
    first = min(found)
    assert first > 0
    for k in (0, first // 2, first):
        from_head, why = replay_to_goal(start, steps[k:], spec.goal(), head=sequence[:k])
        assert why is None and from_head == whole
