"""Clock times in a schedule ("9:00 apple into the fridge") are not counts (the idioms read
them as when): before, the digits after the colon were read as a count, and "00" asked for
zero things, which no condition can hold (a crash outside the reader's typed errors)."""

from __future__ import annotations

import pytest

from emboteam.pfg.offline import OfflineFrontend
from offline_reading import read_offline


@pytest.fixture(scope="module")
def frontend() -> OfflineFrontend:
    return OfflineFrontend()


def _goals(frontend: OfflineFrontend, text: str) -> set[str]:
    return {str(c) for c in read_offline(frontend, text, "FloorPlan1").spec.goal().conditions}


def test_a_schedule_of_clock_times_reads_each_entry_once(frontend: OfflineFrontend) -> None:
    assert _goals(frontend, "9:00 apple into the fridge, 9:30 switch the light off") == {
        "inside(Apple, Fridge)", "switched_off(LightSwitch)"}


def test_minutes_before_a_thing_are_no_count_of_it(frontend: OfflineFrontend) -> None:
    goals = read_offline(frontend, "at 7:15 one potato in the fridge", "FloorPlan1").spec.goal().conditions
    assert [(str(c), c.count) for c in goals] == [("inside(Potato, Fridge)", 1)]


def test_a_zero_asks_for_no_count(frontend: OfflineFrontend) -> None:
    assert _goals(frontend, "0 sugar in the mug please, just put the mug in the coffee machine") == {
        "inside(Mug, CoffeeMachine)"}


def test_a_goal_that_cannot_hold_is_the_readers_typed_error(frontend: OfflineFrontend,
                                                            monkeypatch: pytest.MonkeyPatch) -> None:
    """A count of zero (what "00" gave before) must come out as the reader's own error,
    which the CLI and the benchmark report, not as a pydantic crash."""
    from emboteam.pfg.offline import semantics
    from emboteam.pfg.offline.errors import OfflineParseError

    made = semantics.cond
    monkeypatch.setattr(semantics, "cond", lambda pred, ref, count=1, *rest, **kw: made(
        pred, ref.model_copy(update={"id": None}), 0, *rest, **kw))
    with pytest.raises(OfflineParseError, match="cannot hold"):
        read_offline(frontend, "put the apple into the fridge")
