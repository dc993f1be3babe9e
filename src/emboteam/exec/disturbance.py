"""What a disturbed episode records about its disturbance: what happened, whether the goal
was still reachable by the robots left (the ceiling), and how the run reacted.

Filled by :func:`emboteam.exec.ceiling.disturbance_outcome`; read by the metrics (``SR of
savable``), the tables and the HTML report.
"""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field


class DisturbanceEvent(BaseModel):
    """One breakdown, join or move, as the simulator applied it."""

    model_config = ConfigDict(frozen=True)

    t: float
    kind: str = Field(description="breakdown | join | moved")
    detail: str


class DisturbanceOutcome(BaseModel):
    model_config = ConfigDict(frozen=True)

    spec: str = Field(description="the disturbance options, canonical (Disturbances.label)")
    nominal_makespan: float = Field(0.0, description="makespan of the fault-free reference plan, simulated s")
    events: tuple[DisturbanceEvent, ...] = ()
    disturbed: bool = Field(False, description="a breakdown, join or move happened, or a message was "
                                               "lost or late, before the episode ended")
    savable: bool | None = Field(None, description="the goal was reachable from the state after the last "
                                                   "disturbance by the robots left (None: the planner "
                                                   "could not tell)")
    ceiling: str = Field("", description="why: the episode succeeded, the plan found, or the planner's error")
    ceiling_seconds: float = Field(0.0, description="wall seconds the ceiling's planner call took "
                                                    "(not part of the episode)")
    robots_left: tuple[str, ...] = ()
    wall_after: float | None = Field(None, description="wall seconds from the first breakdown, join or "
                                                       "move to the end of the execution")
    stop_reason: str = ""
    joined: tuple[str, ...] = ()
    joiner_actions: int = Field(0, description="actions the joined robots carried out successfully")
    network: dict[str, int] = Field(default_factory=dict,
                                    description="lost_releases, lock_timeouts, late_reads")
