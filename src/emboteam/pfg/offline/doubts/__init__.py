"""Points of doubt of an offline reading: one small named rule per kind.

Each rule looks at the words and the reading's goal (:class:`.context.DoubtContext`) and
returns :class:`~emboteam.pfg.candidates.Doubt` s, each with the reading as read first and
its alternatives after. :mod:`emboteam.pfg.ranker` combines them into candidates with the
priors of ``priors.json`` (fitted by ``benchmarks/fit_reading_priors.py``).

| kind | rule |
| --- | --- |
| unexplained_mention | :mod:`.unexplained` (also elided verbs and list items: carried-over goals) |
| scene_type | :mod:`.scene_type` |
| state | :mod:`.state` |
| slices | :mod:`.slices` |
| device | :mod:`.device` |
| exclusion, correction | :mod:`.scope` |
| of_compound | :mod:`.of_compound` |
"""

from __future__ import annotations

from emboteam.pfg.candidates import Doubt
from emboteam.pfg.offline.doubts import device, of_compound, scene_type, scope, slices, state, unexplained
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.priors import Priors, load_priors


def find_doubts(ctx: DoubtContext, priors: Priors | None = None) -> list[Doubt]:
    """Every point of doubt of a reading, rule by rule."""
    priors = priors or load_priors()
    found = [*unexplained.doubts(ctx), *scope.doubts(ctx), *of_compound.doubts(ctx), *scene_type.doubts(ctx),
             *device.doubts(ctx), *slices.doubts(ctx), *state.doubts(ctx, priors.state_swaps)]
    return [d for d in found if len(d.choices) > 1]


__all__ = ["DoubtContext", "Priors", "find_doubts", "load_priors"]
