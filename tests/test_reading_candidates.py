"""Readings as a choice (issue 25, items 1-3 and 5): points of doubt, ranked candidates,
unexplained mentions, the priors file, and ``emboteam run --clarify`` on a terminal."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.priors import Priors, PriorsError, load_priors
from emboteam.pfg.ranker import apply_choices, rank
from emboteam.pfg.sentences import sentence
from emboteam.world.goals import Condition, Goal
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState
from offline_reading import read_offline
from pty_run import run_on_terminal

SRC = Path(__file__).resolve().parents[1] / "src"


@pytest.fixture(scope="module")
def frontend() -> OfflineFrontend:
    return OfflineFrontend()


def _read(frontend: OfflineFrontend, text: str, floor_plan: str = "FloorPlan1"):
    return read_offline(frontend, text, floor_plan, team="1,2")


def test_first_candidate_is_the_reading_and_every_candidate_is_complete(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "put the apple in the fridge, no, on the counter")
    assert reading.candidates[0].spec == reading.spec
    assert reading.candidates[0].as_read
    assert [str(c) for c in reading.spec.goal().conditions] == ["inside(Apple, CounterTop)"]
    goals = {frozenset(str(c) for c in cand.goals) for cand in reading.candidates}
    # the rejected side of the self-correction is one of the readings considered
    assert frozenset({"inside(Apple, Fridge)"}) in goals
    assert len(reading.candidates) <= load_priors().max_candidates
    scores = [c.score for c in reading.candidates]
    assert scores == sorted(scores, reverse=True)


def test_candidates_say_their_end_state_in_english(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "warm the bread")
    sentences = [c.sentence for c in reading.candidates]
    assert sentences[0] == "The bread is hot."
    assert "The bread is cooked." in sentences
    other = next(c for c in reading.candidates if not c.as_read)
    assert other.resolves[0].kind == "state"


def test_an_unexplained_mention_is_listed_and_proposes_goals(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "Put the apple in the fridge. Thanks, and the tomato!")
    assert reading.unexplained == ("tomato",)
    assert reading.doubtful
    proposed = {str(c) for cand in reading.candidates for c in cand.goals}
    assert "inside(Tomato, Fridge)" in proposed


def test_places_negations_and_goals_explain_a_mention(frontend: OfflineFrontend) -> None:
    reading = _read(frontend, "take the apple from the counter and put it in the fridge, but not the egg")
    assert reading.unexplained == ()


def test_infeasible_alternatives_are_not_candidates(frontend: OfflineFrontend) -> None:
    scene = load_scene("FloorPlan1")
    team = parse_team("1,2")
    state = WorldState.from_scene(scene, team)
    spec = frontend.parse("slice the apple", scene, state, team).spec
    bad = Condition.parse("inside(Fridge, Apple)")      # a fridge in an apple: the checker refuses it
    doubt = Doubt("state", "apple", (Choice(AS_READ, "as read"), Choice("odd", "odd", add=(bad,))))
    priors = Priors(priors={"state": {AS_READ: 0.1, "odd": 0.9}})

    def feasible(goals: tuple[Condition, ...]) -> bool:
        from emboteam.pfg.offline.doubts.check import feasible as check
        return check(goals, scene, state, team)

    ranked = rank(spec, [doubt], priors, feasible)
    assert [c.as_read for c in ranked] == [True]


def test_an_alternative_that_asks_a_state_and_its_opposite_is_not_a_candidate(frontend: OfflineFrontend) -> None:
    """A doubt that adds "the light on" to a reading that switches it off makes a goal no
    plan can reach (found on a development round: the model then picked it)."""
    scene = load_scene("FloorPlan1")
    team = parse_team("1,2")
    state = WorldState.from_scene(scene, team)
    spec = frontend.parse("switch off the light", scene, state, team).spec
    on = Condition.parse("switched_on(LightSwitch)")
    doubt = Doubt("state", "light", (Choice(AS_READ, "as read"), Choice("on too", "on", add=(on,))))
    priors = Priors(priors={"state": {AS_READ: 0.1, "on too": 0.9}})

    def feasible(goals: tuple[Condition, ...]) -> bool:
        from emboteam.pfg.offline.doubts.check import feasible as check
        return check(goals, scene, state, team)

    assert feasible((on,))                                      # alone, the state is fine
    ranked = rank(spec, [doubt], priors, feasible)
    assert [c.as_read for c in ranked] == [True]


def test_priors_decide_the_order_and_the_reading_changes_only_for_them(frontend: OfflineFrontend) -> None:
    scene = load_scene("FloorPlan1")
    team = parse_team("1,2")
    state = WorldState.from_scene(scene, team)
    spec = frontend.parse("warm the bread", scene, state, team).spec
    hot, cooked = Condition.parse("hot(Bread)"), Condition.parse("cooked(Bread)")
    doubt = Doubt("state", "warm", (Choice(AS_READ, "hot"), Choice("hot->cooked", "cooked", drop=(hot,),
                                                                     add=(cooked,))))
    always = lambda goals: True  # noqa: E731
    keep = rank(spec, [doubt], Priors(priors={"state": {AS_READ: 0.8, "hot->cooked": 0.2}}), always)
    swap = rank(spec, [doubt], Priors(priors={"state": {AS_READ: 0.2, "hot->cooked": 0.8}}), always)
    assert keep[0].goals == (hot,) and swap[0].goals == (cooked,)
    assert Goal(conditions=swap[0].spec.goal().conditions) == Goal(conditions=(cooked,))


def test_apply_choices_refuses_clashing_edits() -> None:
    a = Condition.parse("hot(Bread)")
    drop = Choice("x", "x", drop=(a,))
    assert apply_choices((a,), [drop]) == ()
    assert apply_choices((a,), [drop, drop]) is None


def test_sentence_reads_as_an_end_state() -> None:
    goals = [Condition.parse(t) for t in ("inside(Apple, CounterTop)", "switched_off(LightSwitch)",
                                          "inside(2 of Statue, CoffeeTable)")]
    assert sentence(goals) == ("The apple is on the counter, the light switch is off and two statues are on "
                               "the coffee table.")


def test_a_malformed_priors_file_names_file_and_entry(tmp_path: Path) -> None:
    path = tmp_path / "priors.json"
    path.write_text(json.dumps({"priors": {"state": {"as_read": 1.5}}}))
    with pytest.raises(PriorsError, match=r"priors\.json: entry priors\.state\.as_read"):
        load_priors(path)
    path.write_text(json.dumps({"max_candidates": 20}))
    with pytest.raises(PriorsError, match="entry max_candidates"):
        load_priors(path)


def test_shipped_priors_are_fitted_on_development_data_only() -> None:
    fitted = load_priors().fitted_on
    assert fitted and all(r.startswith(("blind_r", "offline_dev")) for r in fitted)
    assert not any(r in ("blind_r42", "unseen_tasks", "offline_heldout") for r in fitted)


_CLOSE = "The teddy bear goes on the desk; leave the pillow on the bed."


def _run(*extra: str, stdin: int | None = None) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    return subprocess.run([sys.executable, "-m", "emboteam", "run", _CLOSE, "--scene", "FloorPlan306",
                           "--robots", "1,2", *extra], env=env, capture_output=True, text=True,
                          stdin=stdin if stdin is not None else subprocess.DEVNULL, timeout=300)


def test_clarify_without_a_terminal_takes_the_best_and_says_so() -> None:
    done = _run("--clarify")
    assert done.returncode == 0, done.stderr
    assert "no terminal to ask on" in " ".join(done.stdout.split())


def test_run_json_lists_candidates_with_scores() -> None:
    done = _run("--clarify", "--json")
    payload = json.loads(done.stdout)
    assert len(payload["candidates"]) >= 2
    assert payload["candidates"][0]["as_read"] and "score" in payload["candidates"][0]
    assert all(c["sentence"].endswith(".") for c in payload["candidates"])


def test_clarify_on_a_terminal_asks_and_uses_the_choice() -> None:
    """Drives ``run --clarify`` through a pseudo-terminal: the person types 2."""
    text, returncode = run_on_terminal(["run", _CLOSE, "--scene", "FloorPlan306", "--robots", "1,2", "--clarify"],
                                       b"2\n")
    assert "1. The teddy bear is on the desk and the pillow is on the bed." in text
    assert "2. The teddy bear is on the desk." in text
    assert "chosen by the person: The teddy bear is on the desk." in text
    assert returncode == 0


@pytest.mark.parametrize(("text", "floor_plan", "kind", "alternative"), [
    ("heat the potato in the microwave", "FloorPlan1", "means", {"hot(Potato)", "inside(Potato, Microwave)"}),
    ("make me a coffee", "FloorPlan1", "means", {"filled(Mug, coffee)", "inside(Mug, CoffeeMachine)"}),
    ("leave the tomato where it is and put the apple in the fridge", "FloorPlan1", "mention_cue",
     {"inside(Apple, Fridge)", "inside(Tomato, CounterTop)"}),
    ("turn off the lamp", "FloorPlan201", "scene_type", {"switched_off(FloorLamp)"}),
    ("put the apple in the fridge, no, on the counter", "FloorPlan1", "correction", {"inside(Apple, Fridge)"}),
    ("warm the bread", "FloorPlan1", "state", {"cooked(Bread)"}),
    ("Put the apple in the fridge. Thanks, and the tomato!", "FloorPlan1", "unexplained_mention",
     {"inside(Apple, Fridge)", "inside(Tomato, Fridge)"}),
])
def test_each_kind_of_doubt_offers_its_alternative(frontend: OfflineFrontend, text: str, floor_plan: str,
                                                   kind: str, alternative: set[str]) -> None:
    reading = _read(frontend, text, floor_plan)
    offered = [c for c in reading.candidates if {str(g) for g in c.goals} == alternative]
    assert offered, [c.sentence for c in reading.candidates]
    assert kind in {r.kind for r in offered[0].resolves}
    assert reading.candidates[0].spec == reading.spec
