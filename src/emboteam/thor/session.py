"""One AI2-THOR controller per process, reset between episodes.

Starting Unity takes seconds to minutes; a benchmark runs many episodes per worker
process, so the controller of a worker is kept and ``reset`` to the next floor plan and
team size. Every controller is stopped when the process exits.
"""

from __future__ import annotations

import atexit
import contextlib
from collections.abc import Callable, Sequence
from typing import Any

from emboteam.thor.changes import changes_between
from emboteam.thor.environment import ThorEnvironment
from emboteam.thor.launch import keep_temperatures, probe, start_controller
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

_controllers: list[Any] = []  # at most one: a worker process runs one Unity


def _stop_all() -> None:
    for controller in _controllers:
        with contextlib.suppress(Exception):  # the Unity process may already be gone at exit
            controller.stop()
    _controllers.clear()


atexit.register(_stop_all)


def controller_for(floor_plan: str, agent_count: int) -> Any:
    """A live controller with ``agent_count`` agents in ``floor_plan``: the process's
    controller reset (``Initialize`` takes a new ``agentCount``), or a new one."""
    if not _controllers:
        _controllers.append(start_controller(probe(), floor_plan, agent_count))
        return _controllers[0]
    controller = _controllers[0]
    controller.reset(floor_plan, agentCount=agent_count)
    keep_temperatures(controller)
    return controller


def open_thor(scene: Scene, team: Sequence[RobotProfile], state: WorldState, *, spare_agents: int = 0,
              controller_factory: Callable[[str, int], Any] | None = None) -> ThorEnvironment:
    """A ThorEnvironment for ``team`` in ``scene``, brought into the symbolic ``state``
    (the task's initial-state changes, its robots' start cells) and with ``spare_agents``
    for robots that join."""
    factory = controller_factory or controller_for  # looked up now: tests stand in a Unity double
    controller = factory(scene.floor_plan, len(team) + spare_agents)
    starts = {name: r.position for name, r in state.robots.items()}
    return ThorEnvironment(controller, scene, team, setup=changes_between(WorldState.from_scene(scene), state),
                           starts=starts)
