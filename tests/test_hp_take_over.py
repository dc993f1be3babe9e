"""A switch or a door other robots wait for, done by one of them (hp/take_over.py,
hp/stages/take_over.py): the robots that stood holding their things until another robot
switched the faucet on late in its own chain switch it on themselves; the stage never makes
a plan longer, its plans run in the simulator."""

from __future__ import annotations

from emboteam.hp.goalgen import sweep_cell
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.hp.stages.context import Context, Draft
from emboteam.hp.stages.take_over import take_over
from emboteam.hp.take_over import candidates
from emboteam.hp.validate import simulate
from emboteam.world.actions import Action, Skill


def _step(sid: str, robot: str, skill: Skill, target: str, start: float, end: float,
          after: tuple[str, ...] = (), receptacle: str | None = None) -> PlanStep:
    return PlanStep(id=sid, robot=robot, action=Action(skill=skill, target=target, receptacle=receptacle),
                    subtask="c1", after=after, est_start=start, est_end=end)


def _plan(*steps: PlanStep) -> MergedPlan:
    return MergedPlan(robots=("r1", "r2", "r3"), steps=steps, makespan=max(s.est_end for s in steps))


def test_a_switch_two_robots_waited_for_is_offered_to_the_one_free_first() -> None:
    plan = _plan(
        _step("r1.1", "r1", Skill.BreakObject, "Plate_1", 0.0, 5.0),
        _step("r2.1", "r2", Skill.PickupObject, "Bowl_1", 0.0, 1.0),
        _step("r3.1", "r3", Skill.PickupObject, "Cup_1", 0.0, 3.0),
        _step("r1.2", "r1", Skill.SwitchOn, "Faucet_1", 5.0, 5.5),
        _step("r2.2", "r2", Skill.PutObject, "Bowl_1", 5.5, 6.5, ("r1.2",), "SinkBasin_1"),
        _step("r3.2", "r3", Skill.PutObject, "Cup_1", 6.5, 7.5, ("r1.2", "r2.2"), "SinkBasin_1"),
    )
    [c] = candidates(plan)
    assert plan.steps[c.index].id == "r1.2"
    assert c.robots == ("r2", "r3")  # r2 free at 1.0, r3 at 3.0
    assert c.waited == 4.5 + 3.5


def test_only_switches_and_doors_are_taken_over_and_short_waits_are_left() -> None:
    plan = _plan(
        _step("r1.1", "r1", Skill.PickupObject, "Knife_1", 0.0, 5.0),
        _step("r1.2", "r1", Skill.PutObject, "Knife_1", 5.0, 6.0, receptacle="Drawer_2"),
        _step("r2.1", "r2", Skill.PickupObject, "Knife_1", 6.0, 7.0, ("r1.2",)),  # waited for a put
        _step("r1.3", "r1", Skill.OpenObject, "Fridge_1", 6.0, 7.5),
        _step("r3.1", "r3", Skill.PickupObject, "Egg_1", 7.0, 8.0),
        _step("r3.2", "r3", Skill.PutObject, "Egg_1", 8.25, 9.0, ("r1.3",), "Fridge_1"),  # waited 0.25 s
    )
    assert candidates(plan) == []


def test_robots_that_waited_for_the_faucet_switch_it_on_themselves() -> None:
    # FloorPlan1, 2 robots x 96 goals, goal seed 2: robot1 switches the faucet on at
    # 4.5-5.0 s; robot2, free at 3.5 s, waits for it to put its cup in the sink
    spec, state = sweep_cell("FloorPlan1", 2, 128, 2)
    off = HybridPlanner(PlannerConfig(take_over=False)).plan(spec, state)
    on = HybridPlanner(PlannerConfig()).plan(spec, state)
    assert on.makespan < off.makespan - 1.0  # 176.75 -> 174.0 s
    assert any("itself instead of waiting for" in n for n in on.notes)
    timing = simulate(on, state, spec.goal())
    assert timing.ok, timing.failure
    assert abs(timing.makespan - on.makespan) < 1e-6
    again = HybridPlanner(PlannerConfig()).plan(spec, state)
    assert [(s.robot, str(s.action), s.after) for s in again.steps] == [(s.robot, str(s.action), s.after)
                                                                      for s in on.steps]


def _watched() -> tuple[HybridPlanner, list[tuple[float, float]]]:
    """A planner whose take-over stage records each (makespan in, makespan out)."""
    seen: list[tuple[float, float]] = []

    def stage(ctx: Context, draft: Draft) -> Draft:
        out = take_over(ctx, draft)
        seen.append((draft.plan.makespan, out.plan.makespan))
        return out

    planner = HybridPlanner(PlannerConfig(take_over=False))
    stages = list(planner.stages)
    stages.insert(len(stages) - 1, stage)  # before the CP-SAT stage, as improvements() puts it
    planner.stages = tuple(stages)
    return planner, seen


def test_the_stage_never_makes_a_plan_longer() -> None:
    for cell in (("FloorPlan1", 8, 8, 0), ("FloorPlan201", 8, 32, 1), ("FloorPlan1", 8, 32, 2)):
        spec, state = sweep_cell(*cell)
        planner, seen = _watched()
        plan = planner.plan(spec, state)
        assert seen and all(after <= before for before, after in seen)
        assert simulate(plan, state, spec.goal()).ok
