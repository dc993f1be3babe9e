"""Event-driven simulated time, shared by every executor.

Time jumps from one event to the next (an action ending, a scheduled breakdown, a
timer a waiting node asked for), so a 40-second drive costs one tick, not 400; in
between, robot poses are still sampled every ``pose_interval`` simulated seconds for the
trace (without ticking anything).
"""

from __future__ import annotations

import math

from emboteam.exec.recorder import TraceRecorder
from emboteam.world.actions import ActionOutcome
from emboteam.world.environment import Environment


class Driver:
    def __init__(self, env: Environment, recorder: TraceRecorder, *, pose_interval: float = 0.5) -> None:
        self.env = env
        self.recorder = recorder
        self.pose_interval = pose_interval

    def advance_to(self, t: float) -> list[ActionOutcome]:
        """Let time pass up to ``t``; return the actions that ended meanwhile."""
        env, rec = self.env, self.recorder
        done: list[ActionOutcome] = []
        if self.pose_interval > 0:
            k = math.floor(env.now / self.pose_interval + 1e-9) + 1
            sample = k * self.pose_interval
            while sample < t - 1e-9:
                done.extend(env.advance(sample))
                rec.pull_sim_events()
                rec.sample_poses()
                sample += self.pose_interval
        done.extend(env.advance(t))
        rec.pull_sim_events()
        return done

    def anyone_busy(self) -> bool:
        return any(self.env.busy(r) for r in self.env.observe().robots)
