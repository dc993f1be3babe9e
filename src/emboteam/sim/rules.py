"""AI2-THOR's action rules on the symbolic state: when an action may run, and what it does.

Pure functions of (state, robot, action), no time and no faults: the simulator adds
those. Each check returns a typed :class:`Failure` or ``None``; :func:`apply_action`
assumes the check passed. Rules follow AI2-THOR 5.x (docs/world.md, docs/architecture.md); choices where AI2-THOR is
silent are documented on the function that makes them and in docs/world.md.
"""

from __future__ import annotations

from dataclasses import dataclass

from emboteam.sim.physics import settle, switch
from emboteam.world.actions import Action, FailureReason, Skill
from emboteam.world.catalogue import BURNERS, INTERLOCKED, KNIVES, load_catalogue
from emboteam.world.navigation import arrival_point
from emboteam.world.state import ObjectState, WorldState

R = FailureReason

@dataclass(frozen=True, slots=True)
class Failure:
    reason: FailureReason
    message: str


def _visible(state: WorldState, robot: str, o: ObjectState) -> Failure | None:
    if o.gone:
        return Failure(R.ALREADY_SLICED, f"{o.id} was sliced; its pieces remain")
    if o.held_by is not None and o.held_by != robot:
        return Failure(R.HELD_BY_OTHER, f"{o.id} is held by {o.held_by}")
    hider = state.enclosing_closed(o.id)
    if hider is not None:
        return Failure(R.NOT_VISIBLE, f"{o.id} is inside closed {hider}")
    if not state.in_reach(robot, o.id):
        return Failure(R.NOT_REACHABLE, f"{o.id} is {state.distance(robot, o.id):.1f} m away "
                       f"(reach 1.5 m): go to it first")
    return None


def check_action(state: WorldState, robot: str, action: Action) -> Failure | None:
    """Why ``robot`` cannot do ``action`` now, or ``None`` if it can."""
    r = state.robots[robot]
    if r.down:
        return Failure(R.ROBOT_DOWN, f"{robot} is down")
    if not r.profile.can(action.skill):
        return Failure(R.MISSING_SKILL, f"{robot} cannot {action.skill.value}")
    for oid in (action.target, action.receptacle):
        if oid is not None and oid not in state.objects:
            return Failure(R.UNKNOWN_OBJECT, f"no object {oid!r} in {state.floor_plan}")
    o = state.objects[action.target]
    skill = action.skill
    cat = load_catalogue()

    if skill is Skill.GoToObject:
        if o.gone:
            return Failure(R.ALREADY_SLICED, f"{o.id} was sliced; its pieces remain")
        return None

    if skill in (Skill.PutObject, Skill.ThrowObject, Skill.DropHandObject):
        if r.holding is None:
            return Failure(R.HAND_EMPTY, f"{robot} holds nothing")
        if r.holding != o.id:
            return Failure(R.NOT_HOLDING_TARGET, f"{robot} holds {r.holding}, not {o.id}")
        if skill is Skill.PutObject:
            if action.receptacle is None:
                return Failure(R.NOT_A_RECEPTACLE, "PutObject needs a receptacle")
            rec = state.objects[action.receptacle]
            if not rec.has("receptacle"):
                return Failure(R.NOT_A_RECEPTACLE, f"{rec.id} is not a receptacle")
            if rec.id == o.id or rec.id in {d.id for d in state.descendants(o.id)}:
                return Failure(R.NOT_ALLOWED_HERE, f"{o.id} cannot go into itself")
            failure = _visible(state, robot, rec)
            if failure is not None:
                return failure
            if rec.held_by is not None:
                return Failure(R.NOT_ALLOWED_HERE, f"{rec.id} is held by {rec.held_by}")
            if rec.type in cat.must_be_open and not rec.is_open:
                return Failure(R.RECEPTACLE_CLOSED, f"{rec.id} must be open to put things in")
            if not cat.can_place(o.type, rec.type):
                return Failure(R.NOT_ALLOWED_HERE, f"a {o.type} cannot go in/on a {rec.type}")
        if skill is Skill.ThrowObject and _garbage_in_reach(state, robot) is None:
            return Failure(R.NO_GARBAGE_CAN, f"no GarbageCan within reach of {robot}")
        return None

    failure = _visible(state, robot, o)
    if failure is not None:
        return failure

    if skill is Skill.PickupObject:
        if not o.has("pickupable"):
            return Failure(R.NOT_PICKUPABLE, f"{o.id} cannot be picked up")
        if r.holding is not None:
            return Failure(R.HAND_FULL, f"{robot} already holds {r.holding}")
        if o.mass > r.profile.mass_capacity:
            return Failure(R.TOO_HEAVY, f"{o.id} weighs {o.mass:g} kg, {robot} lifts "
                           f"{r.profile.mass_capacity:g} kg")
        return None
    if skill in (Skill.OpenObject, Skill.CloseObject):
        if not o.has("openable"):
            return Failure(R.NOT_OPENABLE, f"{o.id} cannot be opened or closed")
        if skill is Skill.OpenObject and o.is_open:
            return Failure(R.ALREADY_OPEN, f"{o.id} is already open")
        if skill is Skill.CloseObject and not o.is_open:
            return Failure(R.ALREADY_CLOSED, f"{o.id} is already closed")
        if skill is Skill.OpenObject and o.type in INTERLOCKED and o.is_on:
            return Failure(R.ALREADY_ON, f"{o.id} is running: switch it off before opening it")
        return None
    if skill in (Skill.SwitchOn, Skill.SwitchOff):
        if not o.has("toggleable"):
            hint = " (switch its StoveKnob)" if o.type in BURNERS else ""
            return Failure(R.NOT_TOGGLEABLE, f"{o.id} cannot be switched{hint}")
        if skill is Skill.SwitchOn and o.is_on:
            return Failure(R.ALREADY_ON, f"{o.id} is already on")
        if skill is Skill.SwitchOff and not o.is_on:
            return Failure(R.ALREADY_OFF, f"{o.id} is already off")
        if skill is Skill.SwitchOn and o.is_broken:
            return Failure(R.ALREADY_BROKEN, f"{o.id} is broken and no longer switches on")
        if skill is Skill.SwitchOn and o.type in INTERLOCKED and o.is_open:
            return Failure(R.ALREADY_OPEN, f"{o.id} is open: close it before switching it on")
        return None
    if skill is Skill.SliceObject:
        if not o.has("sliceable") or cat.slice_product(o.type) is None:
            return Failure(R.NOT_SLICEABLE, f"{o.id} cannot be sliced")
        if o.is_sliced:
            return Failure(R.ALREADY_SLICED, f"{o.id} is already sliced")
        if o.held_by is not None:
            return Failure(R.NOT_ALLOWED_HERE, f"put {o.id} down before slicing it")
        held = state.objects[r.holding].type if r.holding else None
        if held not in KNIVES:
            return Failure(R.NO_KNIFE, f"{robot} must hold a Knife or ButterKnife to slice")
        return None
    if skill is Skill.BreakObject:
        if not o.has("breakable"):
            return Failure(R.NOT_BREAKABLE, f"{o.id} cannot be broken")
        if o.is_broken:
            return Failure(R.ALREADY_BROKEN, f"{o.id} is already broken")
        return None
    if skill is Skill.CleanObject:
        if not o.has("dirtyable"):
            return Failure(R.NOT_DIRTYABLE, f"{o.id} cannot get dirty or clean")
        if not o.is_dirty:
            return Failure(R.ALREADY_CLEAN, f"{o.id} is already clean")
        return None
    if skill in (Skill.PushObject, Skill.PullObject):
        if not (o.has("moveable") or o.has("pickupable")):
            return Failure(R.NOT_MOVEABLE, f"{o.id} does not move")
        return None
    raise AssertionError(f"unhandled skill {skill}")


def _garbage_in_reach(state: WorldState, robot: str) -> ObjectState | None:
    cans = [g for g in state.of_type("GarbageCan") if state.in_reach(robot, g.id)]
    return min(cans, key=lambda g: state.distance(robot, g.id)) if cans else None


def _floor_for(state: WorldState) -> str | None:
    floors = list(state.of_type("Floor"))
    return floors[0].id if floors else None


def apply_action(state: WorldState, robot: str, action: Action) -> None:
    """Apply a checked action's effects, then its side effects (heat, cold, water).

    - GoToObject puts the robot on the object's interaction pose that the simulator's drive
      from where it stands ends at when nobody is in the way (a held object's point is its
      holder's), so what a plan thinks is in reach there is what the simulator finds.
    - SliceObject spawns the catalogue's pieces on the whole's receptacle; the whole is
      deactivated (``gone``), as AI2-THOR does. Breaking an Egg cracks it the same way.
    - ThrowObject lands the held object in the nearest GarbageCan within reach whatever the
      placement rules (AI2-THOR semantics, docs/world.md: "the held object ends in a GarbageCan").
    - DropHandObject drops it on the floor under the robot.
    - BreakObject switches a running object off (a broken Television or Laptop cannot be
      switched on again, see :func:`check_action`).
    - PushObject/PullObject only shift a position in AI2-THOR, which the symbolic state
      does not model: they succeed without a symbolic effect.
    """
    r = state.robots[robot]
    o = state.objects[action.target]
    skill = action.skill
    if skill is Skill.GoToObject:
        x, _, z = o.position
        r.position = arrival_point(state.floor_plan, r.position, (x, z))
        r.at = o.id
        if r.holding is not None:
            state.attach_to_robot(r.holding, robot)
    elif skill is Skill.PickupObject:
        state.attach_to_robot(o.id, robot)
    elif skill is Skill.PutObject:
        assert action.receptacle is not None
        r.holding = None
        state.move_object(o.id, action.receptacle)
    elif skill is Skill.ThrowObject:
        can = _garbage_in_reach(state, robot)
        assert can is not None
        r.holding = None
        state.move_object(o.id, can.id)
    elif skill is Skill.DropHandObject:
        r.holding = None
        state.move_object(o.id, _floor_for(state), position=(r.position[0], 0.0, r.position[1]))
    elif skill is Skill.OpenObject:
        o.is_open = True
    elif skill is Skill.CloseObject:
        o.is_open = False
    elif skill in (Skill.SwitchOn, Skill.SwitchOff):
        switch(state, o, on=skill is Skill.SwitchOn)
    elif skill is Skill.SliceObject:
        _cut(state, o)
    elif skill is Skill.BreakObject:
        o.is_broken = True
        if o.has("toggleable") and o.is_on:
            switch(state, o, on=False)  # AI2-THOR: a broken TV or laptop goes off for good
        if o.type == "Egg":
            _cut(state, o)
    elif skill is Skill.CleanObject:
        o.is_dirty = False
    settle(state)


def piece_ids(whole_id: str, n: int) -> list[str]:
    """Ids of the pieces a sliced object becomes (the planner declares them ahead)."""
    return [f"{whole_id}_Slice_{k}" for k in range(1, n + 1)]


def _cut(state: WorldState, whole: ObjectState) -> None:
    cat = load_catalogue()
    product = cat.slice_product(whole.type)
    if product is None:
        return
    piece_type, n = product
    ptype = cat.type(piece_type)
    whole.is_sliced = True
    for pid in piece_ids(whole.id, n):
        state.objects[pid] = ObjectState(
            id=pid, type=piece_type, properties=ptype.properties | {"pickupable"},
            mass=round(whole.mass / n, 4), position=whole.position, parent=whole.parent,
            is_sliced=True, is_cooked=whole.is_cooked, temperature=whole.temperature,
            is_dirty=False, source=whole.id,
        )
