"""Reading an instruction with the offline front end in a floor plan at its start, as the
reader's tests do (one place, so that every test reads the way a user's `emboteam run` does)."""

from __future__ import annotations

from emboteam.bench.offline_accuracy import initial_state
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.reading import Reading
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


def read_offline(frontend: OfflineFrontend, text: str, floor_plan: str = "FloorPlan1",
                 team: str = "1,2,3") -> Reading:
    """The reading of ``text`` in ``floor_plan`` as it starts, for the robots ``team``."""
    scene = load_scene(floor_plan)
    robots = parse_team(team)
    return frontend.parse(text, scene, WorldState.from_scene(scene, robots), robots)


def goal_of(frontend: OfflineFrontend, text: str, floor_plan: int | str, team: str = "1,2") -> set[str]:
    """The goal conditions, as text, that ``text`` decomposes to in ``floor_plan`` at the
    start of a benchmark episode (the state the reader's accuracy tests use)."""
    scene = load_scene(floor_plan)
    robots = parse_team(team)
    spec = frontend.decompose(text, scene, initial_state({}, scene, robots), robots)
    return {str(c) for c in spec.goal().conditions}
