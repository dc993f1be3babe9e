"""Which Environment an episode executes in: the symbolic simulator (``--env sim``, the
default) or a live AI2-THOR (``--env ai2thor``, :mod:`emboteam.thor`).

Planning always starts from the symbolic initial state of the task (the scene data is
AI2-THOR's own metadata, so plans name the same objects); the live environment is then
put into that state (:func:`emboteam.thor.session.open_thor`) and the behavior trees run
against it unchanged.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

from emboteam.config import RunConfig
from emboteam.errors import EmboTeamError
from emboteam.sim.simulator import Simulator
from emboteam.world.environment import Environment
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState


class EnvConfigError(EmboTeamError):
    """Options the chosen environment cannot honour (injected faults in AI2-THOR)."""


class ExecutionEnvironment(Environment, Protocol):
    """An Environment whose current state the pipeline scores at the end."""

    @property
    def state(self) -> WorldState: ...


def check_thor_config(cfg: RunConfig) -> None:
    """Before any episode: options AI2-THOR cannot honour, then whether it can start here."""
    if cfg.fault_level > 0 or cfg.faults is not None or cfg.disturbance.any:
        raise EnvConfigError("--faults and the benchmark disturbances are injected by the symbolic "
                             "simulator; with --env ai2thor the failures are AI2-THOR's own")
    from emboteam.thor.launch import probe

    probe()


def make_environment(cfg: RunConfig, scene: Scene, team: Sequence[RobotProfile],
                     state: WorldState) -> ExecutionEnvironment:
    """The environment of one episode, starting in ``state``."""
    if cfg.env == "ai2thor":
        from emboteam.thor.session import open_thor

        return open_thor(scene, team, state, spare_agents=len(cfg.joins))
    from emboteam.mode_table import wiring

    return Simulator(scene, team, seed=cfg.seed, faults=cfg.fault_config(), state=state,
                     avoidance=wiring(cfg.mode).avoidance)
