"""The PDDL predicate vocabulary and its meaning on a :class:`WorldState`.

This module is the *abstraction function* between the symbolic simulator and the
planner: the problem renderer writes the initial state by evaluating these predicates,
and the behavior-tree condition nodes (Pre/Post) evaluate a plan step's literals with the
same functions on what the robot observes. One definition, so planner and executor cannot
disagree about what ``(in Apple_1 Fridge_1)`` means.

Fluents are evaluated on the live state; static facts (types, placement, capability)
never change during an episode.
"""

from __future__ import annotations

from collections.abc import Callable

from emboteam.pddl.literal import Literal
from emboteam.sim.physics import is_cold_source
from emboteam.sim.rules import piece_ids
from emboteam.world.catalogue import BREWERS, BURNERS, INTERLOCKED, KNIVES, WATER_SOURCES, load_catalogue
from emboteam.world.catalogue import HEATERS as HEATING
from emboteam.world.state import WorldState

Evaluator = Callable[..., bool]


def _obj_has(prop: str) -> Evaluator:
    return lambda s, o: prop in s.objects[o].properties if o in s.objects else False


def _available(s: WorldState, o: str) -> bool:
    """The object exists and can be interacted with (not a sliced-away whole, not an
    unspawned slice)."""
    return o in s.objects and not s.objects[o].gone


def _hidden(s: WorldState, o: str) -> bool:
    return o in s.objects and s.enclosing_closed(o) is not None


def _at(s: WorldState, r: str, o: str) -> bool:
    """The robot can reach the object (after GoToObject(o) it always can)."""
    return o in s.objects and r in s.robots and s.in_reach(r, o)


def _can_place(s: WorldState, o: str, r: str) -> bool:
    return load_catalogue().can_place(s.objects[o].type, s.objects[r].type)


def _can_lift(s: WorldState, r: str, o: str) -> bool:
    return s.objects[o].mass <= s.robots[r].profile.mass_capacity


# ---- predicates added for the planner's domain (emboteam.pddl.domain) -------------------
# Each mirrors one rule of sim/rules.py or sim/physics.py, so a plan step's conditions and
# effects can be checked on the live state like the original vocabulary.

def _carried(s: WorldState, o: str) -> bool:
    """Held by a robot, or in/on something that is (an apple on a carried plate)."""
    if o not in s.objects:
        return False
    return any(s.objects[x].held_by is not None for x in (o, *s.ancestors(o)))


def _place_chain(s: WorldState, c: str) -> list[str]:
    return [c, *s.ancestors(c)] if c in s.objects else []


def _cools(s: WorldState, o: str) -> bool:
    return is_cold_source(s.objects[o])


def _chilled_place(s: WorldState, c: str) -> bool:
    """Something put in/on ``c`` turns Cold: ``c`` is a cooling Fridge or inside one."""
    return any(_cools(s, a) for a in _place_chain(s, c))


def _heated_place(s: WorldState, c: str) -> bool:
    """Something put in/on ``c`` heats: ``c`` is a running heater or inside one."""
    return any(s.objects[a].type in HEATING and s.objects[a].is_on for a in _place_chain(s, c))


def _watered_place(s: WorldState, c: str) -> bool:
    """Running water reaches ``c``: it is a basin of a running faucet, or inside one."""
    chain = set(_place_chain(s, c))
    return any(f.type in WATER_SOURCES and f.is_on and chain.intersection(f.controls)
               for f in s.objects.values())


def _piece_of(s: WorldState, p: str, o: str) -> bool:
    """``p`` is one of the pieces slicing ``o`` yields (``Apple_1_Slice_2`` of ``Apple_1``),
    whether or not it has been cut yet."""
    if o not in s.objects or s.objects[o].source is not None:
        return False
    product = load_catalogue().slice_product(s.objects[o].type)
    return product is not None and p in piece_ids(o, product[1])


def _is_floor(s: WorldState, o: str) -> bool:
    """The Floor a dropped object lands on (sim.rules drops onto the first Floor)."""
    floors = [x.id for x in s.of_type("Floor")]
    return bool(floors) and floors[0] == o


#: fluent name -> (argument kinds, evaluator); argument kinds: r = robot, o = object
FLUENTS: dict[str, tuple[str, Evaluator]] = {
    "at": ("ro", _at),
    "holding": ("ro", lambda s, r, o: s.robots[r].holding == o),
    "hand-empty": ("r", lambda s, r: s.robots[r].holding is None),
    "in": ("oo", lambda s, o, r: o in s.objects and s.objects[o].parent == r),
    "within": ("oo", lambda s, o, r: o in s.objects and s.is_within(o, r)),
    "is-open": ("o", lambda s, o: s.objects[o].is_open),
    "is-on": ("o", lambda s, o: s.objects[o].is_on),
    "sliced": ("o", lambda s, o: o in s.objects and s.objects[o].is_sliced),
    "broken": ("o", lambda s, o: s.objects[o].is_broken),
    "dirty": ("o", lambda s, o: s.objects[o].is_dirty),
    "filled": ("o", lambda s, o: s.objects[o].liquid is not None),
    "has-coffee": ("o", lambda s, o: s.objects[o].liquid == "coffee"),
    "hot": ("o", lambda s, o: o in s.objects and s.objects[o].temperature == "Hot"),
    "cold": ("o", lambda s, o: o in s.objects and s.objects[o].temperature == "Cold"),
    "cooked": ("o", lambda s, o: o in s.objects and s.objects[o].is_cooked),
    "available": ("o", _available),
    "hidden": ("o", _hidden),
    "robot-up": ("r", lambda s, r: not s.robots[r].down),
    # added for the planner's domain
    "has-water": ("o", lambda s, o: s.objects[o].liquid == "water"),
    "has-wine": ("o", lambda s, o: s.objects[o].liquid == "wine"),
    "carried": ("o", _carried),
    "chilled-place": ("o", _chilled_place),
    "heated-place": ("o", _heated_place),
    "watered-place": ("o", _watered_place),
}

#: static predicate name -> (argument kinds, evaluator)
STATICS: dict[str, tuple[str, Evaluator]] = {
    "pickupable": ("o", _obj_has("pickupable")),
    "receptacle": ("o", _obj_has("receptacle")),
    "openable": ("o", _obj_has("openable")),
    "toggleable": ("o", _obj_has("toggleable")),
    "sliceable": ("o", _obj_has("sliceable")),
    "breakable": ("o", _obj_has("breakable")),
    "dirtyable": ("o", _obj_has("dirtyable")),
    "fillable": ("o", _obj_has("canFillWithLiquid")),
    "cookable": ("o", _obj_has("cookable")),
    "moveable": ("o", lambda s, o: s.objects[o].has("moveable") or s.objects[o].has("pickupable")),
    "must-open": ("o", lambda s, o: s.objects[o].type in load_catalogue().must_be_open),
    "knife": ("o", lambda s, o: s.objects[o].type in KNIVES),
    "garbage": ("o", lambda s, o: s.objects[o].type == "GarbageCan"),
    "can-place": ("oo", _can_place),
    "can-lift": ("ro", _can_lift),
    "controls": ("oo", lambda s, k, b: b in s.objects[k].controls),
    # added for the planner's domain
    "cools": ("o", _cools),
    "heats": ("o", lambda s, o: s.objects[o].type in HEATING),
    "brews": ("o", lambda s, o: s.objects[o].type in BREWERS),
    "mug": ("o", lambda s, o: s.objects[o].type == "Mug"),
    "interlocked": ("o", lambda s, o: s.objects[o].type in INTERLOCKED),
    "cracks": ("o", lambda s, o: s.objects[o].type == "Egg"),
    "switches": ("oo", lambda s, k, b: s.objects[k].type == "StoveKnob" and b in s.objects[k].controls
                 and s.objects[b].type in BURNERS),
    "waters": ("oo", lambda s, f, b: s.objects[f].type in WATER_SOURCES and b in s.objects[f].controls),
    "piece-of": ("oo", _piece_of),
    "floor": ("o", _is_floor),
}

#: one capability predicate per skill: (can-pickup robot1) ...
CAPABILITIES: dict[str, str] = {
    "GoToObject": "can-goto", "PickupObject": "can-pickup", "PutObject": "can-put",
    "OpenObject": "can-open", "CloseObject": "can-close", "SwitchOn": "can-switch-on",
    "SwitchOff": "can-switch-off", "SliceObject": "can-slice", "BreakObject": "can-break",
    "CleanObject": "can-clean", "ThrowObject": "can-throw", "DropHandObject": "can-drop",
    "PushObject": "can-push", "PullObject": "can-pull",
}


def evaluate(literal: Literal, state: WorldState) -> bool:
    """Truth of a ground literal on the state. Unknown predicates raise KeyError.

    Capability literals are evaluated from the robot's profile; an object that does not
    exist (an unspawned slice) makes every positive fluent about it false.
    """
    name, args = literal.predicate, literal.args
    if name in FLUENTS:
        _, fn = FLUENTS[name]
        try:
            value = bool(fn(state, *args))
        except KeyError:
            value = False
    elif name in STATICS:
        _, fn = STATICS[name]
        try:
            value = bool(fn(state, *args))
        except KeyError:
            value = False
    else:
        skill = next((k for k, v in CAPABILITIES.items() if v == name), None)
        if skill is None:
            raise KeyError(f"unknown PDDL predicate {name!r}")
        robot = state.robots.get(args[0])
        value = robot is not None and any(s.value == skill for s in robot.profile.skills)
    return value if literal.positive else not value


#: fluents a Post check may look at: the rest (``at`` after leaving, ``hand-empty``) are
#: bookkeeping whose observed value can legitimately differ from the plan's idea of it
#: (a robot next to the fridge is also "at" the apple on the counter beside it).
OBSERVABLE_POST = frozenset({
    "holding", "in", "within", "is-open", "is-on", "sliced", "broken", "dirty", "filled",
    "has-coffee", "hot", "cold", "cooked", "at", "has-water", "has-wine",
})


def observable(literal: Literal) -> bool:
    """Should a Post condition check this effect? Negative ``at`` is never checked."""
    if literal.predicate == "at" and not literal.positive:
        return False
    return literal.predicate in OBSERVABLE_POST
