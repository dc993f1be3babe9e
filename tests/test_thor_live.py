"""Conformance against a live AI2-THOR: one MACE-THOR task per room type, end to end
(plan, behavior trees, execution in Unity, goal check on AI2-THOR's own metadata).

Skipped, with the probe's reason, where no AI2-THOR build can start (every machine this
project's CI runs on: no display, no Vulkan, no route to AI2-THOR's build server). On a
workstation with a display, or with Vulkan and ``EMBOTEAM_THOR_PLATFORM=CloudRendering``:
``pytest tests/test_thor_live.py -v``.
"""

from __future__ import annotations

import pytest

from emboteam.bench.suites import get_task
from emboteam.pipeline import RunConfig, run_episode
from emboteam.thor.errors import ThorUnavailableError
from emboteam.thor.launch import probe


def _unavailable() -> str | None:
    try:
        probe()
    except ThorUnavailableError as exc:
        return str(exc)
    return None


REASON = _unavailable()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")

#: one task per room type, each touching a different part of the adapter
PER_ROOM = {
    "kitchen": "mace-thor/fp1-fridge-apple-tomato",   # open, put twice, close
    "living_room": "mace-thor/fp201-box-card-pen",    # put into a pickupable box, close it
    "bedroom": "mace-thor/fp303-desk-clear",          # tidy several objects, two robots
    "bathroom": "mace-thor/fp414-plunger",            # a cabinet and a light switch
}


@pytest.mark.timeout(1800)
@pytest.mark.parametrize("room", sorted(PER_ROOM))
def test_a_mace_thor_task_runs_to_its_goal_in_ai2thor(room: str) -> None:
    task = get_task(PER_ROOM[room])
    episode = run_episode(task, RunConfig(env="ai2thor", frontend="oracle"))
    assert episode.error is None, episode.error
    assert episode.success, [str(c) for c in episode.conditions if not c.holds]
