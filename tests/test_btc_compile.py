"""The compiler's tree: the paper's anatomy, memory semantics, root policy, sync and lock
protocol, and typed errors for plans that cannot become trees."""

from __future__ import annotations

import py_trees
import pytest

from emboteam.btc.blueprint import blueprint, checked_pre
from emboteam.btc.compiler import compile_plan
from emboteam.btc.errors import PlanCompileError
from emboteam.btc.keys import flag_key, lock_key
from emboteam.btc.nodes import (
    Act,
    Attempts,
    EffectsObserved,
    FlagSet,
    HoldsSpot,
    IsolateBranch,
    LiteralsHold,
    RecoverLoop,
    ReleaseSpots,
    SignalDone,
)
from emboteam.btc.recovery import Strategy
from emboteam.hp.plan import MergedPlan, PlanStep, SyncPoint
from emboteam.pddl.literal import Literal
from test_btc_plans import act, fresh_state, fridge_handoff, make_plan, salad

Seq = py_trees.composites.Sequence
Sel = py_trees.composites.Selector


def _compile(plan: MergedPlan, team: str = "1,2"):  # type: ignore[no-untyped-def]
    return compile_plan(plan, state=fresh_state("FloorPlan1", team))


def test_root_is_a_synchronised_success_on_all_parallel_of_isolated_branches() -> None:
    plan, _ = salad()
    tree = _compile(plan, "1,2,3")
    try:
        root = tree.root
        assert isinstance(root, py_trees.composites.Parallel)
        assert isinstance(root.policy, py_trees.common.ParallelPolicy.SuccessOnAll)
        assert root.policy.synchronise  # finished branches are never re-ticked
        assert [c.name for c in root.children] == [f"isolate {r}" for r in plan.robots]
        for robot, child in zip(plan.robots, root.children, strict=True):
            assert isinstance(child, IsolateBranch)
            branch = child.decorated
            assert isinstance(branch, Seq) and branch.memory
            assert [c.name.split()[0] for c in branch.children] == [s.id for s in plan.for_robot(robot)]
    finally:
        tree.close()


def test_each_action_is_sequence_of_fallback_pre_recover_core_post() -> None:
    plan, _ = fridge_handoff()
    tree = _compile(plan)
    try:
        step = tree.steps["robot2.2"]  # PickupObject(Apple_1)
        assert isinstance(step, Seq) and step.memory
        attempts = step.children[0]
        assert isinstance(attempts, Attempts)
        action = attempts.decorated
        assert isinstance(action, Seq) and action.memory
        fallback, core, post = action.children
        assert isinstance(fallback, Sel) and not fallback.memory  # reactive: Pre re-checked
        pre, recover = fallback.children
        assert isinstance(pre, Seq) and not pre.memory
        assert isinstance(recover, RecoverLoop)
        assert isinstance(recover.decorated, Sel) and recover.decorated.memory
        assert isinstance(core, Act) and core.btcpp_id == "PickupObject"
        assert isinstance(post, EffectsObserved)
        lits = next(n for n in pre.children if isinstance(n, LiteralsHold)).literals
        assert Literal(predicate="at", args=("robot2", "Apple_1")) in lits
        assert Literal(predicate="holding", args=("robot2", "Apple_1")) in post.literals
    finally:
        tree.close()


def test_recovery_subtrees_follow_the_skill() -> None:
    plan, _ = fridge_handoff()
    bp = blueprint(plan, fresh_state("FloorPlan1", "1,2"))
    drive = bp.steps["robot2.1"].strategies
    put = bp.steps["robot2.4"].strategies
    assert Strategy.RETRY in drive and Strategy.OPEN not in drive
    assert {Strategy.REAPPROACH, Strategy.OPEN, Strategy.FREE_HAND, Strategy.REGRASP, Strategy.WAIT_SPOT,
            Strategy.RETRY, Strategy.WAIT_SYNC, Strategy.ACQUIRE_SPOT} <= set(put)
    tree = _compile(plan)
    try:
        names = [c.name for c in tree.steps["robot2.4"].children[0].decorated.children[0].children[1]
                 .decorated.children]
        assert names[:2] == ["wait for sync", "acquire spots"]
        assert {"re-approach", "open receptacle", "free the hand", "re-grasp", "retry"} <= set(names)
        assert names[-1] == "give up"
    finally:
        tree.close()


def test_sync_producer_signals_and_consumer_waits() -> None:
    plan, _ = fridge_handoff()
    tree = _compile(plan)
    try:
        consumer = tree.steps["robot2.4"]
        flags = [n for n in consumer.iterate() if isinstance(n, FlagSet)]
        assert [f.producer for f in flags] == ["robot1.2"]
        producer = tree.steps["robot1.2"]
        assert any(isinstance(n, SignalDone) and n.step_id == "robot1.2" for n in producer.children)
        # a step nobody waits for writes no flag
        assert not any(isinstance(n, SignalDone) for n in tree.steps["robot2.1"].children)
    finally:
        tree.close()


def test_sync_points_count_as_dependencies() -> None:
    plan, _ = fridge_handoff()
    steps = [s.model_copy(update={"after": ()}) for s in plan.steps]
    plan2 = MergedPlan(robots=plan.robots, steps=tuple(steps),
                       sync=(SyncPoint(producer="robot1.2", consumer="robot2.4"),))
    bp = blueprint(plan2)
    assert bp.steps["robot2.4"].waits == ("robot1.2",)
    assert bp.steps["robot1.2"].signals


def test_lock_runs_acquire_before_driving_and_release_after_the_last_step_there() -> None:
    plan, _ = fridge_handoff()
    bp = blueprint(plan, fresh_state("FloorPlan1", "1,2"))
    s = bp.steps
    # robot1 reserves the fridge before driving to it, keeps it to open, then lets go
    assert s["robot1.1"].holds == ("Fridge_1",) and s["robot1.1"].releases == ()
    assert s["robot1.2"].holds == ("Fridge_1",) and s["robot1.2"].releases == ("Fridge_1",)
    # robot1's close waits for robot2: a new run, so it never waits while holding the fridge
    assert s["robot1.3"].holds == ("Fridge_1",) and s["robot1.3"].releases == ("Fridge_1",)
    # robot2's drive to the fridge leads to a put that must wait: it drives unreserved
    assert s["robot2.3"].holds == ()
    assert s["robot2.4"].holds == ("Fridge_1",) and s["robot2.4"].releases == ("Fridge_1",)
    assert s["robot2.1"].holds == s["robot2.2"].holds == ("Apple_1",)
    tree = _compile(plan)
    try:
        assert any(isinstance(n, HoldsSpot) and n.spot == "Fridge_1" for n in tree.steps["robot1.1"].iterate())
        rel = [n for n in tree.steps["robot1.2"].children if isinstance(n, ReleaseSpots)]
        assert rel and rel[0].spots == ("Fridge_1",)
        assert not any(isinstance(n, ReleaseSpots) for n in tree.steps["robot1.1"].children)
    finally:
        tree.close()


def test_planner_resources_override_the_prediction() -> None:
    state = fresh_state("FloorPlan1", "1")
    plan = make_plan(state, {"robot1": [act("GoToObject", "Apple_1"), act("PickupObject", "Apple_1")]},
                     resources={"robot1.2": ["CounterTop_2"]})
    bp = blueprint(plan, state)
    assert bp.steps["robot1.1"].holds == ("CounterTop_2",) == bp.steps["robot1.2"].holds


def test_pre_skips_literals_the_step_itself_negates() -> None:
    step = PlanStep(id="r.1", robot="robot1", action=act("OpenObject", "Fridge_1"), subtask="s",
                    pre=(Literal(predicate="at", args=("robot1", "Fridge_1")),
                         Literal(predicate="is-open", args=("Fridge_1",), positive=False)),
                    post=(Literal(predicate="is-open", args=("Fridge_1",)),))
    assert checked_pre(step) == (Literal(predicate="at", args=("robot1", "Fridge_1")),)


def test_blackboard_access_is_declared_per_robot() -> None:
    plan, _ = fridge_handoff()
    tree = _compile(plan)
    try:
        board = tree.runtime.board
        # the consumer may read but not write the producer's flag
        assert board.client("robot2").is_registered(key=flag_key("robot1.2"),
                                                   access=py_trees.common.Access.READ)
        with pytest.raises(AttributeError):
            board.write("robot2", flag_key("robot1.2"), True)
        assert board.client("robot1").is_registered(key=lock_key("Fridge_1"))
    finally:
        tree.close()
    # closing clears the namespace from the process-global blackboard
    assert not [k for k in py_trees.blackboard.Blackboard.storage if k.startswith(board.namespace + "/")]
    other = _compile(plan)
    assert board.namespace != other.runtime.board.namespace  # one namespace per tree
    other.close()


@pytest.mark.parametrize(("mutate", "message"), [
    (lambda s: s.model_copy(update={"after": ("robot9.9",)}) if s.id == "robot2.4" else s, "unknown step"),
    (lambda s: s.model_copy(update={"after": ("robot1.3",)}) if s.id == "robot2.4" else s, "cycle"),
    (lambda s: s.model_copy(update={"pre": (Literal(predicate="levitating", args=("Apple_1",)),)})
     if s.id == "robot2.2" else s, "unknown PDDL predicate"),
    (lambda s: s.model_copy(update={"robot": "robot7"}) if s.id == "robot2.4" else s, "not in the plan's robots"),
])
def test_bad_plans_raise_typed_errors(mutate, message) -> None:  # type: ignore[no-untyped-def]
    plan, _ = fridge_handoff()
    bad = MergedPlan(robots=plan.robots, steps=tuple(mutate(s) for s in plan.steps))
    with pytest.raises(PlanCompileError, match=message):
        compile_plan(bad)


def test_plan_robot_missing_from_the_team_is_an_error() -> None:
    plan, _ = fridge_handoff()
    with pytest.raises(PlanCompileError, match="not in the team"):
        compile_plan(plan, state=fresh_state("FloorPlan1", "1"))
