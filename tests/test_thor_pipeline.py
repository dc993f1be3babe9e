"""``--env ai2thor`` through the whole pipeline (plan, behavior trees, executor), with the
Unity process replaced by the recording double: the wiring, not AI2-THOR's physics."""

from __future__ import annotations

from typing import Any

import pytest

pytest.importorskip("ai2thor.server")

from emboteam.bench.suites import get_task
from emboteam.pipeline import RunConfig
from emboteam.thor import session
from thor_unity_double import UnityDouble


@pytest.fixture
def unity(monkeypatch: pytest.MonkeyPatch) -> list[UnityDouble]:
    started: list[UnityDouble] = []

    def controller_for(floor_plan: str, agent_count: int) -> Any:
        started.append(UnityDouble(floor_plan, agent_count))
        return started[-1]

    monkeypatch.setattr(session, "controller_for", controller_for)
    return started


@pytest.mark.parametrize("mode", ["full", "smart-llm"])
def test_a_task_executes_in_the_thor_environment(unity: list[UnityDouble], mode: str) -> None:
    from emboteam.modes import run_mode

    task = get_task("mace-thor/fp1-fridge-apple-tomato")
    episode = run_mode(task, RunConfig(env="ai2thor", frontend="oracle", mode=mode))
    (double,) = unity
    assert len(double.agents) == len(task.robots)
    fridge = next(o["objectId"] for o in double.objects if o["objectType"] == "Fridge")
    actions = [(c["action"], c.get("objectId")) for c in double.calls]
    assert ("OpenObject", fridge) in actions and ("CloseObject", fridge) in actions
    assert [a for a, oid in actions if a == "PutObject" and oid == fridge] == ["PutObject", "PutObject"]
    assert {c["agentId"] for c in double.calls if c["action"] == "Teleport"} <= set(range(len(task.robots)))
    assert episode.success and episode.error is None and episode.makespan > 0
    assert episode.env == "ai2thor"  # the record says where it ran


def test_a_process_keeps_one_controller_and_resets_it_between_episodes(monkeypatch: pytest.MonkeyPatch) -> None:
    from emboteam.thor.launch import LaunchPlan

    started: list[UnityDouble] = []

    def start(plan: LaunchPlan, floor_plan: str, agent_count: int) -> UnityDouble:
        started.append(UnityDouble(floor_plan, agent_count))
        return started[-1]

    monkeypatch.setattr(session, "probe", lambda: LaunchPlan("CloudRendering", None, "thor-test", True))
    monkeypatch.setattr(session, "start_controller", start)
    monkeypatch.setattr(session, "_controllers", [])
    first = session.controller_for("FloorPlan1", 2)
    again = session.controller_for("FloorPlan201", 3)
    assert again is first and len(started) == 1
    assert again.floor_plan == "FloorPlan201" and len(again.agents) == 3
    assert again.calls[-1] == {"action": "SetDecayTemperatureBool", "allowDecayTemperature": False}


def test_crowded_doorways_run_on_the_grid_in_thor_without_collisions(unity: list[UnityDouble]) -> None:
    """The congestion suite's doorway tasks (a robot parked in a one-cell doorway, the team
    beyond it): in the AI2-THOR environment robots drive the simulator's grid paths step by
    step, wait for each other, and the double refuses any move onto another agent's cell."""
    from emboteam.bench.suites import load_suite
    from emboteam.modes import run_mode

    doorways = [t for t in load_suite("congestion").tasks if t.starts]
    episodes = [run_mode(t, RunConfig(env="ai2thor", frontend="oracle", mode="full")) for t in doorways]
    assert all(e.success for e in episodes), [(e.task, e.error) for e in episodes if not e.success]
    assert sum(e.collisions for e in episodes) == 0 and sum(e.nav_waits for e in episodes) > 0
    assert all(d.by_action("MoveAhead") for d in unity)
    assert not [c for d in unity for c in d.calls if c["action"] in ("GetShortestPathToPoint", "GetReachablePositions")]
