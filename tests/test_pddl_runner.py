"""Fast Downward as a subprocess: exit codes, plan files, cache, parallel calls."""

from __future__ import annotations

from pathlib import Path

import pytest

from emboteam.pddl.domain import domain_pddl
from emboteam.pddl.errors import (
    PlannerInputError,
    PlannerLimitError,
    PlannerMemoryError,
    PlannerTimeoutError,
    PlanningError,
)
from emboteam.pddl.problem import build_problem
from emboteam.pddl.runner import FastDownward, PlanCache, SolveResult, driver_path, interpret
from emboteam.world.goals import Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


def problem_text(goal: str, team: str = "1", fp: str = "FloorPlan1") -> str:
    s = WorldState.from_scene(load_scene(fp), parse_team(team))
    return build_problem(s, Goal.parse(goal).conditions, list(s.robots)).text


def test_driver_is_found_in_the_installed_package() -> None:
    path = driver_path()
    assert path.name == "fast-downward.py" and path.is_file()


def test_a_solvable_problem_yields_a_plan() -> None:
    fd = FastDownward()
    result = fd.solve(domain_pddl(), problem_text("inside(Apple, Fridge)"))
    assert result.solved and result.exit_code == 0 and not result.cached
    assert any(line.startswith("(put robot1 apple_1 fridge_1") for line in result.plan)
    assert fd.calls == 1


def test_an_unsolvable_problem_is_reported_not_raised() -> None:
    text = problem_text("inside(Pot, Fridge)", team="7")  # robot7 lifts 0.08 kg
    result = FastDownward().solve(domain_pddl(), text)
    assert result.status == "unsolvable" and result.exit_code in (10, 11)
    assert "unsolvable" in result.message


def test_input_errors_carry_fast_downwards_words() -> None:
    with pytest.raises(PlannerInputError, match="exit 31"):
        FastDownward().solve(domain_pddl(), "(define (problem broken) (:domain emboteam-thor)")
    with pytest.raises(PlannerInputError, match="unknown alias"):
        FastDownward("no-such-alias").solve(domain_pddl(), problem_text("inside(Apple, Fridge)"))
    with pytest.raises(PlannerInputError, match="does not support"):
        FastDownward("seq-opt-lmcut").solve(domain_pddl(), problem_text("inside(Apple, Fridge)"))


def test_time_limit_is_a_typed_error() -> None:
    hard = problem_text("inside(Apple, Fridge) & sliced(Bread) & hot(Potato) & cold(Tomato) & "
                        "inside(Cup, Cabinet_1) & inside(Mug, Drawer_1) & broken(Vase) & open(Cabinet_5) & "
                        "filled(Bowl, water) & inside(Egg, Pan)", team="1,2,3,4")
    # with 1 s overall the driver leaves the translator no time: killed by its CPU limit
    with pytest.raises(PlannerTimeoutError, match="out of time"):
        FastDownward("astar(blind())", time_limit=1).solve(domain_pddl(), hard)


@pytest.mark.parametrize(("code", "error"), [
    (20, PlannerMemoryError), (22, PlannerMemoryError), (21, PlannerTimeoutError),
    (23, PlannerTimeoutError), (24, PlannerTimeoutError), (30, PlannerInputError),
    (32, PlannerInputError), (33, PlannerInputError), (34, PlannerInputError), (35, PlannerInputError),
    (36, PlannerInputError), (37, PlannerInputError), (99, PlannerInputError), (-9, PlannerLimitError),
    (247, PlannerLimitError), (232, PlannerTimeoutError), (-24, PlannerTimeoutError),
])
def test_exit_codes_map_to_typed_errors(code: int, error: type[PlanningError]) -> None:
    with pytest.raises(error):
        interpret(code, None, "planner said so")


@pytest.mark.parametrize("code", [0, 1, 2, 3])
def test_plan_found_codes_are_solved(code: int) -> None:
    assert interpret(code, ("(goto robot1 apple_1)",), "").solved
    with pytest.raises(PlannerInputError, match="without a plan file"):
        interpret(code, None, "")


@pytest.mark.parametrize("code", [10, 11, 12, 13])
def test_unsolvable_codes(code: int) -> None:
    assert interpret(code, None, "").status == "unsolvable"


def test_cache_in_memory_and_on_disk(tmp_path: Path) -> None:
    text = problem_text("sliced(Bread)")
    first = FastDownward(cache=PlanCache(tmp_path))
    a = first.solve(domain_pddl(), text)
    b = first.solve(domain_pddl(), text)
    assert first.calls == 1 and first.cache_hits == 1 and b.cached and b.plan == a.plan
    second = FastDownward(cache=PlanCache(tmp_path))  # a new process would see the same files
    c = second.solve(domain_pddl(), text)
    assert second.calls == 0 and c.cached and c.plan == a.plan
    other = FastDownward("astar(hmax())", cache=PlanCache(tmp_path))  # the configuration is in the key
    other.solve(domain_pddl(), text)
    assert other.calls == 1


def test_parallel_calls_keep_job_order_and_report_errors_in_place() -> None:
    fd = FastDownward()
    jobs = [(domain_pddl(), problem_text("inside(Apple, Fridge)")),
            (domain_pddl(), "(define (problem broken)"),
            (domain_pddl(), problem_text("switched_off(LightSwitch)"))]
    results = fd.solve_many(jobs, workers=2)
    assert isinstance(results[0], SolveResult) and any("apple_1" in x for x in results[0].plan)
    assert isinstance(results[1], PlannerInputError)
    assert isinstance(results[2], SolveResult) and any("lightswitch_1" in x for x in results[2].plan)


def test_limits_must_be_positive() -> None:
    with pytest.raises(PlannerInputError):
        FastDownward(time_limit=0)


def test_anytime_plans_found_before_a_limit_are_kept() -> None:
    result = interpret(23, ("(goto robot1 apple_1)",), "")
    assert result.solved and result.exit_code == 23 and "before the limit" in result.message
