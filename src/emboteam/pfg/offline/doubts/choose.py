"""The offline reading as a choice: its points of doubt, its ranked candidates and the
mentions nothing explains (the hook :class:`~emboteam.pfg.offline.frontend.OfflineFrontend`
calls once it has read an instruction)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from emboteam.pfg.candidates import Candidate, Doubt
from emboteam.pfg.offline.discourse import Mention
from emboteam.pfg.offline.doubts import find_doubts
from emboteam.pfg.offline.doubts.check import feasible
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.priors import Priors, load_priors
from emboteam.pfg.offline.doubts.unexplained import unexplained_spans
from emboteam.pfg.offline.tagger import Item
from emboteam.pfg.ranker import rank
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Condition
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState


@dataclass(frozen=True)
class Choices:
    candidates: tuple[Candidate, ...]
    unexplained: tuple[str, ...]
    doubts: tuple[Doubt, ...]


def choices(spec: TaskSpec, items: Sequence[Item], scene: Scene, state: WorldState,
            team: Sequence[RobotProfile], history: Sequence[Mention] = (), priors: Priors | None = None) -> Choices:
    """The candidates of a reading (best first, the reader's own among them) and the
    words of each mention nothing explains."""
    ctx = DoubtContext(items=items, goals=tuple(spec.goal().conditions), scene=scene, state=state,
                       history=history)
    priors = priors or load_priors()
    doubts = find_doubts(ctx, priors)
    cache: dict[frozenset[Condition], bool] = {}

    def check(goals: tuple[Condition, ...]) -> bool:
        key = frozenset(goals)
        if key not in cache:
            cache[key] = feasible(goals, scene, state, team)
        return cache[key]

    ranked = rank(spec, doubts, priors, check)
    return Choices(ranked, tuple(words for _, words, _ in unexplained_spans(ctx)), tuple(doubts))
