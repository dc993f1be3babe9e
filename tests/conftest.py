"""Shared fixtures: scenes, teams, fresh states and simulators, the AI2-THOR source data.

Scenes are cached and immutable; every state or simulator fixture is fresh per test, so
tests may mutate them freely.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import asdict
from pathlib import Path
from typing import Any

import pytest

from emboteam.sim import Simulator
from emboteam.world import Scene, WorldState, load_catalogue, load_scene, parse_team
from emboteam.world.catalogue import Catalogue
from emboteam.world.robots import RobotProfile

#: ../shared next to the repository (AI2-THOR metadata, SMART-LLM peer data); see shared_data.py
from shared_data import AI2THOR, SHARED, SMART_LLM

__all__ = ["AI2THOR", "SHARED", "SMART_LLM"]


#: ``@pytest.mark.isolated``: the test runs in a child interpreter (tests/isolation.py)
pytest_plugins = ["isolation"]



def _shared_json(path: Path) -> Any:
    if not path.exists():
        pytest.skip(f"shared data not available: {path}")
    return json.loads(path.read_text())


@pytest.fixture(scope="session")
def thor_inventories() -> dict[str, list[dict[str, Any]]]:
    """AI2-THOR 5.x object metadata of the 120 iTHOR floor plans (scene_inventories.json)."""
    data: dict[str, list[dict[str, Any]]] = _shared_json(AI2THOR / "scene_inventories.json")
    return data


@pytest.fixture(scope="session")
def thor_restrictions() -> dict[str, Any]:
    """AI2-THOR's ReceptacleRestrictions (receptacle_restrictions.json)."""
    data: dict[str, Any] = _shared_json(AI2THOR / "receptacle_restrictions.json")
    return data


@pytest.fixture(scope="session")
def thor_web_table() -> dict[str, Any]:
    """AI2-THOR's public object-type table (object_types_web_table.json)."""
    data: dict[str, Any] = _shared_json(AI2THOR / "object_types_web_table.json")
    return data


@pytest.fixture(scope="session")
def smart_llm_robots() -> list[dict[str, Any]]:
    """SMART-LLM's 28 robot definitions (robots.json), in task-file order (1-based)."""
    robots: list[dict[str, Any]] = _shared_json(SMART_LLM / "robots.json")["robots"]
    return robots


@pytest.fixture(scope="session")
def catalogue() -> Catalogue:
    return load_catalogue()


@pytest.fixture
def scene1() -> Scene:
    """FloorPlan1, the kitchen most AI2-THOR examples use."""
    return load_scene("FloorPlan1")


@pytest.fixture
def team12() -> tuple[RobotProfile, ...]:
    """Two all-skill robots with 100 kg capacity (SMART-LLM profiles 1 and 2)."""
    return parse_team("1,2")


@pytest.fixture
def state1(scene1: Scene, team12: tuple[RobotProfile, ...]) -> WorldState:
    """A fresh FloorPlan1 state with robot1 and robot2."""
    return WorldState.from_scene(scene1, team12)


@pytest.fixture
def sim1(scene1: Scene, team12: tuple[RobotProfile, ...]) -> Simulator:
    """A fresh fault-free simulator on FloorPlan1 with robot1 and robot2."""
    return Simulator(scene1, team12, seed=0)


def snapshot(state: WorldState) -> dict[str, Any]:
    """A deep, comparable copy of everything in a state (objects and robots)."""
    return {
        "objects": {k: asdict(v) for k, v in state.objects.items()},
        "robots": {k: {f: getattr(v, f) for f in ("position", "at", "holding", "down")}
                   for k, v in state.robots.items()},
    }


@pytest.fixture
def state_snapshot() -> Callable[[WorldState], dict[str, Any]]:
    """``state_snapshot(state)``: a deep copy to compare a state before/after an action."""
    return snapshot
