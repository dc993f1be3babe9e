"""The goal checker: each condition's truth on a state, with the objects that satisfy it.

SR is "every condition holds"; GCR counts *required instances*: ``inside(2 of
Vegetable, Fridge)`` with one vegetable in the fridge contributes 1 of 2 (docs/metrics.md).
Conditions are checked independently: two conditions over "any apple" may be satisfied by
different apples, as in SMART-LLM's and ALFRED's goal checks.
"""

from __future__ import annotations

from collections.abc import Iterator
from functools import lru_cache
from itertools import islice

from pydantic import BaseModel, ConfigDict

from emboteam.errors import EmboTeamError
from emboteam.world.catalogue import load_catalogue, place_types
from emboteam.world.goals import Condition, Goal, ObjectRef, Predicate
from emboteam.world.scene import Scene
from emboteam.world.state import ObjectState, WorldState


class GoalValidationError(EmboTeamError):
    """A goal that names objects or types the scene lacks, or asks the impossible."""


class ConditionResult(BaseModel):
    model_config = ConfigDict(frozen=True)

    condition: Condition
    holds: bool
    satisfied: int
    required: int
    witnesses: tuple[str, ...] = ()

    def __str__(self) -> str:
        mark = "ok " if self.holds else "NOT"
        return f"{mark} {self.condition} ({self.satisfied}/{self.required})"


class GoalReport(BaseModel):
    model_config = ConfigDict(frozen=True)

    results: tuple[ConditionResult, ...]

    @property
    def success(self) -> bool:
        return all(r.holds for r in self.results)

    @property
    def gcr(self) -> float:
        required = sum(r.required for r in self.results)
        if required == 0:
            return 1.0
        return sum(min(r.satisfied, r.required) for r in self.results) / required

    def unmet(self) -> list[Condition]:
        return [r.condition for r in self.results if not r.holds]


def matches(ref: ObjectRef, o: ObjectState, state: WorldState) -> bool:
    """Does object ``o`` match the reference? Slices match their whole's type and id."""
    if ref.id is not None:
        return o.id == ref.id or o.source == ref.id
    if o.type in ref.types:
        return True
    return o.source is not None and state.objects[o.source].type in ref.types


def _unary(pred: Predicate, o: ObjectState, liquid: str | None) -> bool:
    if pred is Predicate.sliced:
        return o.is_sliced
    if pred is Predicate.broken:
        return o.is_broken
    if pred is Predicate.switched_on:
        return o.is_on
    if pred is Predicate.switched_off:
        return not o.is_on
    if pred is Predicate.open:
        return o.is_open
    if pred is Predicate.closed:
        return not o.is_open
    if pred is Predicate.hot:
        return o.temperature == "Hot"
    if pred is Predicate.cold:
        return o.temperature == "Cold"
    if pred is Predicate.cooked:
        return o.is_cooked
    if pred is Predicate.clean:
        return not o.is_dirty
    if pred is Predicate.dirty:
        return o.is_dirty
    if pred is Predicate.filled:
        return o.liquid is not None and (liquid is None or o.liquid == liquid)
    if pred is Predicate.held:
        return o.held_by is not None
    raise AssertionError(pred)


def check_condition(cond: Condition, state: WorldState) -> ConditionResult:
    """The condition's truth on ``state``, with the objects that satisfy it."""
    witnesses = tuple(_witnesses(cond, state))
    satisfied = len(witnesses)
    return ConditionResult(condition=cond, holds=satisfied >= cond.count, satisfied=satisfied,
                           required=cond.count, witnesses=witnesses)


def condition_holds(cond: Condition, state: WorldState) -> bool:
    """``check_condition(cond, state).holds``, without the report: the planner asks
    thousands of times a plan (every protected goal after each unit it accepts), and
    building the validated result cost more than the check; it stops at the
    ``count``-th witness."""
    need = cond.count
    if need <= 0:
        return True
    return next(islice(_witnesses(cond, state), need - 1, None), None) is not None


def _witnesses(cond: Condition, state: WorldState) -> Iterator[str]:
    """The ids of the objects that satisfy ``cond``, in the state's order."""
    # the planner checks conditions thousands of times per plan: the subject test of
    # :func:`matches` is inlined here and the receptacle reference built once per call
    objects = state.objects
    ref, pred = cond.subject, cond.predicate
    ref_id, ref_types = ref.id, ref.types
    where = cond.receptacle
    if pred is Predicate.inside and where is not None and where.types:
        where = _place_ref(where.types)
    # the subjects first, in the state's order, in one comprehension (most conditions name
    # one object of some eighty)
    if ref_id is not None:
        subjects = [o for o in objects.values() if o.id == ref_id or o.source == ref_id]
    else:
        subjects = [o for o in objects.values() if o.type in ref_types
                    or (o.source is not None and objects[o.source].type in ref_types)]
    for o in subjects:
        if pred is Predicate.sliced:
            ok = o.is_sliced and o.source is None  # the whole, not each of its pieces
        elif pred is Predicate.broken and o.gone:
            ok = o.is_broken  # a cracked egg is gone, but it was broken
        elif o.gone:
            continue  # a sliced whole no longer exists; its pieces stand for it
        elif pred is Predicate.inside:
            assert where is not None
            ok = any(matches(where, objects[r], state) for r in state.ancestors(o.id))
        else:
            ok = _unary(pred, o, cond.liquid)
        if ok:
            yield o.id


@lru_cache(maxsize=1024)
def _place_ref(types: tuple[str, ...]) -> ObjectRef:
    """The reference an ``inside`` goal's receptacle types stand for (Sink: Sink or SinkBasin)."""
    return ObjectRef(types=tuple(sorted(place_types(types))))


def check_goal(goal: Goal, state: WorldState) -> GoalReport:
    """Each condition's truth on ``state``."""
    return GoalReport(results=tuple(check_condition(c, state) for c in goal.conditions))


_NEEDS: dict[Predicate, str] = {
    Predicate.sliced: "sliceable", Predicate.broken: "breakable", Predicate.switched_on: "toggleable",
    Predicate.switched_off: "toggleable", Predicate.open: "openable", Predicate.closed: "openable",
    Predicate.cooked: "cookable", Predicate.dirty: "dirtyable", Predicate.filled: "canFillWithLiquid",
    Predicate.held: "pickupable",
}


def _candidates(ref: ObjectRef, scene: Scene) -> list[str]:
    """Types a reference can stand for in the scene, slices included."""
    cat = load_catalogue()
    if ref.id is not None:
        if scene.has_object(ref.id):
            return [scene.get(ref.id).type]
        base = ref.id.split("_Slice_")[0]
        if "_Slice_" in ref.id and scene.has_object(base):
            product = cat.slice_product(scene.get(base).type)
            return [product[0]] if product else []
        return []
    present = scene.type_counts()
    out = []
    for t in ref.types:
        if t in present:
            out.append(t)
        source = cat.source_type(t)
        if source is not None and source in present:
            out.append(t)
        product = cat.slice_product(t)
        if product is not None and t in present:
            out.append(product[0])
    return out


def _type_can(t: str, prop: str) -> bool:
    """The type, or the slices it can be cut into, have the property (Bread -> toast)."""
    cat = load_catalogue()
    product = cat.slice_product(t)
    return cat.type(t).has(prop) or (product is not None and cat.type(product[0]).has(prop))


def _instances(ref: ObjectRef, scene: Scene) -> int:
    """How many objects could stand for a type reference, counting possible slices."""
    products = load_catalogue().slice_products    # (the dict itself: asked per scene type)
    n = 0
    # by type, not by object (asked for every condition the reader checks)
    for t, count in scene.type_counts().items():
        product = products.get(t)
        if t in ref.types:
            n += count * (product[1] if product is not None and product[0] in ref.types else 1)
        elif product is not None and product[0] in ref.types:
            n += count * product[1]
    return n


def validate_goal(goal: Goal, scene: Scene) -> None:
    """Raise :class:`GoalValidationError` naming every reference the scene cannot satisfy."""
    cat = load_catalogue()
    problems: list[str] = []
    for cond in goal.conditions:
        types = _candidates(cond.subject, scene)
        if not types:
            problems.append(f"{cond}: {scene.floor_plan} has no {cond.subject}")
            continue
        need = _NEEDS.get(cond.predicate)
        if cond.predicate is Predicate.sliced:
            ok = any(cat.slice_product(t) is not None for t in types)
        else:
            ok = need is None or any(_type_can(t, need) for t in types)
        if not ok:
            problems.append(f"{cond}: no {cond.subject} here is {need or cond.predicate}")
        if cond.receptacle is not None:
            rtypes = _candidates(cond.receptacle, scene)
            if not rtypes:
                problems.append(f"{cond}: {scene.floor_plan} has no {cond.receptacle}")
            elif not any(cat.type(r).has("receptacle") for r in rtypes):
                problems.append(f"{cond}: {cond.receptacle} is not a receptacle")
        if cond.subject.types and cond.count > _instances(cond.subject, scene):
            problems.append(f"{cond}: {scene.floor_plan} has only "
                            f"{_instances(cond.subject, scene)} {cond.subject}")
    if problems:
        raise GoalValidationError("; ".join(problems))
