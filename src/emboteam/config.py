"""The configuration of one episode, shared by ``emboteam run`` and a benchmark job.

:class:`RunConfig` is the only episode configuration: a benchmark :class:`~emboteam.bench.jobs.Job`
*is* a RunConfig plus its task, so nothing is mapped (or dropped) between the two. The mode
and front-end names live here, below everything that wires them (docs/architecture.md).
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from emboteam.pddl.runner import PlannerInput
from emboteam.sim.disturbances import Disturbances
from emboteam.sim.faults import FaultConfig

Mode = Literal["full", "no-pfg-hp", "no-hp", "no-btc", "no-avoidance", "smart-llm", "lamma-p"]
Frontend = Literal["oracle", "offline", "llm", "hybrid"]
#: when the hybrid front end asks the LLM: only for a doubtful offline reading, or always
LLMWhen = Literal["doubt", "always", "close"]
#: where episodes execute: the symbolic simulator, or a live AI2-THOR (emboteam.thor)
EnvName = Literal["sim", "ai2thor"]

#: every mode, in the order the tables list them
MODES: tuple[Mode, ...] = ("full", "no-pfg-hp", "no-hp", "no-btc", "no-avoidance", "smart-llm", "lamma-p")
ABLATIONS: tuple[Mode, ...] = ("full", "no-pfg-hp", "no-hp", "no-btc", "no-avoidance")
BASELINES: tuple[Mode, ...] = ("smart-llm", "lamma-p")
#: front ends that call an LLM (and need an LLM spec)
LLM_FRONTENDS: tuple[Frontend, ...] = ("llm", "hybrid")


class RunConfig(BaseModel):
    """How to run an episode: the mode, the front end, the LLM, faults, seed, limits."""

    model_config = ConfigDict(frozen=True)

    mode: Mode = "full"
    frontend: Frontend = "offline"
    llm: str | None = Field(None, description="PROVIDER:MODEL[@BASE_URL]")
    llm_timeout: float = 60.0
    llm_record: str | None = Field(None, description="cassette folder to record LLM calls into")
    llm_merge: bool = Field(False, description="the paper's LLM merge stage: the LLM proposes orderings")
    clarify: bool = Field(False, description="ask the person on the terminal to choose among the "
                          "offline reader's close readings, or to answer an LLM front end's clarification "
                          "(no terminal: the best reading with a note; an LLM's question ends the episode)")
    llm_when: LLMWhen = Field("doubt", description="hybrid front end: ask the LLM only when the offline "
                              "reading is in doubt, or always; close: the LLM only scores "
                              "the offline reader's close readings (PMI), never reviews")
    planner_input: PlannerInput = Field("sas", description="what Fast Downward reads: our own SAS task "
                                        "(search binary only) or PDDL (driver and translator)")
    schedule: Literal["fast", "optimal"] = Field("fast", description="fast: the planner's own stages; optimal: "
                                                 "then CP-SAT over the whole schedule (hp/optimal.py)")
    close_after_use: bool = Field(True, description="the team closes a closed receptacle it puts things "
                                  "into unless the instruction asks it open (pfg/close_after_use.py); "
                                  "False: --leave-open")
    fault_level: float = Field(0.0, ge=0, le=1)
    faults: FaultConfig | None = Field(None, description="explicit faults (overrides fault_level)")
    seed: int = 0
    time_limit: float = Field(900.0, description="simulated seconds")
    joins: tuple[str, ...] = Field((), description="PROFILE@SECONDS: robots joining mid-run")
    env: EnvName = Field("sim", description="execute in the symbolic simulator or a live AI2-THOR")
    disturbance: Disturbances = Field(default_factory=Disturbances,
                                      description="benchmark disturbances, placed per task (exec/ceiling.py)")

    def fault_config(self) -> FaultConfig:
        return self.faults if self.faults is not None else FaultConfig.level(self.fault_level)


__all__ = ["ABLATIONS", "BASELINES", "LLM_FRONTENDS", "MODES", "EnvName", "Frontend", "LLMWhen", "Mode",
           "RunConfig"]
