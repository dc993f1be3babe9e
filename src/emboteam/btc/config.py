"""Budgets of the reactive layer: how long a step may keep trying before its branch gives
up and the executor replans. Bounded everywhere, so a hopeless step always ends."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field


class BTConfig(BaseModel):
    model_config = ConfigDict(frozen=True)

    #: attempts of a step's core action (the first included); an actuation fault at the
    #: default 0.2 failure rate survives five attempts with probability 0.2**5 = 0.03 %
    max_attempts: int = Field(5, ge=1)
    #: recovery subtrees that act on the environment (re-approach, open, put down,
    #: re-grasp) per step, failed ones included
    max_recoveries: int = Field(6, ge=0)
    #: bounded back-off waits per step (spot busy outside the lock protocol, object held
    #: by another robot)
    max_waits: int = Field(20, ge=0)
    #: simulated seconds of one back-off wait
    wait_seconds: float = Field(1.0, gt=0)
    #: simulated seconds a spot lock stays valid after its holder stopped renewing it (a
    #: holder renews its locks while it works; a lost release or a broken-down holder
    #: stops that, and a waiting robot takes the lock over once the lease has run out)
    lock_lease: float = Field(5.0, gt=0)
