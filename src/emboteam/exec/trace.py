"""The executor's record of an episode: a time-ordered list of events, written as JSONL.

Kinds (``data`` fields in brackets):

- ``action_start`` / ``action_end``   robot, [step, action, success, reason, message, recovery,
  strategy, plan] (``plan``: 0 for the first plan, k after the k-th replan: step ids repeat
  across plans; ``action_start`` also has skill, target, receptacle and the interaction spot)
- ``node``                             robot, [node, path, status] (behavior-tree status change)
- ``blackboard``                       robot, [key, value] (sync flags, resource locks)
- ``pose``                             robot, [x, z, holding]
- ``sim``                              [kind, detail] (faults, breakdowns, joins, moved objects)
- ``replan``                           [reason, unmet, robots, error]
- ``recovery``                         robot, [step, strategy, object, why, fault, gave_up]
  (a recovery subtree starts, or a step gives up; its actions are ``action_*`` events
  with ``recovery`` true)
- ``network``                          robot, [what, key, ...] the blackboard as a lossy network:
  ``release_lost`` (a lock release did not arrive), ``lock_timeout`` (a waiter took over a
  lock whose lease ran out), ``late_read`` (a done flag reaches this robot late)
- ``nav``                              (once, at the end) [floor_plan, grid, avoidance, starts,
  moves, waits, replans, yields, vertex_conflicts, edge_conflicts]: every robot's start cell and every
  MoveAhead it executed on the navigation grid (``Simulator.nav_record``), which
  ``exec/nav_check.py`` replays and the report draws
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict

EventKind = Literal["action_start", "action_end", "node", "blackboard", "pose", "sim", "replan",
                    "recovery", "network", "nav"]


class TraceEvent(BaseModel):
    model_config = ConfigDict(frozen=True)

    t: float
    kind: EventKind
    robot: str | None = None
    data: dict[str, Any] = {}


def write_jsonl(events: Iterable[TraceEvent], path: Path) -> None:
    with path.open("w") as fh:
        for ev in events:
            fh.write(ev.model_dump_json() + "\n")


def read_jsonl(path: Path) -> list[TraceEvent]:
    return [TraceEvent.model_validate(json.loads(line)) for line in path.read_text().splitlines()
            if line.strip()]
