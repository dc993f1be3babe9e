"""Scripted per-robot action lists: the stand-in for an LLM that writes action lists directly.

The ``no-pfg-hp`` ablation and the SMART-LLM baseline need an LLM's free-form per-robot
action lists. Without an LLM, this module stands in for it, and results say so
("scripted stand-in"). It writes what SMART-LLM's few-shot programs write for each goal
condition — go to the object, open what must be opened, pick up, go, put; take a knife
to slice and put it back — and allocates each condition's script to one robot that has
every skill it needs (as SMART-LLM allocates subtasks), or, when no single robot has them,
splits the script action by action over robots that have each skill, in order, with no
synchronisation: exactly the weakness a planner and a behavior tree address.

It reads the scene (which objects exist, which receptacle encloses what) but plans
nothing: no preconditions are checked, no mass capacity, no cross-robot ordering.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from emboteam.world.actions import Action, Skill
from emboteam.world.catalogue import (
    BREWERS,
    COLD_SOURCES,
    INTERLOCKED,
    KNIVES,
    WATER_SOURCES,
    load_catalogue,
    place_types,
)
from emboteam.world.goals import Condition, Goal, ObjectRef, Predicate
from emboteam.world.robots import RobotProfile
from emboteam.world.state import ObjectState, WorldState

S = Skill


def _pick(ref: ObjectRef, state: WorldState, near: tuple[float, float], taken: set[str],
          *, receptacle: bool = False) -> ObjectState | None:
    """The object a script writer would name: the id, or the nearest instance of the type."""
    if ref.id is not None:
        return state.objects.get(ref.id)
    types = place_types(ref.types) if receptacle else frozenset(ref.types)
    cands = [o for o in state.objects.values() if o.type in types and not o.gone and o.id not in taken]
    if not cands:
        return None
    return min(cands, key=lambda o: (math.hypot(o.position[0] - near[0], o.position[2] - near[1]), o.id))


def _fetch(o: ObjectState, state: WorldState) -> list[Action]:
    steps = [Action(skill=S.GoToObject, target=o.id)]
    hider = state.enclosing_closed(o.id)
    if hider is not None:
        steps.append(Action(skill=S.OpenObject, target=hider))
    steps.append(Action(skill=S.PickupObject, target=o.id))
    return steps


def _deliver(o: ObjectState, rec: ObjectState, state: WorldState) -> list[Action]:
    steps = [Action(skill=S.GoToObject, target=rec.id)]
    if rec.type in load_catalogue().must_be_open and not rec.is_open:
        steps.append(Action(skill=S.OpenObject, target=rec.id))
    steps.append(Action(skill=S.PutObject, target=o.id, receptacle=rec.id))
    return steps


def _first(state: WorldState, *types: str) -> ObjectState | None:
    return next(iter(sorted(state.of_type(*types), key=lambda o: o.id)), None)


def script_for(cond: Condition, state: WorldState, near: tuple[float, float],
               taken: set[str]) -> list[Action]:
    """The action list a script writer would produce for one condition (one instance)."""
    o = _pick(cond.subject, state, near, taken)
    if o is None:
        return []
    taken.add(o.id)
    p = cond.predicate
    if p is Predicate.inside:
        assert cond.receptacle is not None
        rec = _pick(cond.receptacle, state, (o.position[0], o.position[2]), set(), receptacle=True)
        if rec is None:
            return []
        if rec.type == "GarbageCan":
            return [*_fetch(o, state), Action(skill=S.GoToObject, target=rec.id),
                    Action(skill=S.ThrowObject, target=o.id)]
        return _fetch(o, state) + _deliver(o, rec, state)
    if p in (Predicate.switched_on, Predicate.switched_off):
        skill = S.SwitchOn if p is Predicate.switched_on else S.SwitchOff
        return [Action(skill=S.GoToObject, target=o.id), Action(skill=skill, target=o.id)]
    if p in (Predicate.open, Predicate.closed):
        skill = S.OpenObject if p is Predicate.open else S.CloseObject
        return [Action(skill=S.GoToObject, target=o.id), Action(skill=skill, target=o.id)]
    if p is Predicate.broken:
        return [Action(skill=S.GoToObject, target=o.id), Action(skill=S.BreakObject, target=o.id)]
    if p is Predicate.held:
        return _fetch(o, state)
    if p is Predicate.sliced:
        knife = _first(state, *sorted(KNIVES))
        if knife is None:
            return []
        back = knife.parent or o.parent or o.id
        return [*_fetch(knife, state), Action(skill=S.GoToObject, target=o.id),
                Action(skill=S.SliceObject, target=o.id), Action(skill=S.GoToObject, target=back),
                Action(skill=S.PutObject, target=knife.id, receptacle=back)]
    if p in (Predicate.hot, Predicate.cooked):
        oven = _first(state, *sorted(INTERLOCKED))      # the microwave: closed, then run
        if oven is None:
            return []
        return [*_fetch(o, state), *_deliver(o, oven, state),
                Action(skill=S.CloseObject, target=oven.id), Action(skill=S.SwitchOn, target=oven.id)]
    if p is Predicate.cold:
        fridge = _first(state, *sorted(COLD_SOURCES))
        return [] if fridge is None else _fetch(o, state) + _deliver(o, fridge, state)
    if p in (Predicate.clean, Predicate.filled):
        if cond.liquid == "coffee":
            machine = _first(state, *sorted(BREWERS))
            if machine is None:
                return []
            return [*_fetch(o, state), *_deliver(o, machine, state),
                    Action(skill=S.SwitchOn, target=machine.id)]
        basin, faucet = _first(state, "SinkBasin"), _first(state, *sorted(WATER_SOURCES))
        if basin is None or faucet is None:
            return []
        return [*_fetch(o, state), *_deliver(o, basin, state), Action(skill=S.GoToObject, target=faucet.id),
                Action(skill=S.SwitchOn, target=faucet.id)]
    return []


def scripted_action_lists(goal: Goal, state: WorldState,
                          team: Sequence[RobotProfile]) -> dict[str, list[Action]]:
    """Per-robot action lists for a goal, SMART-LLM style (see module docstring)."""
    lists: dict[str, list[Action]] = {p.name: [] for p in team}
    load: dict[str, int] = dict.fromkeys(lists, 0)
    taken: set[str] = set()
    for cond in goal.conditions:
        for _ in range(cond.count):
            near = state.robots[team[0].name].position if team else (0.0, 0.0)
            script = script_for(cond, state, near, taken)
            if not script:
                continue
            needed = {a.skill for a in script}
            capable = [p for p in team if needed <= p.skills]
            if capable:
                robot = min(capable, key=lambda p: (load[p.name], p.name)).name
                lists[robot].extend(script)
                load[robot] += len(script)
                continue
            for action in script:  # no single robot can: split by skill, unsynchronised
                able = [p for p in team if action.skill in p.skills]
                if not able:
                    continue
                robot = min(able, key=lambda p: (load[p.name], p.name)).name
                if action.skill is not S.GoToObject and (not lists[robot] or lists[robot][-1].target
                                                         not in (action.target, action.receptacle)):
                    lists[robot].append(Action(skill=S.GoToObject, target=action.receptacle or action.target))
                lists[robot].append(action)
                load[robot] += 1
    return lists
