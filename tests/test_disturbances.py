"""Benchmark disturbances: spec parsing, seeded resolution, job keys, the blackboard as a
lossy network (a lost lock release times out, a flag is read late), the linear executors
with joins and delays, the ceiling's verdicts, and episodes surviving each disturbance."""

from __future__ import annotations

import pytest
from py_trees.common import Access

from emboteam.bench.jobs import BenchConfig, Job, expand_jobs
from emboteam.bench.suites import get_task
from emboteam.btc.config import BTConfig
from emboteam.btc.keys import lock_key
from emboteam.btc.runtime import Runtime
from emboteam.errors import UnknownRobotError
from emboteam.exec.ceiling import _ceiling
from emboteam.exec.linear import run_linear
from emboteam.mode_table import planner_for
from emboteam.pipeline import RunConfig, run_episode
from emboteam.sim.disturbances import (
    BreakdownSpec,
    Disturbances,
    DisturbanceSpecError,
    JoinSpec,
    MoveSpec,
    When,
    parse_when,
    resolve,
)
from emboteam.sim.faults import FaultConfig, MessageFaults, ObjectMove
from emboteam.sim.simulator import Simulator
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team, robot_profile
from emboteam.world.scene import load_scene
from test_btc_plans import fridge_handoff, team_sim

# ---- parsing ---------------------------------------------------------------------------


def test_times_parse_as_fractions_percentages_or_seconds() -> None:
    assert parse_when("0.3", bare="fraction", option="x") == When(value=0.3, unit="fraction")
    assert parse_when("30%", bare="fraction", option="x") == When(value=0.3, unit="fraction")
    assert parse_when("12.5s", bare="fraction", option="x") == When(value=12.5, unit="seconds")
    assert parse_when("30", bare="seconds", option="--join") == When(value=30, unit="seconds")
    assert When(value=0.3, unit="fraction").seconds(40.0) == pytest.approx(12.0)


@pytest.mark.parametrize("text", ["random", "@0.3", "random@", "random@soon", "random@1.5", "random@-1"])
def test_bad_breakdown_specs_are_typed_errors(text: str) -> None:
    with pytest.raises(DisturbanceSpecError):
        BreakdownSpec.parse(text)


def test_specs_and_their_canonical_label() -> None:
    d = Disturbances.parse(breakdown=["random@0.3"], join=["5@30", "random@40%"], moves=["random@0.5,Apple_1@20s"],
                           msg_loss=0.5, msg_delay=2)
    assert d.breakdowns == (BreakdownSpec(robot="random", at=When(value=0.3, unit="fraction")),)
    assert d.joins[0] == JoinSpec(profile="5", at=When(value=30, unit="seconds"))
    assert d.moves[1] == MoveSpec(object="Apple_1", at=When(value=20, unit="seconds"))
    assert d.label == "breakdown=random@0.3;join=5@30s,random@40%;moves=random@0.5,Apple_1@20s;" \
                      "msg-loss=0.5;msg-delay=2"
    assert Disturbances.parse(breakdown=["RANDOM@30%"]).label == "breakdown=random@0.3"
    assert not Disturbances().any and Disturbances().label == ""


def test_bad_option_values_are_typed_errors() -> None:
    with pytest.raises(UnknownRobotError):
        Disturbances.parse(join=["99@3"])
    with pytest.raises(DisturbanceSpecError):
        Disturbances.parse(msg_loss=1.5)
    with pytest.raises(DisturbanceSpecError):
        Disturbances.parse(msg_delay=-1)


# ---- resolution and keys -----------------------------------------------------------------


def test_resolution_is_seeded_and_mode_independent() -> None:
    team = parse_team("1,2,3")
    spec = Disturbances.parse(breakdown=["random@0.5"], join=["random@10s"], moves=["random@0.2"])

    def run(seed: int):  # type: ignore[no-untyped-def]
        return resolve(spec, team=team, seed=seed, task="mace-thor/x", nominal_makespan=40.0,
                       plan_objects=["Apple_1", "Tomato_1"])

    assert run(3) == run(3)
    first = run(0)
    assert first.breakdowns[0].at == pytest.approx(20.0) and first.moves[0].at == pytest.approx(8.0)
    assert first.moves[0].candidates == ("Apple_1", "Tomato_1") and first.moves[0].into_closed
    assert len({run(s).breakdowns[0].robot for s in range(12)}) > 1  # the seed draws the robot
    profile, at = first.joins[0]
    assert at == 10.0 and profile.name.endswith("b")  # a second unit of a team member
    assert profile.skills == robot_profile(profile.name[:-1]).skills


def test_named_breakdown_must_be_in_the_team() -> None:
    spec = Disturbances.parse(breakdown=["robot9@1s"])
    with pytest.raises(DisturbanceSpecError, match="not in the team"):
        resolve(spec, team=parse_team("1,2"), seed=0, task="t", nominal_makespan=10.0)


def test_job_key_changes_only_when_disturbed() -> None:
    task = get_task("mace-thor/fp1-toast")
    plain = Job(task=task, seed=1, fault_level=0.2)
    assert "disturb" not in plain.key  # stores written before disturbances stay valid
    disturbed = Job(task=task, seed=1, fault_level=0.2, disturbance=Disturbances.parse(breakdown=["random@0.3"]))
    assert disturbed.key == plain.key + "|disturb=breakdown=random@0.3"
    cfg = BenchConfig(suite="mace-thor", seeds=2, disturbance=disturbed.disturbance, workers=1)
    assert all(j.disturbance == disturbed.disturbance for j in expand_jobs(cfg, [task]))


# ---- the blackboard as a lossy network --------------------------------------------------------


def _runtime(messages: MessageFaults, seed: int = 0):  # type: ignore[no-untyped-def]
    sim = team_sim("FloorPlan1", "1,2")
    rt = Runtime(sim, config=BTConfig(lock_lease=5.0), messages=messages, seed=seed)
    for robot in ("robot1", "robot2"):
        rt.board.register(robot, lock_key("spot"), Access.WRITE)
    return sim, rt


def test_a_lost_lock_release_times_out_after_the_lease() -> None:
    sim, rt = _runtime(MessageFaults(release_loss=1.0))
    assert rt.try_acquire("robot1", "spot")
    sim.advance(2.0)
    rt.release("robot1", ["spot"])
    assert rt.lost_releases == 1 and rt.holder("robot2", "spot") == "robot1"  # the release never arrived
    assert not rt.try_acquire("robot2", "spot")
    assert rt.next_wakeup(sim.now) == pytest.approx(7.0)  # the waiter is woken when the lease ends
    sim.advance(6.9)
    assert not rt.try_acquire("robot2", "spot")
    sim.advance(7.0)
    assert rt.try_acquire("robot2", "spot") and rt.lock_timeouts == 1
    assert rt.holder("robot1", "spot") == "robot2"
    rt.close()


def test_a_held_lock_never_times_out() -> None:
    sim, rt = _runtime(MessageFaults(release_loss=1.0))
    assert rt.try_acquire("robot1", "spot")
    sim.advance(100.0)
    assert not rt.try_acquire("robot2", "spot") and rt.lock_timeouts == 0
    rt.close()


def test_without_loss_a_release_frees_the_lock_at_once() -> None:
    _, rt = _runtime(MessageFaults())
    assert rt.try_acquire("robot1", "spot")
    rt.release("robot1", ["spot"])
    assert rt.try_acquire("robot2", "spot") and rt.lost_releases == 0
    rt.close()


def test_a_delayed_flag_is_read_late_by_others_only() -> None:
    sim, rt = _runtime(MessageFaults(flag_delay=4.0), seed=1)
    from emboteam.btc.keys import flag_key

    rt.board.register("robot1", flag_key("robot1.1"), Access.WRITE)
    rt.board.register("robot2", flag_key("robot1.1"), Access.READ)
    rt.set_flag("robot1", "robot1.1")
    assert rt.flag_set("robot1", "robot1.1")  # the writer knows at once
    assert not rt.flag_set("robot2", "robot1.1") and rt.late_reads == 1
    arrives = rt.next_wakeup(sim.now)
    assert arrives is not None and 0 < arrives <= 4.0
    sim.advance(arrives)
    assert rt.flag_set("robot2", "robot1.1")
    rt.close()


def test_linear_executor_reads_flags_late_and_a_joiner_stays_idle() -> None:
    plan, goal = fridge_handoff()
    base = run_linear(team_sim("FloorPlan1", "1,2"), plan, goal)
    late = run_linear(team_sim("FloorPlan1", "1,2"), plan, goal, messages=MessageFaults(flag_delay=5.0), seed=2,
                      joins=[(robot_profile(3), 1.0)])
    assert late.network["late_reads"] >= 1 and late.makespan > base.makespan
    assert late.joined_robots == ("robot3",) and late.joiner_actions == 0


# ---- the ceiling ---------------------------------------------------------------------------


def test_ceiling_says_unsavable_when_no_robot_is_left() -> None:
    state = get_task("mace-thor/fp1-fridge-apple-tomato").initial_state()
    for r in state.robots.values():
        r.down = True
    savable, why, left = _ceiling(get_task("mace-thor/fp1-fridge-apple-tomato").goal, state, planner_for("full"))
    assert savable is False and why.startswith("UnsavableTaskError") and left == ()


def test_ceiling_asks_the_planner_with_the_robots_left() -> None:
    task = get_task("mace-thor/fp1-fridge-apple-tomato")
    state, team = task.initial_state(), task.team()
    savable, why, left = _ceiling(task.goal, state, planner_for("full"))
    assert savable is True and "plan of" in why and left == tuple(sorted(p.name for p in team))
    # the goal needs a skill only one team member has: break that member and it is out of reach
    needs_open = [p.name for p in team if any(s.value == "OpenObject" for s in p.skills)]
    assert len(needs_open) == 1
    state.robots[needs_open[0]].down = True
    savable, why, left = _ceiling(task.goal, state, planner_for("full"))
    assert savable is False and why.startswith("UnsavableTaskError") and needs_open[0] not in left


def test_ceiling_of_a_goal_that_already_holds() -> None:
    state = get_task("mace-thor/fp1-fridge-apple-tomato").initial_state()
    assert _ceiling(Goal(conditions=()), state, planner_for("full"))[0] is True


# ---- episodes under each disturbance ----------------------------------------------------------

TASKS = ["mace-thor/fp1-fridge-apple-tomato", "mace-thor/fp6-salad-prep"]


def _episode(task: str, seed: int = 0, mode: str = "full", **options: object):  # type: ignore[no-untyped-def]
    cfg = RunConfig(mode=mode, frontend="oracle", fault_level=0.2, seed=seed,  # type: ignore[arg-type]
                    disturbance=Disturbances.parse(**options))  # type: ignore[arg-type]
    return run_episode(get_task(task), cfg)


@pytest.mark.parametrize("task", TASKS)
def test_a_breakdown_is_survived_or_ends_at_once_with_a_typed_reason(task: str) -> None:
    for seed in (0, 1):
        ep = _episode(task, seed, breakdown=["random@0.3"])
        d = ep.disturbance
        assert d is not None and d.events and d.events[0].kind == "breakdown"
        assert d.nominal_makespan > 0 and d.events[0].t == pytest.approx(0.3 * d.nominal_makespan, abs=1e-3)
        assert d.savable is not None
        if d.savable:
            assert ep.success, (seed, ep.error)
        else:
            assert not ep.success and ep.error and ep.error.startswith("UnsavableTaskError")
            assert d.stop_reason == "unsavable" and d.wall_after is not None


@pytest.mark.parametrize("task", TASKS)
def test_a_moved_object_is_found_again(task: str) -> None:
    ep = _episode(task, 0, moves=["random@0.4"])
    d = ep.disturbance
    assert d is not None and d.savable
    assert ep.success, ep.error


def test_a_lossy_blackboard_still_succeeds() -> None:
    ep = _episode(TASKS[0], 0, msg_loss=1.0, msg_delay=2.0)
    assert ep.success, ep.error
    assert ep.disturbance is not None and ep.disturbance.network.get("lost_releases", 0) >= 1


def test_a_joining_robot_gets_work() -> None:
    ep = _episode(TASKS[1], 0, join=["random@20%"])
    d = ep.disturbance
    assert ep.success and d is not None and d.joined
    assert d.joiner_actions >= 1


def test_a_joiner_far_from_the_work_is_still_given_some() -> None:
    # the plain replan leaves robot21b idle here (the team stands at the fridge already);
    # the executor asks for a plan in which the newcomer works
    ep = _episode(TASKS[0], 0, join=["random@30%"])
    d = ep.disturbance
    assert ep.success and d is not None and d.joined == ("robot21b",)
    assert d.joiner_actions >= 1


def test_same_seed_same_disturbed_episode() -> None:
    a = _episode(TASKS[0], 1, breakdown=["random@0.3"], moves=["random@0.5"])
    b = _episode(TASKS[0], 1, breakdown=["random@0.3"], moves=["random@0.5"])
    assert a.disturbance is not None and b.disturbance is not None
    assert a.disturbance.events == b.disturbance.events and a.success == b.success
    assert [e.model_dump() for e in a.trace if e.kind != "pose"] == [e.model_dump() for e in b.trace if e.kind != "pose"]


@pytest.mark.parametrize("mode", ["no-btc", "lamma-p", "smart-llm"])
def test_baselines_run_under_the_same_disturbance(mode: str) -> None:
    full = _episode(TASKS[0], 0, breakdown=["random@0.3"])
    other = _episode(TASKS[0], 0, mode=mode, breakdown=["random@0.3"])
    assert other.disturbance is not None and full.disturbance is not None
    # the same robot breaks down at the same time in every mode
    assert other.disturbance.events[0].detail == full.disturbance.events[0].detail
    assert other.disturbance.events[0].t == pytest.approx(full.disturbance.events[0].t)


# ---- where a random move puts things ------------------------------------------------------

def _moved_to(team: str, draws: int = 12) -> list[str]:
    """Where ``draws`` random moves of FloorPlan209's newspaper put it (each in a fresh
    simulator, keyed apart by ``draw``), as the ``moved`` events say."""
    details = []
    for i in range(draws):
        move = ObjectMove(object="Newspaper_1", at=1.0, into_closed=True, draw=f"t|{i}")
        sim = Simulator(load_scene("FloorPlan209"), parse_team(team.split(",")),
                        faults=FaultConfig(moves=(move,)), avoidance=True)
        sim.advance(2.0)
        details += [e.detail for e in sim.events if e.kind == "moved"]
    return details


def test_a_random_move_shuts_things_away_only_from_a_team_that_can_open() -> None:
    """fp209-floor-clutter's team (robots 25 and 24) cannot open anything: the newspaper
    was put in a drawer and the task became unsavable by the disturbance generator's
    doing. A person tidying puts things where they can be got back."""
    no_opener = _moved_to("25,24")
    assert len(no_opener) == 12 and not any("(closed" in d for d in no_opener), no_opener
    assert any("(closed" in d for d in _moved_to("25,1"))  # robot1 opens: drawers are fair game


def test_moved_objects_of_the_former_unsavable_draws_are_found_again() -> None:
    for task, seed in (("mace-thor/fp209-floor-clutter", 0), ("mace-thor/fp21-cup-of-water", 2),
                       ("mace-thor/fp414-rinse-cloth", 1)):
        ep = _episode(task, seed, moves=["random@0.5"])
        d = ep.disturbance
        assert d is not None and d.events and d.events[0].kind == "moved"
        assert d.savable and ep.success, (task, seed, ep.error)


def test_a_random_move_puts_nothing_behind_a_broken_robot() -> None:
    """FloorPlan5 with robot2 broken down in its one-cell doorway: the counters behind it
    are out of robot1's reach, so a person moving the apple puts it on robot1's side."""
    from test_sim_traffic import _doorway

    state, _door, robot1_side = _doorway()
    state.robots["robot2"].down = True
    places = []
    for i in range(12):
        move = ObjectMove(object="Apple_1", at=1.0, into_closed=True, draw=f"t|{i}")
        sim = Simulator(load_scene("FloorPlan5"), parse_team(["1", "2"]), state=state,
                        faults=FaultConfig(moves=(move,)), avoidance=True)
        sim.advance(2.0)
        places += [sim.state.objects["Apple_1"].parent for e in sim.events if e.kind == "moved"]
    assert len(places) == 12
    nav = sim.traffic.nav
    for place in places:
        p = sim.state.objects[place].position
        assert any(pose.cell in robot1_side for pose in nav.poses_for((p[0], p[2]))), place
