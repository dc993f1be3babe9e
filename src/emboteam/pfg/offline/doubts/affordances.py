"""The goals the scene allows for a thing, by what it affords: what an unexplained
mention proposes when no word of its own stretch says what to do with it.

- a thing that switches: the switch state it is not in now (all of its type off -> on),
  unless it is switched only to be used (a phone, a laptop: ``not_for``);
- a thing that opens (not a container, whose opening is a means): the state it is not in;
- a thing that is picked up: placed in one of the places named near it (within ``reach``
  words, nearest first, at most ``most``), the destinations the instruction mentions.

Which property proposes what is data (``affordances.json``, checked at load).
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

from pydantic import BaseModel, Field

from emboteam.pfg.offline.doubts.context import DoubtContext, fitting_first
from emboteam.pfg.offline.doubts.context import type_props as _props
from emboteam.pfg.offline.doubts.destination import led
from emboteam.pfg.offline.doubts.wants import one_object, placed
from emboteam.pfg.offline.knowledge import read
from emboteam.world.checker import check_condition
from emboteam.world.goals import Condition, Predicate

AFFORDANCES_FILE = Path(__file__).with_name("affordances.json")


class _Switch(BaseModel):
    property: str
    label: str
    #: types whose switch is a means of using them, never asked for by a bare mention
    not_for: list[str] = Field(default_factory=list)


class _Open(BaseModel):
    property: str
    label: str
    not_with: list[str] = Field(default_factory=list)


class _Place(BaseModel):
    property: str
    label: str
    reach: int = Field(7, ge=1, le=30)
    most: int = Field(2, ge=1, le=5)


class Affordances(BaseModel):
    about: str = ""
    switch: _Switch
    open: _Open
    place: _Place


@cache
def load_affordances(path: Path = AFFORDANCES_FILE) -> Affordances:
    """The affordances file, checked by its schema at load (a malformed entry is a
    :class:`~emboteam.pfg.offline.knowledge.KnowledgeDataError` naming file and entry)."""
    return read(path, Affordances)


def _flip(ctx: DoubtContext, type_: str, attr: str, yes: Predicate, no: Predicate) -> Predicate | None:
    """The state of ``attr`` every object of the type is not in now (None when mixed)."""
    now = {getattr(o, attr) for o in ctx.state.of_type(type_)}
    if now == {False}:
        return yes
    if now == {True}:
        return no
    return None


def places_near(ctx: DoubtContext, k: int, thing: str, place: _Place | None = None) -> list[str]:
    """Receptacles named as destinations (:func:`.destination.led`) within ``reach``
    words of position ``k``, nearest first (after it before before it at the same
    distance); ``place``: the file's ``place`` entry unless given."""
    where = place or load_affordances().place
    near = [(abs(m - k) + (0.5 if m < k else 0), types[0]) for m, _, named in ctx.mentions()
            if m != k and abs(m - k) <= where.reach and (types := fitting_first(thing, named))[0] != thing
            and "receptacle" in _props(types[0]) and led(ctx, m) is not None]
    return list(dict.fromkeys(t for _, t in sorted(near)))


def proposals(ctx: DoubtContext, k: int, thing: str) -> list[tuple[str, Condition]]:
    """(label, goal) the scene allows for the thing named at ``k``."""
    data = load_affordances()
    props = _props(thing)
    out: list[tuple[str, Condition]] = []
    if data.place.property in props:
        # a place where it is already asks nothing ("the remote's all the way over on the desk")
        goals = [g for p in places_near(ctx, k, thing, data.place) if not check_condition(g := placed(thing, p), ctx.state).holds]
        out += [(data.place.label, g) for g in goals[:data.place.most]]
    if data.switch.property in props and thing not in data.switch.not_for and (p := _flip(ctx, thing, "is_on", Predicate.switched_on,
                                                     Predicate.switched_off)) is not None:
        out.append((data.switch.label, one_object(p, thing)))
    if data.open.property in props and not props & set(data.open.not_with) and (
            p := _flip(ctx, thing, "is_open", Predicate.open, Predicate.closed)) is not None:
        out.append((data.open.label, one_object(p, thing)))
    return out
