"""The role a place phrase plays for a thing: a keep of its place or of a state only, a
landmark that names which receptacle is meant.

A keep cue ("stays", "remains", "leave it") keeps the thing where it is; one that a state
word follows with no place after it keeps that state instead ("the laptop stays shut",
"the lamp stays on"): the thing's place is then no condition (gold readings never add it,
and a keep of a state is not a keep of a place). One rule for :mod:`.kept_place` and
:mod:`.mention_cues`. Cue words: ``place_roles.json`` (schema checked at load).
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache
from pathlib import Path

from pydantic import Field

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.destination import present
from emboteam.pfg.offline.doubts.mention_words import SidedCue, found, load_mention_cues
from emboteam.pfg.offline.knowledge import Strict, read
from emboteam.pfg.offline.tagger import Item
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.goals import Predicate

KIND = "landmark_place"
PLACE_ROLES_FILE = Path(__file__).with_name("place_roles.json")


class PlaceRoles(Strict):
    about: str = ""
    #: words that, right after a state word, make it a preposition of a place ("stays on there")
    place_after_state: list[str] = Field(min_length=1)
    #: prepositions right after a receptacle that describe where it stands ("the box on the floor")
    describing_preps: list[str] = Field(min_length=1)


@cache
def load_place_roles(path: Path = PLACE_ROLES_FILE) -> PlaceRoles:
    """The cue file, checked by its schema."""
    return read(path, PlaceRoles)


def keeps_state(items: Sequence[Item], e: int) -> bool:
    """Whether a keep cue ending at ``e`` keeps a state, not a place: a state word follows
    it that no place phrase follows ("stays shut", "stays open"; not "stays on the desk",
    "stays cold in there": a state and a place)."""
    if e >= len(items) or items[e].state is None:
        return False
    nxt = items[e + 1] if e + 1 < len(items) else None
    return nxt is None or not (nxt.det or nxt.noun is not None or nxt.pron is not None
                               or nxt.text in load_place_roles().place_after_state
                               or nxt.text in load_mention_cues().place_preps)


def state_kept(ctx: DoubtContext, k: int, end: int, cues: Sequence[SidedCue]) -> bool:
    """Whether a keep cue said after the thing at ``k`` (before ``end``) keeps a state."""
    reach = min(end, k + 1 + load_mention_cues().cue_reach)
    return any(keeps_state(ctx.items, s + len(c.words)) for c in cues if c.side != "before"
               for s in found(ctx, k + 1, reach, c.words))


def _described_at(ctx: DoubtContext, k: int, places: frozenset[str]) -> bool:
    """Whether the mention at ``k`` is described by a place right after it ("the box on
    the floor") and no verb acts on it ("put the box on the floor" moves it)."""
    items = ctx.items
    if k + 1 >= len(items) or items[k + 1].prep is None or items[k + 1].text not in load_place_roles().describing_preps:
        return False      # "the pot from the stove" ("that's already on"): where it comes from, kept
    after = next((m for m in range(k + 2, min(len(items), k + 5)) if ctx.named_types(items[m])), None)
    if after is None or not set(ctx.named_types(items[after])) & places:
        return False
    j = k - 1
    while j >= 0 and (items[j].det or items[j].number is not None or items[j].state is not None):
        j -= 1
    return j < 0 or items[j].verb is None or items[j].prep is not None


def doubts(ctx: DoubtContext) -> list[Doubt]:
    """A receptacle that receives things, read as placed where it already stands ("into
    the box on the floor", "in the box, the box on the side table"): the place names which
    receptacle it is (a landmark), it is not an end state of the box. The alternative
    drops that place."""
    hosts = {t for c in ctx.goals if c.predicate is Predicate.inside and c.receptacle is not None
             for t in ref_types(c.receptacle)}
    out: list[Doubt] = []
    for c in ctx.goals:
        if c.predicate is not Predicate.inside or c.receptacle is None:
            continue
        thing = next(iter(ref_types(c.subject)), None)
        if thing is None or thing not in hosts or not ref_types(c.receptacle) & present(ctx, thing) \
                or not any(_described_at(ctx, k, ref_types(c.receptacle)) for k, _, types in ctx.mentions() if thing in types):
            continue
        name = type_name(thing)
        out.append(Doubt(KIND, name, (Choice(AS_READ, f"{name}: {clause(c)}"),
                                      Choice("identifies", f"{name}: where it stands names it", drop=(c,)))))
    return out
