"""Points of doubt of an offline reading: one small named rule per kind.

Each rule looks at the words and the reading's goal (:class:`.context.DoubtContext`) and
returns :class:`~emboteam.pfg.candidates.Doubt` s, each with the reading as read first and
its alternatives after. :mod:`emboteam.pfg.ranker` combines them into candidates with the
priors of ``priors.json`` (fitted by ``benchmarks/fit_reading_priors.py``).

| kind | rule |
| --- | --- |
| unexplained_mention | :mod:`.unexplained` (its own window's place or keeping, :mod:`.window`; also elided verbs and list items: carried-over goals) |
| scene_type | :mod:`.scene_type` |
| state | :mod:`.state` |
| slices | :mod:`.slices` |
| device | :mod:`.device` |
| exclusion | :mod:`.scope` |
| undo | :mod:`.scope` (an undo: a moved thing back to where it came from or lived, ``rule_words.json``) |
| correction | :mod:`..corrections` (a self-correction's slot read another way: the other readings) |
| of_compound | :mod:`.of_compound` |
| means | :mod:`.means` (the microwave, coffee machine, toaster left as the end state) |
| instance | :mod:`.instances` (one object, or any of its type) |
| contents | :mod:`.contents` ("everything on X except Y goes in Z": a receptacle's contents; things picked by a property, "all the breakables", :mod:`.properties`) |
| resumed | :mod:`.resumed` ("the three vases, all of them you put in a cupboard": the pronoun's things) |
| compare | :mod:`.compare` ("the heavier of the two ... goes on the bed": the scene's masses pick) |
| others | :mod:`.others` ("the one on the table goes in the box, the other ones stay": one moved, the rest kept) |
| joins | :mod:`.joins` ("the roll on the floor joins the other one": placed where the others of its kind end; ``joins.json``) |
| exclusive | :mod:`.exclusive` ("only the floor lamp on": the other lights, screens off) |
| next_place | :mod:`.destination` (where a thing's own words send it; the one destination finder, ``destination_cues.json``) |
| mention_cue | :mod:`.mention_cues` (a thing with no goal read in its own words: kept, a state) |
| device_state | :mod:`.device_state` (a device's end state in its own words: particles, calques, kept, purposes; ``state_words.json``) |
| placed_instead | :mod:`.placed_instead` (a carried thing read as held or switched: placed where the words near it point) |
| kept_place | :mod:`.kept_place` (a thing acted on with no place: the place its words keep or send it to, ``kept_place.json``) |
| landmark_place | :mod:`.place_roles` (a receptacle that receives things, read as placed where it already stands: the place names it)
| switch | :mod:`.switches` (a switch goal the other way; a named device, or its knob, switched: priors only) |

The words of contents and exclusive are data: ``rule_words.json`` (:mod:`.rule_words`);
the cues of mention_cue are ``mention_cues.json``; every destination cue is
``destination_cues.json``.
"""

from __future__ import annotations

from emboteam.pfg.candidates import Doubt
from emboteam.pfg.offline.doubts import (
    compare,
    contents,
    destination,
    device,
    device_state,
    exclusive,
    instances,
    joins,
    kept_place,
    means,
    mention_cues,
    of_compound,
    others,
    place_roles,
    placed_instead,
    resumed,
    scene_type,
    scope,
    slices,
    state,
    switches,
    unexplained,
)
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.priors import Priors, load_priors


def reading_doubts(ctx: DoubtContext) -> list[Doubt]:
    """The doubts that may give a whole reading from the words (also when the grammar
    found nothing): contents, exclusive purposes, next places, a narrative's device states,
    things taken up by a quantified pronoun."""
    # a narrative's device states ("when I walk in the TV is on") may make a reading too
    told = device_state.doubts(ctx) if ctx.narrative else []
    found = [*contents.doubts(ctx), *exclusive.doubts(ctx), *destination.doubts(ctx), *told,
             *resumed.doubts(ctx), *joins.doubts(ctx)]
    return [d for d in found if len(d.choices) > 1]


def find_doubts(ctx: DoubtContext, priors: Priors | None = None) -> list[Doubt]:
    """Every point of doubt of a reading, rule by rule."""
    priors = priors or load_priors()
    states = device_state.doubts(ctx)
    stated_by_words = {d.span for d in states}
    cued = [*states, *(d for d in mention_cues.doubts(ctx) if d.span not in stated_by_words)]
    # a mention whose own words give its goal is settled by that doubt, not by the weaker
    # guesses of an unexplained mention or of a kept thing
    said = {d.span for d in cued}
    found = [*cued, *(d for d in unexplained.doubts(ctx) if d.span not in said), *kept_place.doubts(ctx, cued),
             *scope.doubts(ctx),
             *of_compound.doubts(ctx), *scene_type.doubts(ctx),
             *device.doubts(ctx), *slices.doubts(ctx), *state.doubts(ctx, priors.state_swaps), *means.doubts(ctx),
             *instances.doubts(ctx), *others.doubts(ctx), *compare.doubts(ctx), *switches.doubts(ctx), *placed_instead.doubts(ctx),
             *place_roles.doubts(ctx),
             *(d for d in reading_doubts(ctx) if d.kind != device_state.KIND)]
    return [d for d in found if len(d.choices) > 1]


__all__ = ["DoubtContext", "Priors", "find_doubts", "load_priors", "reading_doubts"]
