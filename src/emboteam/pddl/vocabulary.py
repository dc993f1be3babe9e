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
from emboteam.world.catalogue import KNIVES, load_catalogue
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
    "has-coffee", "hot", "cold", "cooked", "at",
})


def observable(literal: Literal) -> bool:
    """Should a Post condition check this effect? Negative ``at`` is never checked."""
    if literal.predicate == "at" and not literal.positive:
        return False
    return literal.predicate in OBSERVABLE_POST
