"""The team closes what it opens: a closed fridge a reading puts things into is closed
again, unless the words ask it open, it started open, or nobody can close it."""

from __future__ import annotations

from emboteam.config import RunConfig
from emboteam.pfg.close_after_use import close_after_use
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.pipeline import run_episode
from emboteam.task import Instruction
from emboteam.world.goals import Condition
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


def _spec(*goals: str) -> TaskSpec:
    return TaskSpec(instruction="x", subtasks=tuple(
        Subtask(id=f"s{i}", description=g, goal=(Condition.parse(g),)) for i, g in enumerate(goals, 1)))


def _state(team: str = "1,2") -> WorldState:
    return WorldState.from_scene(load_scene("FloorPlan1"), parse_team(team))


def test_a_closed_fridge_things_go_into_gets_a_closing_subtask_after_them() -> None:
    spec, notes = close_after_use(_spec("inside(Apple, Fridge)", "switched_off(LightSwitch)",
                                        "inside(Tomato, Fridge)"), _state(), parse_team("1,2"))
    added = spec.subtasks[-1]
    assert [str(c) for c in added.goal] == ["closed(Fridge)"]
    assert added.depends_on == ("s1", "s3")    # after both puts, not after the light
    assert len(spec.subtasks) == 4 and notes and "closed(Fridge)" in notes[0]


def test_taking_a_thing_out_of_the_fridge_also_comes_before_the_close() -> None:
    state = _state()
    inside = {state.objects[o.parent].type for o in state.objects.values() if o.type == "Egg" and o.parent}
    assert inside == {"Fridge"}    # FloorPlan1's egg starts in the fridge
    spec, _ = close_after_use(_spec("inside(Apple, Fridge)", "inside(Egg, CounterTop)"), state, parse_team("1,2"))
    assert spec.subtasks[-1].depends_on == ("s1", "s2")


def test_nothing_is_added_where_the_words_ask_it_open_or_closed_already() -> None:
    for goals in (("inside(Apple, Fridge)", "open(Fridge)"), ("inside(Apple, Fridge)", "closed(Fridge)"),
                  ("inside(Apple, CounterTop)",)):
        spec = _spec(*goals)
        assert close_after_use(spec, _state(), parse_team("1,2")) == (spec, [])


def test_nothing_is_added_for_a_team_that_cannot_close() -> None:
    team = parse_team("1,2")
    closers = [r for r in team]
    cannot = tuple(r.model_copy(update={"skills": frozenset(s for s in r.skills if s.value != "CloseObject")})
                   for r in closers)
    spec = _spec("inside(Apple, Fridge)")
    assert close_after_use(spec, _state(), cannot) == (spec, [])


def test_an_episode_closes_the_fridge_by_default_and_leaves_it_open_when_asked() -> None:
    task = Instruction.typed("put the apple in the fridge", "FloorPlan1", "1,2")
    closed = run_episode(task, RunConfig(frontend="offline"))
    assert closed.success and {c.condition for c in closed.conditions} == {"inside(Apple, Fridge)", "closed(Fridge)"}
    assert any("added closed(Fridge)" in n for n in closed.notes)
    left = run_episode(task, RunConfig(frontend="offline", close_after_use=False))
    assert left.success and {c.condition for c in left.conditions} == {"inside(Apple, Fridge)"}
    assert left.actions < closed.actions    # no walk back to the fridge to close it
