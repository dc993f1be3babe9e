"""Point of doubt: the switch state of a device the instruction names.

The words about a device's power are the ones readers lose most often without a note
(development rounds r45-r51: "with its ring lit", "the telly showing something", "why is
the light on", "📺 ON"): the reading then switches the device the other way, or never
switches a device it names as a place or landmark. Two alternatives, both from the scene
and not from the words (the words' own cues are :mod:`.device_state`'s):

- ``flip``: a switch goal read the other way (on for off, off for on), when that asks for
  a change (the devices it names are not all in that state now: "if the lamp is still on,
  switch it off" never asks for the lamp on);
- ``mentioned``: a device the words name with no switch goal (itself, or the knob that
  switches it: a burner's) put in the switch state it is not in now (:mod:`.affordances`).

Both priors are small (``priors.json``, kind ``switch``): the reading as read stays first
unless the other doubts settle it otherwise; these only make the right reading reachable.
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.affordances import load_affordances
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types, type_props
from emboteam.pfg.offline.doubts.wants import one_object
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.goals import Condition, Predicate

KIND = "switch"

_OTHER = {Predicate.switched_on: Predicate.switched_off, Predicate.switched_off: Predicate.switched_on}


def _flips(ctx: DoubtContext) -> list[Doubt]:
    out = []
    for c in ctx.goals:
        if (other := _OTHER.get(c.predicate)) is None:
            continue
        alt = c.model_copy(update={"predicate": other})
        if _holds_now(ctx, alt):
            continue
        out.append(Doubt(KIND, str(c), (Choice(AS_READ, clause(c)),
                                        Choice("flip", clause(alt), drop=(c,), add=(alt,)))))
    return out


def _holds_now(ctx: DoubtContext, c: Condition) -> bool:
    on = c.predicate is Predicate.switched_on
    now = [o.is_on for t in ref_types(c.subject) for o in ctx.state.of_type(t)]
    return bool(now) and all(x == on for x in now)


def _switched_by(ctx: DoubtContext, type_: str) -> str | None:
    """The type that switches a thing: its own when it switches, else the one of the scene
    that controls it (a burner's knob), None when nothing does."""
    if load_affordances().switch.property in type_props(type_):
        return type_
    ids = {o.id for o in ctx.state.of_type(type_)}
    return next((o.type for o in ctx.state.objects.values() if ids & set(o.controls)), None)


def _unswitched(ctx: DoubtContext) -> list[Doubt]:
    switched = {t for c in (*ctx.goals, *ctx.steps) if c.predicate in _OTHER for t in ref_types(c.subject)}
    out = []
    seen: set[str] = set()
    for _, item, types in ctx.mentions():
        device = _switched_by(ctx, types[0])
        if device is None or device in switched or device in seen:
            continue
        seen.add(device)
        now = {o.is_on for o in ctx.state.of_type(device)}
        if len(now) != 1:
            continue
        c = one_object(Predicate.switched_off if now == {True} else Predicate.switched_on, device)
        out.append(Doubt(KIND, item.text, (Choice(AS_READ, f"{item.text!r} leaves the {type_name(device)} as it is"),
                                           Choice("mentioned", clause(c), add=(c,)))))
    return out


def doubts(ctx: DoubtContext) -> list[Doubt]:
    return [*_flips(ctx), *_unswitched(ctx)]


__all__ = ["KIND", "doubts"]
