"""An episode: one task run end to end, with its outcome, metrics and trace.

On disk (``emboteam run --out DIR``)::

    DIR/episode.json   Episode without the trace
    DIR/trace.jsonl    one TraceEvent per line
    DIR/report.html    the self-contained viewer (emboteam report DIR rebuilds it)
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from emboteam.config import RunConfig
from emboteam.exec.disturbance import DisturbanceOutcome
from emboteam.exec.trace import TraceEvent, write_jsonl
from emboteam.hp.plan import MergedPlan
from emboteam.pfg.candidates import NotAttempted
from emboteam.pfg.clarification import Clarification
from emboteam.pfg.taskspec import TaskSpec
from emboteam.sim.faults import FaultConfig
from emboteam.task import EpisodeTask
from emboteam.world.checker import check_goal
from emboteam.world.goals import Goal
from emboteam.world.state import WorldState


class ConditionOutcome(BaseModel):
    """A goal condition's truth at the end of the episode."""

    model_config = ConfigDict(frozen=True)

    condition: str
    holds: bool
    satisfied: int
    required: int


def episode_header(task: EpisodeTask, cfg: RunConfig, robots: Sequence[str]) -> dict[str, object]:
    """The fields every episode of ``task`` under ``cfg`` starts with, failed ones included."""
    return dict(task=task.key, instruction=task.instruction, floor_plan=task.floor_plan,
                robots=tuple(robots), category=task.category, mode=cfg.mode, frontend=cfg.frontend,
                llm=cfg.llm, seed=cfg.seed, faults=cfg.fault_config(), fault_level=cfg.fault_level, env=cfg.env)


def score(goal: Goal, state: WorldState) -> tuple[bool, float, tuple[ConditionOutcome, ...]]:
    """Success, GCR and per-condition outcomes of ``goal`` on the final ``state``."""
    report = check_goal(goal, state)
    outcomes = tuple(ConditionOutcome(condition=str(r.condition), holds=r.holds,
                                      satisfied=r.satisfied, required=r.required)
                     for r in report.results)
    return report.success, report.gcr, outcomes


class Episode(BaseModel):
    model_config = ConfigDict(frozen=True)

    task: str = Field(description="SUITE/ID; adhoc/instruction for an instruction given on the command line")
    instruction: str
    floor_plan: str
    robots: tuple[str, ...] = Field(description="team member names, e.g. robot1")
    category: str = ""
    mode: str = Field("full", description="full | no-pfg-hp | no-hp | no-btc | no-avoidance | smart-llm | lamma-p")
    frontend: str = "offline"
    llm: str | None = Field(None, description="PROVIDER:MODEL[@BASE_URL] of the LLM front end, if any")
    seed: int = 0
    faults: FaultConfig = FaultConfig()
    fault_level: float = 0.0
    env: str = Field("sim", description="where it executed: sim (the symbolic simulator) | ai2thor")

    success: bool = False
    gcr: float = 0.0
    exec: float = Field(0.0, description="share of executed actions that succeeded")
    makespan: float = Field(0.0, description="simulated seconds until the last robot stopped")
    actions: int = Field(0, description="actions executed (started), failed ones included")
    failed_actions: int = 0
    recoveries: int = 0
    replans: int = 0
    collisions: int = Field(0, description="vertex and edge conflicts of the robots' motion "
                                           "(exec/nav_check.py replaying the trace's nav event)")
    nav_waits: int = Field(0, description="times a robot waited on the grid for another robot")
    nav_replans: int = Field(0, description="drives re-planned around other robots")
    path_seconds: float = Field(0.0, description="wall-clock seconds spent planning paths on the grid")
    llm_calls: int = 0
    tokens: int = 0
    plan_seconds: float = Field(0.0, description="wall-clock seconds in PFG + HP")
    wall_seconds: float = 0.0
    error: str | None = Field(None, description="the typed error that ended the episode early")
    notes: tuple[str, ...] = Field((), description="what the front end could not read, or read "
                                   "with doubt, one line each (span and why)")
    unexplained: tuple[str, ...] = Field((), description="words naming a thing of the scene that ended in no "
                                         "goal and that nothing explains (offline front end)")
    candidates: tuple[dict[str, Any], ...] = Field((), description="the readings considered, best first: "
                                                   "sentence, goals, score, the doubts each settles")
    not_attempted: tuple[NotAttempted, ...] = Field((), description="requested goal conditions the planner "
                                                    "could not plan, left out of the run, each with why")
    clarification: Clarification | None = Field(None, description="the question the front end asked instead "
                                                "of guessing (the episode then ends with ClarificationNeeded)")

    disturbance: DisturbanceOutcome | None = Field(None, description="what a benchmark disturbance did "
                                                   "(bench --breakdown/--join/--moves/--msg-*)")
    conditions: tuple[ConditionOutcome, ...] = ()
    taskspec: TaskSpec | None = None
    plan: MergedPlan | None = None
    trace: tuple[TraceEvent, ...] = Field((), exclude=True)

    def summary(self) -> dict[str, object]:
        """The fields of ``emboteam run --json`` (docs/architecture.md)."""
        return {
            "task": self.task, "success": self.success, "gcr": round(self.gcr, 4),
            "exec": round(self.exec, 4), "makespan": round(self.makespan, 2),
            "actions": self.actions, "llm_calls": self.llm_calls, "tokens": self.tokens,
            "plan_seconds": round(self.plan_seconds, 4), "error": self.error,
            "notes": list(self.notes), "unexplained": list(self.unexplained),
            "candidates": list(self.candidates),
            "not_attempted": [n.model_dump() for n in self.not_attempted],
            "clarification": self.clarification.to_json() if self.clarification is not None else None,
        }

    def save(self, directory: Path) -> None:
        directory.mkdir(parents=True, exist_ok=True)
        (directory / "episode.json").write_text(self.model_dump_json(indent=1))
        write_jsonl(self.trace, directory / "trace.jsonl")
