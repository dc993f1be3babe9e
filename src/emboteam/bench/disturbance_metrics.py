"""Metrics of disturbed episodes (docs/metrics.md, "Disturbances").

- **SR of savable**: successes among the episodes whose ceiling says the goal was still
  reachable after the disturbance by the robots left (``Episode.disturbance.savable``).
  "No savable task lost" is SR of savable = 1.
- **savable share**: savable episodes / episodes with a verdict.
- **unsavable ended typed**: unsavable episodes that ended with a typed error, and the
  longest wall time from the disturbance to their end.
- **joiner took over**: among episodes where a robot joined (so work remained when it
  came), those in which it carried out at least one action.
"""

from __future__ import annotations

import statistics
from collections.abc import Sequence

from pydantic import BaseModel, ConfigDict, Field

from emboteam.exec.episode import Episode


class DisturbanceSummary(BaseModel):
    model_config = ConfigDict(frozen=True)

    spec: str = Field(description="the disturbance options (canonical); several joined by ' + '")
    n: int
    disturbed: int = Field(description="episodes where a disturbance happened before the end")
    savable: int
    unsavable: int
    unknown: int = Field(description="episodes the ceiling's planner could not decide")
    savable_share: float = Field(description="savable / (savable + unsavable); 1 when none was decided")
    sr: float
    sr_savable: float | None = Field(description="successes among savable episodes (None: none savable)")
    unsavable_typed: int = Field(description="unsavable episodes that ended with a typed error")
    unsavable_wall_max: float | None = Field(
        description="longest wall seconds from the disturbance to the end of an unsavable episode")
    wall_after_p50: float | None = Field(description="median wall seconds from the disturbance to the end")
    joined: int = Field(description="episodes in which a robot joined")
    joiner_took_over: int = Field(description="of those, episodes where a joiner carried out an action")
    lost_releases: int = 0
    lock_timeouts: int = 0
    late_reads: int = 0


def summarize_disturbance(episodes: Sequence[Episode]) -> DisturbanceSummary | None:
    """The disturbance metrics of episodes (None if none of them was disturbed by options)."""
    eps = [e for e in episodes if e.disturbance is not None]
    if not eps:
        return None
    outs = [e.disturbance for e in eps if e.disturbance is not None]
    savable = [e for e in eps if e.disturbance is not None and e.disturbance.savable is True]
    unsavable = [e for e in eps if e.disturbance is not None and e.disturbance.savable is False]
    decided = len(savable) + len(unsavable)
    walls = [o.wall_after for o in outs if o.wall_after is not None]
    un_walls = [e.disturbance.wall_after for e in unsavable
                if e.disturbance is not None and e.disturbance.wall_after is not None]
    joined = [o for o in outs if o.joined]

    def total(key: str) -> int:
        return sum(o.network.get(key, 0) for o in outs)

    return DisturbanceSummary(
        spec=" + ".join(sorted({o.spec for o in outs})), n=len(eps), disturbed=sum(o.disturbed for o in outs),
        savable=len(savable), unsavable=len(unsavable), unknown=len(eps) - decided,
        savable_share=len(savable) / decided if decided else 1.0,
        sr=sum(e.success for e in eps) / len(eps),
        sr_savable=sum(e.success for e in savable) / len(savable) if savable else None,
        unsavable_typed=sum(1 for e in unsavable if e.error),
        unsavable_wall_max=max(un_walls) if un_walls else None,
        wall_after_p50=round(statistics.median(walls), 4) if walls else None,
        joined=len(joined), joiner_took_over=sum(1 for o in joined if o.joiner_actions > 0),
        lost_releases=total("lost_releases"), lock_timeouts=total("lock_timeouts"), late_reads=total("late_reads"),
    )


def disturbance_by_mode(episodes: Sequence[Episode]) -> dict[str, DisturbanceSummary]:
    """:func:`summarize_disturbance` per mode (modes without disturbed episodes left out)."""
    modes: dict[str, list[Episode]] = {}
    for e in episodes:
        modes.setdefault(e.mode, []).append(e)
    found = {m: summarize_disturbance(eps) for m, eps in modes.items()}
    return {m: s for m, s in found.items() if s is not None}
