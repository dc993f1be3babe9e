"""Random, mutually consistent goal conditions over a scene: test inputs for the
domain/simulator agreement tests and the planner's scaling benchmark.

Each object takes at most one condition per *aspect* (where it is, its temperature, its
form, its door, its power, its liquid, its cleanliness), and combinations no plan can
reach are never drawn: a running open microwave (the door interlock), a broken appliance
switched on, a hot object in a fridge, a broken egg (cracking it consumes it). The goals
are meant to be solvable, not guaranteed to be: the tests count what the planner proves
unsolvable.
"""

from __future__ import annotations

import random
from collections.abc import Sequence

from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.catalogue import (
    BREWERS,
    COLD_SOURCES,
    HEATERS,
    INTERLOCKED,
    WATER_SOURCES,
    load_catalogue,
)
from emboteam.world.goals import Condition, Goal, ObjectRef, Predicate
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import ObjectState, WorldState

#: predicate -> the aspect of its subject it fixes
ASPECT: dict[Predicate, str] = {
    Predicate.inside: "loc", Predicate.held: "loc", Predicate.hot: "temp", Predicate.cold: "temp",
    Predicate.cooked: "cook", Predicate.sliced: "form", Predicate.broken: "form",
    Predicate.open: "door", Predicate.closed: "door", Predicate.switched_on: "power",
    Predicate.switched_off: "power", Predicate.filled: "liquid", Predicate.clean: "clean",
}


def _cond(pred: Predicate, o: ObjectState, *, by_type: bool, place: ObjectState | None = None,
          liquid: str | None = None) -> Condition:
    subject = ObjectRef(types=(o.type,)) if by_type else ObjectRef(id=o.id)
    receptacle = None
    if place is not None:
        receptacle = ObjectRef(types=(place.type,)) if by_type else ObjectRef(id=place.id)
    return Condition(predicate=pred, subject=subject, receptacle=receptacle, liquid=liquid)


def candidate_conditions(state: WorldState, rng: random.Random, *, max_mass: float = 100.0,
                         type_refs: float = 0.3) -> list[tuple[str, Condition]]:
    """Every condition worth drawing, as (subject id, condition), shuffled."""
    cat = load_catalogue()
    objs = [o for o in state.objects.values() if not o.gone and o.source is None]
    counts: dict[str, int] = {}
    for o in objs:
        counts[o.type] = counts.get(o.type, 0) + 1
    fridges = [o for o in objs if o.type in COLD_SOURCES]
    heaters = [o for o in objs if o.type in HEATERS & INTERLOCKED]  # hot/cooked goals are drawn for microwaves
    basins = [state.objects[b] for f in objs if f.type in WATER_SOURCES for b in f.controls
              if b in state.objects and state.objects[b].has("receptacle")]
    out: list[tuple[str, Condition]] = []
    for o in objs:
        # a type reference only where the type is unique: "any Cabinet" is too easy
        by_type = counts[o.type] == 1 and rng.random() < type_refs
        if o.has("pickupable") and o.mass <= max_mass:
            places = [r for r in objs if r.has("receptacle") and r.id != o.id and r.id != o.parent
                      and cat.can_place(o.type, r.type) and o.id not in state.ancestors(r.id)
                      and r.type not in ("Floor", "GarbageCan")]
            if places:
                place = rng.choice(sorted(places, key=lambda r: r.id))
                unique = by_type and counts[place.type] == 1
                out.append((o.id, _cond(Predicate.inside, o, by_type=unique, place=place)))
            if any(cat.can_place(o.type, h.type) for h in heaters):
                out.append((o.id, _cond(Predicate.hot, o, by_type=by_type)))
            if any(cat.can_place(o.type, f.type) for f in fridges):
                out.append((o.id, _cond(Predicate.cold, o, by_type=by_type)))
            wettable = any(cat.can_place(o.type, b.type) for b in basins)
            if o.has("canFillWithLiquid") and wettable:
                out.append((o.id, _cond(Predicate.filled, o, by_type=by_type, liquid="water")))
            if o.has("cookable") and heaters:
                out.append((o.id, _cond(Predicate.cooked, o, by_type=by_type)))
        if o.has("sliceable") and cat.slice_product(o.type) is not None and o.type != "Egg":
            out.append((o.id, _cond(Predicate.sliced, o, by_type=by_type)))
        if o.has("breakable") and o.type != "Egg" and not o.is_broken:
            out.append((o.id, _cond(Predicate.broken, o, by_type=by_type)))
        if o.has("openable"):
            pred = Predicate.closed if o.is_open else Predicate.open
            out.append((o.id, _cond(pred, o, by_type=by_type)))
        if o.has("toggleable"):
            pred = Predicate.switched_off if o.is_on else Predicate.switched_on
            out.append((o.id, _cond(pred, o, by_type=by_type)))
        if o.has("dirtyable") and o.is_dirty and o.has("pickupable") and any(
                cat.can_place(o.type, b.type) for b in basins):
            out.append((o.id, _cond(Predicate.clean, o, by_type=by_type)))
    rng.shuffle(out)
    return out


def _compatible(oid: str, cond: Condition, taken: dict[str, dict[str, Condition]],
                state: WorldState) -> bool:
    mine = taken.get(oid, {})
    aspect = ASPECT[cond.predicate]
    if aspect in mine:
        return False
    o = state.objects[oid]
    preds = {c.predicate for c in mine.values()} | {cond.predicate}
    if o.type in INTERLOCKED and {Predicate.open, Predicate.switched_on} <= preds:
        return False
    if Predicate.broken in preds and preds & {Predicate.switched_on, Predicate.switched_off}:
        return False
    if Predicate.hot in preds and Predicate.inside in preds:
        where = next(c for c in (*mine.values(), cond) if c.predicate is Predicate.inside)
        assert where.receptacle is not None
        if any(t in COLD_SOURCES for t in (*where.receptacle.types, (where.receptacle.id or "").split("_")[0])):
            return False
    if Predicate.cold in preds and Predicate.inside in preds:
        where = next(c for c in (*mine.values(), cond) if c.predicate is Predicate.inside)
        assert where.receptacle is not None
        if any(t in HEATERS | BREWERS
               for t in (*where.receptacle.types, (where.receptacle.id or "").split("_")[0])):
            return False
    return True


def random_conditions(state: WorldState, n: int, rng: random.Random, *, max_mass: float = 100.0,
                      type_refs: float = 0.3, exclude: Sequence[Predicate] = ()) -> list[Condition]:
    """Up to ``n`` mutually consistent conditions (fewer if the scene has fewer)."""
    taken: dict[str, dict[str, Condition]] = {}
    out: list[Condition] = []
    for oid, cond in candidate_conditions(state, rng, max_mass=max_mass, type_refs=type_refs):
        if len(out) >= n:
            break
        if cond.predicate in exclude or not _compatible(oid, cond, taken, state):
            continue
        taken.setdefault(oid, {})[ASPECT[cond.predicate]] = cond
        out.append(cond)
    return out


#: the scaling sweep's teams cycle through these profiles (all-rounders and specialists),
#: so a team of N robots is the same in every benchmark and test that builds one
SWEEP_PROFILES = (1, 2, 3, 4, 9, 6, 19, 14)


def goal_cell(scene: str, profiles: Sequence[int], conditions: int, seed: int = 0) -> tuple[TaskSpec, WorldState]:
    """A planner input: the team ``profiles`` in ``scene`` and ``conditions`` random
    consistent conditions drawn from ``seed``, one subtask per condition."""
    team = parse_team(list(profiles))
    state = WorldState.from_scene(load_scene(scene), team)
    conds = random_conditions(state, conditions, random.Random(seed))
    spec = TaskSpec(instruction=str(Goal(conditions=tuple(conds))), subtasks=tuple(
        Subtask(id=f"c{i}", description=str(c), goal=(c,)) for i, c in enumerate(conds, 1)))
    return spec, state


def sweep_cell(scene: str, robots: int, conditions: int, seed: int = 0) -> tuple[TaskSpec, WorldState]:
    """One cell of the scaling sweep (benchmarks/plan_latency.py): ``robots`` robots cycling
    through :data:`SWEEP_PROFILES`."""
    return goal_cell(scene, [SWEEP_PROFILES[i % len(SWEEP_PROFILES)] for i in range(robots)], conditions, seed)
