"""``condition_holds`` (the planner's check without the report) answers as
``check_condition(...).holds`` does, on states where goals hold and where they do not."""

from __future__ import annotations

from emboteam.hp.goalgen import sweep_cell
from emboteam.world.checker import check_condition, condition_holds
from emboteam.world.goals import Condition, ObjectRef, Predicate
from emboteam.world.state import WorldState


def _by_type(state: WorldState) -> list[Condition]:
    """Type-level conditions with counts 1-3 on the state's own types (several objects of
    a type: the count decides)."""
    types = sorted({o.type for o in state.objects.values()})
    out = []
    for t in types:
        for pred in (Predicate.open, Predicate.closed, Predicate.switched_off, Predicate.dirty, Predicate.clean):
            out += [Condition(predicate=pred, subject=ObjectRef(types=(t,)), count=n) for n in (1, 2, 3)]
    out += [Condition(predicate=Predicate.inside, subject=ObjectRef(types=(t,)),
                      receptacle=ObjectRef(types=("CounterTop",)), count=n) for t in types for n in (1, 2)]
    return out


def _changed(state: WorldState) -> WorldState:
    """The state with every openable open and every other object's dirt washed off."""
    s = state.copy()
    for o in s.objects.values():
        if o.has("openable"):
            o.is_open = True
        else:
            o.is_dirty = False
    return s


def test_condition_holds_answers_as_the_report_does() -> None:
    answers = set()
    for scene in ("FloorPlan1", "FloorPlan201"):
        spec, state = sweep_cell(scene, 4, 32, 0)
        conditions = [*spec.goal().conditions, *_by_type(state)]
        for s in (state, _changed(state)):
            for c in conditions:
                expected = check_condition(c, s).holds
                assert condition_holds(c, s) is expected, (scene, str(c))
                answers.add(expected)
    assert answers == {True, False}
