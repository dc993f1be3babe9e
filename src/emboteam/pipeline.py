"""One episode end to end: front end -> hybrid planner -> behavior trees -> execution.

This is where the stages meet, and the only place that knows every mode of the paper's
Tables 1 and 2; each mode is a choice of parts, not a fork:

=============  ======================  ======================  ===========================
mode           decomposition / goals   planning                execution
=============  ======================  ======================  ===========================
full           front end (PFG)         HP: FD + formal merge,  behavior trees: checks,
                                       validated by simulation  recovery, sync, replanning
no-hp          front end (PFG)         FD per subtask, no      behavior trees
                                       validation, concatenated
no-btc         front end (PFG)         HP                      linear per robot, no checks
no-pfg-hp      LLM action lists        none                    behavior trees (no sync)
smart-llm      LLM action lists        none                    concurrent lists, no checks
lamma-p        front end (PFG)         FD per subtask + merge, linear per robot, no checks
                                       no validation
=============  ======================  ======================  ===========================

Without an LLM, "LLM action lists" come from :mod:`emboteam.pfg.scripted` (the results
say so). Every typed error becomes a recorded failed episode.
"""

from __future__ import annotations

import time
from collections.abc import Sequence

from pydantic import BaseModel, ConfigDict, Field

from emboteam.bench.jobs import MODES, EnvName, Frontend, LLMWhen, Mode
from emboteam.bench.task import BenchTask
from emboteam.errors import EmboTeamError
from emboteam.exec.episode import ConditionOutcome, Episode
from emboteam.pddl.runner import PlannerInput
from emboteam.sim.disturbances import Disturbances
from emboteam.sim.faults import FaultConfig
from emboteam.sim.setup import apply_changes
from emboteam.world.checker import check_goal
from emboteam.world.goals import Goal
from emboteam.world.robots import RobotProfile, parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


class RunConfig(BaseModel):
    """How to run an episode: the mode, the front end, the LLM, faults, seed, limits."""

    model_config = ConfigDict(frozen=True)

    mode: Mode = "full"
    frontend: Frontend = "offline"
    llm: str | None = Field(None, description="PROVIDER:MODEL[@BASE_URL]")
    llm_timeout: float = 60.0
    llm_record: str | None = Field(None, description="cassette folder to record LLM calls into")
    llm_merge: bool = Field(False, description="the paper's LLM merge stage: the LLM proposes orderings")
    llm_when: LLMWhen = Field("doubt", description="hybrid front end: ask the LLM only when the offline "
                              "reading is in doubt, or always")
    planner_input: PlannerInput = Field("sas", description="what Fast Downward reads: our own SAS task "
                                        "(search binary only) or PDDL (driver and translator)")
    fault_level: float = Field(0.0, ge=0, le=1)
    faults: FaultConfig | None = Field(None, description="explicit faults (overrides fault_level)")
    seed: int = 0
    time_limit: float = Field(900.0, description="simulated seconds")
    joins: tuple[str, ...] = Field((), description="PROFILE@SECONDS: robots joining mid-run")
    env: EnvName = Field("sim", description="execute in the symbolic simulator or a live AI2-THOR")
    disturbance: Disturbances = Field(default_factory=Disturbances,
                                      description="benchmark disturbances, placed per task (bench/ceiling.py)")

    def fault_config(self) -> FaultConfig:
        return self.faults if self.faults is not None else FaultConfig.level(self.fault_level)


def adhoc_task(instruction: str, floor_plan: str, robots: str | Sequence[str]) -> BenchTask:
    """A task from the command line: no ground-truth goal, so success is judged against
    the goal the front end understood (the episode says so in its ``category``)."""
    fp = load_scene(floor_plan).floor_plan
    team = parse_team(robots if isinstance(robots, str) else ",".join(robots))
    return BenchTask(id="instruction", suite="adhoc", floor_plan=fp,
                     robots=tuple(str(p.number or p.name) for p in team), category="imported",
                     instruction=instruction, goal=Goal(conditions=()))


def initial_state(task: BenchTask) -> tuple[WorldState, tuple[RobotProfile, ...]]:
    scene = load_scene(task.floor_plan)
    team = parse_team(list(task.robots))
    state = WorldState.from_scene(scene, team)
    apply_changes(state, task.setup)
    return state, team


def _episode(task: BenchTask, cfg: RunConfig, **fields: object) -> Episode:
    _, team = initial_state(task)
    base: dict[str, object] = dict(
        task=task.key, instruction=task.instruction, floor_plan=task.floor_plan,
        robots=tuple(p.name for p in team), category=task.category, mode=cfg.mode,
        frontend=cfg.frontend, llm=cfg.llm, seed=cfg.seed, faults=cfg.fault_config(),
        fault_level=cfg.fault_level, env=cfg.env,
    )
    base.update(fields)
    return Episode.model_validate(base)


def score(goal: Goal, state: WorldState) -> tuple[bool, float, tuple[ConditionOutcome, ...]]:
    report = check_goal(goal, state)
    outcomes = tuple(ConditionOutcome(condition=str(r.condition), holds=r.holds,
                                      satisfied=r.satisfied, required=r.required)
                     for r in report.results)
    return report.success, report.gcr, outcomes


def check_config(cfg: RunConfig) -> None:
    """Raise the typed error of an unusable configuration (an LLM spec that names no
    provider, ``--frontend llm`` without ``--llm``, a missing API key) before any episode
    runs: such errors are the user's to fix, not failed episodes."""
    from emboteam.modes import make_llm

    make_llm(cfg)
    if cfg.env == "ai2thor":
        from emboteam.environments import check_thor_config

        check_thor_config(cfg)  # fails fast, in a second or so, when AI2-THOR cannot start here


def run_episode(task: BenchTask, cfg: RunConfig) -> Episode:
    """Plan and execute one task; a typed error ends it as a recorded failed episode."""
    from emboteam.llm.client import LLMClient
    from emboteam.modes import make_llm, run_mode  # the stage wiring lives in modes.py

    started = time.perf_counter()
    llm: LLMClient | None = None
    try:
        llm = make_llm(cfg)
        episode = run_mode(task, cfg, llm)
    except EmboTeamError as exc:
        state, _ = initial_state(task)
        _, gcr, conds = score(task.goal, state) if task.goal.conditions else (False, 0.0, ())
        # a failed episode still reports what its LLM calls cost
        usage = {"llm_calls": llm.usage.calls, "tokens": llm.usage.tokens} if llm is not None else {}
        episode = _episode(task, cfg, success=False, gcr=gcr, conditions=conds,
                           error=f"{type(exc).__name__}: {exc}", **usage)
    return episode.model_copy(update={"wall_seconds": round(time.perf_counter() - started, 4)})


__all__ = ["MODES", "RunConfig", "adhoc_task", "check_config", "initial_state", "run_episode", "score"]
