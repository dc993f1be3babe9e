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
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.catalogue import (
    BREWERS,
    COLD_SOURCES,
    HEATERS,
    INTERLOCKED,
    WATER_SOURCES,
    Catalogue,
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


@dataclass(frozen=True)
class _Scene:
    """What the condition rules read about a scene: computed once in
    :func:`candidate_conditions`, so that each rule stays small and all see the same facts."""

    state: WorldState
    cat: Catalogue
    #: the objects conditions are drawn over (present, not pieces of another)
    objs: list[ObjectState]
    #: objects per type: a type reference only where the type is unique
    counts: dict[str, int]
    fridges: list[ObjectState]
    #: hot/cooked goals are drawn for microwaves (heaters with a door interlock)
    heaters: list[ObjectState]
    #: the receptacles water sources fill (sinks and basins)
    basins: list[ObjectState]

    @classmethod
    def of(cls, state: WorldState) -> _Scene:
        objs = [o for o in state.objects.values() if not o.gone and o.source is None]
        counts: dict[str, int] = {}
        for o in objs:
            counts[o.type] = counts.get(o.type, 0) + 1
        basins = [state.objects[b] for f in objs if f.type in WATER_SOURCES for b in f.controls
                  if b in state.objects and state.objects[b].has("receptacle")]
        return cls(state, load_catalogue(), objs, counts,
                   fridges=[o for o in objs if o.type in COLD_SOURCES],
                   heaters=[o for o in objs if o.type in HEATERS & INTERLOCKED], basins=basins)

    def fits_any(self, o: ObjectState, places: Sequence[ObjectState]) -> bool:
        """Can ``o`` be put into one of ``places``?"""
        return any(self.cat.can_place(o.type, p.type) for p in places)


def _inside(x: _Scene, o: ObjectState, by_type: bool, rng: random.Random) -> Condition | None:
    """``o`` inside a receptacle drawn from those that can take it (not where it is, not
    inside itself, never the floor or the bin)."""
    places = [r for r in x.objs if r.has("receptacle") and r.id != o.id and r.id != o.parent
              and x.cat.can_place(o.type, r.type) and o.id not in x.state.ancestors(r.id)
              and r.type not in ("Floor", "GarbageCan")]
    if not places:
        return None
    place = rng.choice(sorted(places, key=lambda r: r.id))
    unique = by_type and x.counts[place.type] == 1
    return _cond(Predicate.inside, o, by_type=unique, place=place)


def _hot(x: _Scene, o: ObjectState, by_type: bool) -> Condition | None:
    return _cond(Predicate.hot, o, by_type=by_type) if x.fits_any(o, x.heaters) else None


def _cold(x: _Scene, o: ObjectState, by_type: bool) -> Condition | None:
    return _cond(Predicate.cold, o, by_type=by_type) if x.fits_any(o, x.fridges) else None


def _filled(x: _Scene, o: ObjectState, by_type: bool) -> Condition | None:
    wettable = x.fits_any(o, x.basins)
    if o.has("canFillWithLiquid") and wettable:
        return _cond(Predicate.filled, o, by_type=by_type, liquid="water")
    return None


def _cooked(x: _Scene, o: ObjectState, by_type: bool) -> Condition | None:
    return _cond(Predicate.cooked, o, by_type=by_type) if o.has("cookable") and x.heaters else None


def _sliced(x: _Scene, o: ObjectState, by_type: bool) -> Condition | None:
    # an egg is cracked (broken), never sliced
    if o.has("sliceable") and x.cat.slice_product(o.type) is not None and o.type != "Egg":
        return _cond(Predicate.sliced, o, by_type=by_type)
    return None


def _broken(x: _Scene, o: ObjectState, by_type: bool) -> Condition | None:
    # cracking an egg consumes it: no goal can name it afterwards
    if o.has("breakable") and o.type != "Egg" and not o.is_broken:
        return _cond(Predicate.broken, o, by_type=by_type)
    return None


def _door(x: _Scene, o: ObjectState, by_type: bool) -> Condition | None:
    if not o.has("openable"):
        return None
    return _cond(Predicate.closed if o.is_open else Predicate.open, o, by_type=by_type)


def _power(x: _Scene, o: ObjectState, by_type: bool) -> Condition | None:
    if not o.has("toggleable"):
        return None
    return _cond(Predicate.switched_off if o.is_on else Predicate.switched_on, o, by_type=by_type)


def _clean(x: _Scene, o: ObjectState, by_type: bool) -> Condition | None:
    if o.has("dirtyable") and o.is_dirty and o.has("pickupable") and x.fits_any(o, x.basins):
        return _cond(Predicate.clean, o, by_type=by_type)
    return None


_Rule = Callable[[_Scene, ObjectState, bool], Condition | None]
#: conditions on an object a robot can carry (after :func:`_inside`), in drawing order
_CARRIED: tuple[_Rule, ...] = (_hot, _cold, _filled, _cooked)
#: conditions on any object, in drawing order
_CHANGED: tuple[_Rule, ...] = (_sliced, _broken, _door, _power, _clean)


def _conditions_of(x: _Scene, o: ObjectState, by_type: bool, rng: random.Random, max_mass: float
                   ) -> list[Condition]:
    """The conditions worth drawing on ``o``: where it goes and what is done to it when a
    robot can carry it, then what is done to it where it stands. The order (and the
    random draw of :func:`_inside`) is fixed: goal seeds give the same goals as before."""
    found: list[Condition | None] = []
    if o.has("pickupable") and o.mass <= max_mass:
        found.append(_inside(x, o, by_type, rng))
        found += [rule(x, o, by_type) for rule in _CARRIED]
    found += [rule(x, o, by_type) for rule in _CHANGED]
    return [c for c in found if c is not None]


def candidate_conditions(state: WorldState, rng: random.Random, *, max_mass: float = 100.0,
                         type_refs: float = 0.3) -> list[tuple[str, Condition]]:
    """Every condition worth drawing, as (subject id, condition), shuffled."""
    x = _Scene.of(state)
    out: list[tuple[str, Condition]] = []
    for o in x.objs:
        # a type reference only where the type is unique: "any Cabinet" is too easy
        by_type = x.counts[o.type] == 1 and rng.random() < type_refs
        out += [(o.id, c) for c in _conditions_of(x, o, by_type, rng, max_mass)]
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
