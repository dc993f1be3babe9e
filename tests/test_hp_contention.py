"""The resource-aware makespan bound and the bottleneck-first acceptance order."""

from __future__ import annotations

from emboteam.hp import HybridPlanner, PlannerConfig
from emboteam.hp.contention import bottleneck_first, spot_seconds
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.hp.validate import resource_bound, simulate
from emboteam.pddl.problem import planning_state
from emboteam.world.actions import Action, Skill
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


def _step(i: int, robot: str, subtask: str, skill: Skill = Skill.OpenObject, target: str = "Fridge_1") -> PlanStep:
    return PlanStep(id=f"{robot}.{i}", robot=robot, action=Action(skill=skill, target=target), subtask=subtask)


def test_the_bound_is_the_largest_of_work_share_subtask_and_busiest_spot() -> None:
    steps = (_step(1, "r1", "a"), _step(2, "r1", "a", target="Cabinet_1"), _step(1, "r2", "b", target="Drawer_1"),
             _step(2, "r2", "c", target="Drawer_2"))
    plan = MergedPlan(robots=("r1", "r2", "r3", "r4"), steps=steps)
    durations = {"r1.1": 4.0, "r1.2": 3.0, "r2.1": 2.0, "r2.2": 1.0}
    # every step at one spot: the fridge serves one robot at a time
    b = resource_bound(plan, durations, {s.id: "Fridge_1" for s in steps})
    assert (b.work, b.subtask, b.spot, b.spot_name) == (2.5, 7.0, 10.0, "Fridge_1") and b.value == 10.0
    # no shared spot: subtask a's 7 s by one robot bound it
    b = resource_bound(plan, durations, {})
    assert b.value == 7.0 and b.spot == 0.0 and b.object == 4.0


def test_a_spot_cannot_be_reached_before_the_steps_that_lead_to_it() -> None:
    """Two robots each drive 3 s to the microwave, use it 4 s and carry the result away
    for 2 s: the microwave's 8 s of use cannot start before 3 s nor end later than 2 s
    before the end, so no schedule takes less than 13 s (the serial time alone says 8)."""
    def job(robot: str) -> tuple[PlanStep, ...]:
        return (_step(1, robot, robot, Skill.GoToObject, "Microwave_1"), _step(2, robot, robot, target="Microwave_1"),
                _step(3, robot, robot, Skill.GoToObject, "CounterTop_1"))
    plan = MergedPlan(robots=("r1", "r2"), steps=(*job("r1"), *job("r2")))
    durations = {f"{r}.{i}": d for r in ("r1", "r2") for i, d in ((1, 3.0), (2, 4.0), (3, 2.0))}
    b = resource_bound(plan, durations, {"r1.2": "Microwave_1", "r2.2": "Microwave_1"})
    assert (b.spot, b.spot_window, b.window_name) == (8.0, 13.0, "Microwave_1")
    assert b.value == 13.0
    # the second robot needs no head: the least head counts (0 + 8 + 2)
    durations["r2.1"] = 0.0
    assert resource_bound(plan, durations, {"r1.2": "Microwave_1", "r2.2": "Microwave_1"}).spot_window == 10.0


def test_an_object_is_worked_on_by_one_robot_at_a_time() -> None:
    """Open a book, pick it up, carry it, put it on a shelf: four subtasks, two robots,
    no shared spot, but every step is on the book, so they run one after another."""
    steps = (_step(1, "r1", "open", Skill.OpenObject, "Book_1"), _step(2, "r1", "pick", Skill.PickupObject, "Book_1"),
             _step(3, "r1", "carry", Skill.GoToObject, "Shelf_1"),
             PlanStep(id="r1.4", robot="r1", subtask="put",
                      action=Action(skill=Skill.PutObject, target="Book_1", receptacle="Shelf_1")),
             _step(1, "r2", "other", Skill.OpenObject, "Drawer_1"))
    plan = MergedPlan(robots=("r1", "r2"), steps=steps)
    durations = {"r1.1": 1.5, "r1.2": 1.0, "r1.3": 5.2, "r1.4": 1.0, "r2.1": 1.5}
    b = resource_bound(plan, durations, {})
    assert (b.object, b.object_name) == (8.7, "Book_1")
    assert b.value == 8.7 and b.subtask == 5.2
    # what the robot held, when the simulator says so, decides: nothing held, no carry
    assert resource_bound(plan, durations, {}, holding={}).object == 3.5


def test_simulated_makespan_is_at_least_the_resource_bound() -> None:
    """Two robots heating two things in one microwave queue there."""
    state = planning_state(WorldState.from_scene(load_scene("FloorPlan1"), parse_team("1,2")))
    goal = Goal.parse("hot(Potato) & hot(Cup)")
    plan = HybridPlanner(PlannerConfig()).plan_goal(goal, state)
    timing = simulate(plan, state, goal)
    assert timing.ok
    assert timing.resources.spot_name == "Microwave_1"
    assert 0 < timing.resources.value <= timing.makespan + 1e-6
    assert plan.resource_bound == round(timing.resources.value, 3)


def test_users_of_the_most_contended_spot_are_accepted_first() -> None:
    uses = [{"Knife_1": 1.0}, {"Microwave_1": 4.0, "Knife_1": 1.0}, None, {"Microwave_1": 6.0},
            {"Drawer_1": 9.0}]
    order = bottleneck_first(["knife", "both", "unplanned", "oven", "drawer"], uses)
    # the microwave (10 s over two units) first, its heavier user before the lighter; the
    # drawer is nobody else's: it keeps its place among the rest
    assert order == ["oven", "both", "knife", "unplanned", "drawer"]


def test_spot_seconds_counts_manipulation_where_the_object_is_reached() -> None:
    state = WorldState.from_scene(load_scene("FloorPlan1"), parse_team("1"))
    state.move_object("Apple_1", "Fridge_1")
    actions = [("robot1", Action(skill=Skill.GoToObject, target="Fridge_1")),
               ("robot1", Action(skill=Skill.OpenObject, target="Fridge_1")),
               ("robot1", Action(skill=Skill.PickupObject, target="Apple_1")),
               ("robot1", Action(skill=Skill.SliceObject, target="Apple_1_Slice_1"))]
    use = spot_seconds(state, actions)
    assert set(use) == {"Fridge_1"} and use["Fridge_1"] > 0


def test_a_round_is_interleaved_by_time_not_unit_by_unit() -> None:
    """robot1 fetches an apple for the fridge, robot2 only opens the fridge: robot2 gets
    there first, so its opening goes first and robot1's own opening is skipped (already
    done), where the unit-by-unit order would have robot2 wait for robot1's whole trip."""
    from emboteam.hp.interleave import interleave
    from emboteam.hp.merge import SeqStep
    from emboteam.pddl.domain import Universe

    state = planning_state(WorldState.from_scene(load_scene("FloorPlan1"), parse_team("1,2")))
    state.robots["robot2"].position = (state.objects["Fridge_1"].position[0], state.objects["Fridge_1"].position[2])

    def a(skill: Skill, target: str, receptacle: str | None = None) -> Action:
        return Action(skill=skill, target=target, receptacle=receptacle)

    fetch = [SeqStep("robot1", x, "s1", "u1") for x in (
        a(Skill.GoToObject, "Apple_1"), a(Skill.PickupObject, "Apple_1"), a(Skill.GoToObject, "Fridge_1"),
        a(Skill.OpenObject, "Fridge_1"), a(Skill.PutObject, "Apple_1", "Fridge_1"))]
    opening = [SeqStep("robot2", x, "s2", "u2") for x in (a(Skill.GoToObject, "Fridge_1"), a(Skill.OpenObject, "Fridge_1"))]
    goals = list(Goal.parse("inside(Apple_1, Fridge_1) & open(Fridge_1)").conditions)
    mixed = interleave(state, [fetch, opening], goals, Universe(state))
    assert mixed is not None
    steps, final = mixed
    opens = [g.robot for g in steps if g.action.skill is Skill.OpenObject]
    assert opens == ["robot2"]
    order = [(g.robot, g.action.skill) for g in steps]
    assert order.index(("robot2", Skill.OpenObject)) < order.index(("robot1", Skill.PickupObject))
    assert final.objects["Apple_1"].parent == "Fridge_1"
    # a goal the interleaving cannot reach leaves the unit-by-unit order in place
    assert interleave(state, [fetch, opening], [*goals, *Goal.parse("closed(Fridge_1)").conditions],
                      Universe(state)) is None


def test_interleaving_is_tried_only_where_the_unit_by_unit_order_makes_a_robot_wait() -> None:
    from emboteam.hp.interleave import worth_it
    from emboteam.hp.merge import SeqStep, ground_sequence

    state = planning_state(WorldState.from_scene(load_scene("FloorPlan1"), parse_team("1,2")))

    def steps(*xs: tuple[str, Skill, str]) -> list[SeqStep]:
        return [SeqStep(r, Action(skill=k, target=t), "s", "u") for r, k, t in xs]

    apart, _ = ground_sequence(state, steps(("robot1", Skill.GoToObject, "Fridge_1"), ("robot1", Skill.OpenObject, "Fridge_1"),
                                            ("robot2", Skill.GoToObject, "Cabinet_1"), ("robot2", Skill.OpenObject, "Cabinet_1")))
    assert not worth_it(apart)  # nothing in common: both start at once
    # robot2's whole job waits for robot1's long trip: it closes the door robot1 opened
    chained, _ = ground_sequence(state, steps(
        ("robot1", Skill.GoToObject, "Apple_1"), ("robot1", Skill.GoToObject, "Fridge_1"),
        ("robot1", Skill.OpenObject, "Fridge_1"), ("robot2", Skill.GoToObject, "Fridge_1"),
        ("robot2", Skill.CloseObject, "Fridge_1"), ("robot2", Skill.GoToObject, "Toaster_1"),
        ("robot2", Skill.SwitchOn, "Toaster_1")))
    assert worth_it(chained)


def test_no_mace_thor_plan_beats_its_resource_bound() -> None:
    """The bound claims every schedule of a plan's actions takes at least that long; the
    simulated schedule of each MACE-THOR plan is one of them."""
    from emboteam.bench.suites import load_suite
    from emboteam.pfg.oracle import OracleFrontend

    planner = HybridPlanner(PlannerConfig())
    tighter = 0
    for task in load_suite("mace-thor").tasks:
        state = task.initial_state()
        spec = OracleFrontend(task.goal).decompose(task.instruction, load_scene(task.floor_plan), state, task.team())
        plan = planner.plan(spec, state)
        timing = simulate(plan, planning_state(state), task.goal)
        b = timing.resources
        assert timing.ok and b.value <= timing.makespan + 1e-6, task.id
        assert b.spot_window >= b.spot and b.object_window >= b.object
        tighter += b.value > max(b.work, b.subtask, b.spot) + 1e-6
    assert tighter > 0  # heads, tails and objects tighten some of them
