"""Readings checked by the planner (issue 25): a reading the planner refuses gives way to
its next candidate that plans, else to its largest part that plans, and nothing is
dropped silently (``not_attempted`` in the episode and ``--json``, exit 1 for a partly
done job); a self-correction between two opposed requests is a choice, not an error."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from emboteam.config import RunConfig
from emboteam.exec.episode import Episode
from emboteam.hp.feasible import MAX_CANDIDATES, plan_feasible
from emboteam.hp.plan import MergedPlan
from emboteam.pddl.errors import PlannerTimeoutError, UnsolvableSubtaskError
from emboteam.pfg.candidates import Candidate
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.consistency import ContradictoryInstruction
from emboteam.pfg.reading import Reading
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.pipeline import run_episode
from emboteam.task import Instruction
from emboteam.world.goals import Condition
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
from pty_run import run_on_terminal

SRC = Path(__file__).resolve().parents[1] / "src"
#: the mug cannot go in the bowl in FloorPlan1 (the planner proves it); the fridge can open
PART = "Put the mug in the bowl and open the fridge."
#: read as "the vase in the box" too, which no robot can reach; the next reading plans
NEXT = "Statue in the box, both vases stay where they are."
#: one object placed twice in one breath, "actually" after it: a self-correction
CORRECTED = "Put the tomato in the fridge and put the tomato in the sink, actually."


def _episode(text: str, floor_plan: str = "FloorPlan1") -> Episode:
    return run_episode(Instruction.typed(text, floor_plan, "1,2"), RunConfig(mode="full", frontend="offline"))


def _cli(*args: str, stdin: int | None = None) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(SRC), "COLUMNS": "200"}
    return subprocess.run([sys.executable, "-m", "emboteam", *args], env=env, capture_output=True, text=True,
                          stdin=stdin if stdin is not None else subprocess.DEVNULL, timeout=300)


def _read(text: str, floor_plan: str = "FloorPlan1") -> Reading:
    scene = load_scene(floor_plan)
    team = parse_team("1,2")
    return OfflineFrontend().parse(text, scene, WorldState.from_scene(scene, team), team)


# ---- the planner's refusal is no longer the end ----------------------------------------------

@pytest.fixture(scope="module")
def part() -> Episode:
    return _episode(PART)


def test_a_reading_the_planner_refuses_runs_its_plannable_part_and_says_what_was_left(part: Episode) -> None:
    assert part.error is None
    assert [n.condition for n in part.not_attempted] == ["inside(Mug, Bowl)"]
    assert "UnsolvableSubtaskError" in part.not_attempted[0].reason
    held = {c.condition: c.holds for c in part.conditions}
    assert held == {"open(Fridge)": True, "inside(Mug, Bowl)": False}   # scored on all it asked
    assert not part.success and part.actions > 0
    assert any(n.startswith("unsure (planning)") for n in part.notes)


def test_the_report_page_gets_what_was_not_attempted(part: Episode) -> None:
    from emboteam.report.episode_report import episode_view, render_episode_report

    assert episode_view(part)["meta"]["not_attempted"][0]["condition"] == "inside(Mug, Bowl)"
    assert "Not attempted (the planner could not plan it)" in render_episode_report(part)


def test_the_same_input_gives_the_same_outcome_twice(part: Episode) -> None:
    again = _episode(PART)
    assert again.not_attempted == part.not_attempted
    assert again.taskspec == part.taskspec and again.notes == part.notes
    assert again.conditions == part.conditions
    assert again.plan is not None and part.plan is not None and again.plan.steps == part.plan.steps


def test_a_lower_candidate_that_plans_is_taken_when_the_first_cannot_be_planned() -> None:
    episode = _episode(NEXT, "FloorPlan211")
    assert episode.error is None and episode.not_attempted == ()
    assert episode.candidates[0]["goals"] == ["inside(Statue, Box)", "inside(Vase, Box)"]
    assert any("took the next reading that plans, candidate 2: The statue is in the box." in n
               for n in episode.notes)
    assert episode.taskspec is not None and [str(c) for c in episode.taskspec.goal().conditions] == \
        ["inside(Statue, Box)"]
    assert episode.success


def test_when_nothing_of_the_reading_plans_its_typed_error_stands() -> None:
    episode = _episode("Put the mug in the bowl.")
    assert episode.error is not None and episode.error.startswith("UnsolvableSubtaskError")
    assert episode.not_attempted == ()


# ---- the fallback's order, on a planner that answers by rule ---------------------------------

def _spec(*conds: str) -> TaskSpec:
    return TaskSpec(instruction="x", subtasks=tuple(Subtask(id=f"s{i}", description=c, goal=(Condition.parse(c),))
                                                    for i, c in enumerate(conds, 1)))


def _planner(refuse: set[frozenset[str]], calls: list[frozenset[str]]):
    """Refuses exactly the goals in ``refuse`` (as the planner would, typed), plans the rest."""
    def plan(spec: TaskSpec) -> MergedPlan:
        goal = frozenset(str(c) for c in spec.goal().conditions)
        calls.append(goal)
        if goal in refuse:
            raise UnsolvableSubtaskError("no plan", subtask="joint")
        return MergedPlan(robots=("robot1",), steps=())
    return plan


def test_conditions_that_plan_alone_but_not_together_leave_out_the_unsure_one_first() -> None:
    spec = _spec("open(Fridge)", "held(Pen)", "closed(Box)")
    calls: list[frozenset[str]] = []
    whole = frozenset({"open(Fridge)", "held(Pen)", "closed(Box)"})
    found = plan_feasible(spec, _planner({whole}, calls), unsure=("held(Pen)",))
    assert [n.condition for n in found.not_attempted] == ["held(Pen)"]
    assert "not together" in found.not_attempted[0].reason
    assert {str(c) for c in found.spec.goal().conditions} == {"open(Fridge)", "closed(Box)"}
    assert {str(c) for c in found.requested.goal().conditions} == whole


def test_the_next_candidates_are_tried_best_first_and_at_most_a_few() -> None:
    spec = _spec("open(Fridge)")
    others = [Candidate(goals=(Condition.parse(f"open(Cabinet_{i})"),), sentence=f"c{i}", score=-i,
                        spec=_spec(f"open(Cabinet_{i})")) for i in range(1, MAX_CANDIDATES + 3)]
    refused = {frozenset({"open(Fridge)"})} | {frozenset({f"open(Cabinet_{i})"}) for i in range(1, MAX_CANDIDATES + 3)}
    calls: list[frozenset[str]] = []
    with pytest.raises(UnsolvableSubtaskError):
        plan_feasible(spec, _planner(refused, calls), others)
    tried = [c for c in calls if c != frozenset({"open(Fridge)"})]
    assert tried == [frozenset({f"open(Cabinet_{i})"}) for i in range(1, MAX_CANDIDATES + 1)]


def test_a_time_out_on_the_whole_goal_is_a_reason_to_plan_a_part() -> None:
    spec = _spec("open(Fridge)", "closed(Box)")

    def plan(s: TaskSpec) -> MergedPlan:
        if len(s.goal().conditions) > 1:
            raise PlannerTimeoutError("Fast Downward: search out of time")
        return MergedPlan(robots=("robot1",), steps=())
    found = plan_feasible(spec, plan)
    assert len(found.not_attempted) == 1 and "PlannerTimeoutError" in found.not_attempted[0].reason


def test_after_two_time_outs_no_more_candidates_are_tried() -> None:
    spec = _spec("open(Fridge)")
    others = [Candidate(goals=(Condition.parse(f"open(Cabinet_{i})"),), sentence=f"c{i}", score=-i,
                        spec=_spec(f"open(Cabinet_{i})")) for i in (1, 2)]
    calls: list[str] = []

    def plan(s: TaskSpec) -> MergedPlan:
        calls.append(str(s.goal().conditions[0]))
        raise PlannerTimeoutError("Fast Downward: search out of time")
    with pytest.raises(PlannerTimeoutError):
        plan_feasible(spec, plan, others)
    assert calls == ["open(Fridge)", "open(Cabinet_1)"]


# ---- the command line ---------------------------------------------------------------------------

def test_run_json_lists_what_was_not_attempted_and_exits_1() -> None:
    done = _cli("run", PART, "--scene", "FloorPlan1", "--robots", "1,2", "--json")
    assert done.returncode == 1, done.stderr
    payload = json.loads(done.stdout)
    assert [n["condition"] for n in payload["not_attempted"]] == ["inside(Mug, Bowl)"]
    assert payload["exit_code"] == 1 and payload["error_type"] is None
    assert "not attempted: inside(Mug, Bowl)" in payload["error"]
    assert payload["actions"] > 0      # the feasible part ran


def test_run_panel_and_plan_say_what_was_not_attempted() -> None:
    done = _cli("run", PART, "--scene", "FloorPlan1", "--robots", "1,2")
    assert done.returncode == 1
    assert "not attempted (the planner could not plan it)" in done.stdout
    planned = _cli("plan", PART, "--scene", "FloorPlan1", "--robots", "1,2", "--json")
    assert planned.returncode == 1
    assert json.loads(planned.stdout)["not_attempted"][0]["condition"] == "inside(Mug, Bowl)"


def test_a_run_that_did_everything_lists_nothing_not_attempted() -> None:
    done = _cli("run", "Open the fridge.", "--scene", "FloorPlan1", "--robots", "1,2", "--json")
    assert done.returncode == 0
    assert json.loads(done.stdout)["not_attempted"] == []


# ---- a self-correction between two opposed requests: a choice -----------------------------------

@pytest.mark.parametrize("text", [CORRECTED, "Put the tomato in the fridge and put the tomato in the sink instead."])
def test_a_corrected_place_keeps_the_later_and_offers_the_earlier(text: str) -> None:
    reading = _read(text)
    assert [str(c) for c in reading.spec.goal().conditions] == ["inside(Tomato, SinkBasin)"]
    assert "inside(Tomato, SinkBasin)" in reading.unsure
    earlier = [c for c in reading.candidates if [str(g) for g in c.goals] == ["inside(Tomato, Fridge)"]]
    assert earlier and any(r.kind == "correction" and r.label == "keep_first" for r in earlier[0].resolves)


def test_a_corrected_state_offers_the_earlier_state() -> None:
    reading = _read("Switch the light off and switch the light on, sorry.")
    assert [str(c) for c in reading.spec.goal().conditions] == ["switched_on(LightSwitch)"]
    assert any([str(g) for g in c.goals] == ["switched_off(LightSwitch)"] for c in reading.candidates)


def test_a_condition_is_no_self_correction_its_stated_state_is_no_candidate() -> None:
    reading = _read("If the desk lamp is still on, it should be switched off.", "FloorPlan315")
    assert [str(c) for c in reading.spec.goal().conditions] == ["switched_off(DeskLamp)"]
    assert not any("switched_on(DeskLamp)" in map(str, c.goals) for c in reading.candidates)


@pytest.mark.parametrize("text", ["put the apple in the fridge and put the apple in the sink",
                                  "Open and close the fridge."])
def test_two_requests_said_with_the_same_weight_are_still_refused(text: str) -> None:
    with pytest.raises(ContradictoryInstruction):
        _read(text)


def test_clarify_without_a_terminal_takes_the_later_request_and_says_so() -> None:
    done = _cli("run", CORRECTED, "--scene", "FloorPlan1", "--robots", "1,2", "--clarify")
    assert done.returncode == 0, done.stderr
    text = " ".join(done.stdout.split())
    assert "no terminal to ask on" in text and "The tomato is in the sink." in text


def test_clarify_on_a_terminal_asks_between_the_two_requests() -> None:
    """``run --clarify`` through a pseudo-terminal: the person picks the earlier request."""
    text, returncode = run_on_terminal(["run", CORRECTED, "--scene", "FloorPlan1", "--robots", "1,2", "--clarify"],
                                       b"2\n")
    assert "1. The tomato is in the sink." in text and "2. The tomato is in the fridge." in text
    assert "chosen by the person: The tomato is in the fridge." in text
    assert returncode == 0
