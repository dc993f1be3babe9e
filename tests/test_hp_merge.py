"""Merging sequences into a partial order: causal links, commuting updates, transitive
reduction, timing and the lower bound (no planner calls: sequences are written by hand)."""

from __future__ import annotations

import random

import pytest

from emboteam.hp.merge import SeqStep, StepFailure, assemble, ground_sequence, order
from emboteam.hp.rounds import polish
from emboteam.hp.validate import estimate, lower_bound, simulate
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.actions import Action, Skill
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

S = Skill


def fresh(team: str = "1,2") -> WorldState:
    return WorldState.from_scene(load_scene("FloorPlan1"), parse_team(team))


def step(robot: str, skill: Skill, target: str, receptacle: str | None = None, subtask: str = "t") -> SeqStep:
    return SeqStep(robot, Action(skill=skill, target=target, receptacle=receptacle), subtask, subtask)


def fridge_sequence() -> list[SeqStep]:
    """robot1 opens the fridge and puts the apple in; robot2 puts the tomato in; robot2
    also switches the light off (unrelated to everything else)."""
    return [
        step("robot1", S.GoToObject, "Fridge_1"), step("robot1", S.OpenObject, "Fridge_1"),
        step("robot1", S.GoToObject, "Apple_1"), step("robot1", S.PickupObject, "Apple_1"),
        step("robot1", S.GoToObject, "Fridge_1"), step("robot1", S.PutObject, "Apple_1", "Fridge_1"),
        step("robot2", S.GoToObject, "Tomato_1"), step("robot2", S.PickupObject, "Tomato_1"),
        step("robot2", S.GoToObject, "Fridge_1"), step("robot2", S.PutObject, "Tomato_1", "Fridge_1"),
        step("robot2", S.GoToObject, "LightSwitch_1"), step("robot2", S.SwitchOff, "LightSwitch_1"),
    ]


def test_causal_links_become_sync_points_and_commuting_puts_do_not() -> None:
    state = fresh()
    grounded, _ = ground_sequence(state, fridge_sequence())
    plan = assemble(grounded, order(grounded, {}), ["robot1", "robot2"], {})
    put_tomato = plan.step("robot2.4")
    assert put_tomato.action.target == "Tomato_1"
    assert put_tomato.after == ("robot1.2",)  # needs the fridge open, not the apple's put
    assert [(sp.producer, sp.consumer) for sp in plan.sync] == [("robot1.2", "robot2.4")]
    assert "open:Fridge_1" in plan.sync[0].reason
    assert plan.step("robot2.1").after == ()  # fetching the tomato waits for nobody
    timing = simulate(plan, state)
    assert timing.ok, timing.failure
    # robot2 works while robot1 does: the fridge spot is shared, one at a time
    assert timing.makespan < sum(e - s for s, e in timing.times.values())


def test_closing_the_fridge_waits_for_the_other_robots_put() -> None:
    """A threat: robot1 closes the fridge robot2 still needs open."""
    state = fresh()
    seq = [*fridge_sequence()[:10], step("robot1", S.CloseObject, "Fridge_1")]
    grounded, _ = ground_sequence(state, seq)
    plan = assemble(grounded, order(grounded, {}), ["robot1", "robot2"], {})
    close = next(s for s in plan.steps if s.action.skill is S.CloseObject)
    assert "robot2.4" in close.after
    assert simulate(plan, state).ok


def test_waits_are_transitively_reduced() -> None:
    state = fresh()
    grounded, _ = ground_sequence(state, [*fridge_sequence(), step("robot1", S.CloseObject, "Fridge_1")])
    waits = order(grounded, {})
    # recompute reachability: no kept wait is implied by another path
    preds: list[set[int]] = []
    last: dict[str, int] = {}
    for j, g in enumerate(grounded):
        p = set(waits[j]) | ({last[g.robot]} if g.robot in last else set())
        preds.append(p)
        last[g.robot] = j

    def ancestors(j: int) -> set[int]:
        seen: set[int] = set()
        stack = list(preds[j])
        while stack:
            i = stack.pop()
            if i not in seen:
                seen.add(i)
                stack += preds[i]
        return seen

    for j in range(len(grounded)):
        for i in waits[j]:
            others = preds[j] - {i}
            assert not any(i in ancestors(o) or i == o for o in others), (i, j)


def test_subtask_dependencies_order_whole_groups() -> None:
    state = fresh()
    seq = [step("robot1", S.GoToObject, "LightSwitch_1", subtask="a"), step("robot1", S.SwitchOff, "LightSwitch_1",
                                                                           subtask="a"),
           step("robot2", S.GoToObject, "Tomato_1", subtask="b")]
    grounded, _ = ground_sequence(state, seq)
    free = order(grounded, {})
    assert free[2] == []
    bound = order(grounded, {"b": ("a",)})
    assert bound[2] == [1]
    concat = order(grounded, {"b": ("a",)}, "concatenate")
    assert concat[2] == [1]
    sequential = order(grounded, {}, "sequential")
    assert sequential[2] == [1]


def test_random_linearisations_of_a_merged_plan_all_work() -> None:
    state = fresh("1,2,3")
    seq = [
        step("robot1", S.GoToObject, "ButterKnife_1"), step("robot1", S.PickupObject, "ButterKnife_1"),
        step("robot1", S.GoToObject, "Bread_1"), step("robot1", S.SliceObject, "Bread_1"),
        step("robot2", S.GoToObject, "Microwave_1"), step("robot2", S.OpenObject, "Microwave_1"),
        step("robot3", S.GoToObject, "Bread_1_Slice_1"), step("robot3", S.PickupObject, "Bread_1_Slice_1"),
        step("robot3", S.GoToObject, "Microwave_1"), step("robot3", S.PutObject, "Bread_1_Slice_1", "Microwave_1"),
        step("robot2", S.CloseObject, "Microwave_1"), step("robot2", S.SwitchOn, "Microwave_1"),
        step("robot1", S.PutObject, "ButterKnife_1", "CounterTop_2"),
    ]
    grounded, final = ground_sequence(state, seq)
    plan = assemble(grounded, order(grounded, {}), ["robot1", "robot2", "robot3"], {})
    assert final.objects["Bread_1_Slice_1"].temperature == "Hot"
    rng = random.Random(1)
    for _ in range(20):
        s = state.copy()
        done: set[str] = set()
        queues = {r: plan.for_robot(r) for r in plan.robots}
        while any(queues.values()):
            ready = [r for r, q in queues.items() if q and all(a in done for a in q[0].after)]
            st = queues[rng.choice(ready)].pop(0)
            assert check_action(s, st.robot, st.action) is None, st
            apply_action(s, st.robot, st.action)
            done.add(st.id)
        assert s.objects["Bread_1_Slice_1"].temperature == "Hot"
        assert s.objects["Bread_1_Slice_1"].parent == "Microwave_1"


def test_a_step_that_cannot_run_is_reported() -> None:
    with pytest.raises(StepFailure, match="Fridge_1 must be open"):
        ground_sequence(fresh(), [step("robot1", S.GoToObject, "Apple_1"), step("robot1", S.PickupObject, "Apple_1"),
                                  step("robot1", S.GoToObject, "Fridge_1"),
                                  step("robot1", S.PutObject, "Apple_1", "Fridge_1")])


def test_lower_bound_and_estimates() -> None:
    state = fresh()
    grounded, _ = ground_sequence(state, fridge_sequence())
    plan = assemble(grounded, order(grounded, {}), ["robot1", "robot2"], {})
    seconds = {s.id: g.seconds for s, g in zip(plan.steps, grounded, strict=True)}
    est = estimate(plan, seconds)
    work = {r: sum(seconds[s.id] for s in plan.for_robot(r)) for r in plan.robots}
    assert lower_bound(plan, seconds) >= max(work.values())
    assert est.makespan >= est.lower_bound
    for s in est.steps:
        for p in s.after:
            assert est.step(p).est_end <= s.est_start + 1e-9


def test_polish_drops_hops_a_robot_leaves_without_acting() -> None:
    def go(robot: str, target: str) -> tuple[str, Action]:
        return robot, Action(skill=S.GoToObject, target=target)

    pick = ("robot1", Action(skill=S.PickupObject, target="Apple_1"))
    actions = [go("robot1", "Toaster_1"), go("robot2", "Fridge_1"), go("robot1", "Apple_1"), pick,
               go("robot2", "Bread_1")]
    assert polish(actions) == [go("robot1", "Apple_1"), pick, go("robot2", "Bread_1")]
    # the polished sequence runs and ends where the original does
    state = fresh()
    _, polished = ground_sequence(state, [SeqStep(r, a, "t") for r, a in polish(actions)])
    _, original = ground_sequence(state, [SeqStep(r, a, "t") for r, a in actions])
    assert polished.robots["robot1"].position == original.robots["robot1"].position
    assert polished.objects["Apple_1"].held_by == original.objects["Apple_1"].held_by == "robot1"
