"""Goal conditions -> PDDL goal formulas, with the objects each may be satisfied by.

A condition over one object id becomes a formula over that object (and the pieces it may
be cut into: a slice of ``Apple_1`` in the fridge satisfies ``inside(Apple_1, Fridge)``, as
:func:`emboteam.world.checker.matches` reads it). "Any instance of a type" becomes a
disjunction over the candidates, "N of types" a disjunction of conjunctions over
N-subsets (or, past :data:`MAX_COMBINATIONS`, the N most promising candidates). Every
formula mirrors :func:`emboteam.world.checker.check_condition`: a sliced whole no longer
counts (only ``sliced`` looks at it), ``inside`` is transitive, "Sink" means Sink or
SinkBasin, a cracked egg counts as broken.

Completeness against the checker: every way the checker accepts a condition must be a
way the compiled problem can reach it. So a whole that cannot satisfy a condition itself
but whose pieces can is cut (``inside(Bread, Toaster)``: only bread slices go in a
toaster; too heavy to lift whole; ``cooked(Egg)``: only a cracked egg cooks), and an
object that cannot go in/on the receptacle directly may get there in a *vessel* that can
(a lettuce slice on a plate in the microwave, an egg in a pan on a burner), since
``inside`` counts contents of contents.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Sequence
from dataclasses import dataclass, field
from itertools import combinations

from emboteam.pddl.domain import pending_pieces
from emboteam.pddl.errors import ImpossibleGoalError, PlanningError, UnknownGoalObjectError
from emboteam.sim.physics import is_cold_source
from emboteam.world.actions import Skill
from emboteam.world.catalogue import COLD_SOURCES, load_catalogue, place_types
from emboteam.world.checker import check_condition
from emboteam.world.goals import Condition, ObjectRef, Predicate
from emboteam.world.state import ObjectState, WorldState

#: most vessels offered per condition (nearest first)
MAX_VESSELS = 2

#: past this many N-subsets, "N of types" commits to the N most promising candidates
MAX_COMBINATIONS = 20
#: at most this many candidates for "any instance" (nearest and easiest first): more only
#: grows the problem, rarely the plan's quality
MAX_CANDIDATES = 6
#: at most this many places for "in any drawer" when narrowing (open and near first): a
#: kitchen with 27 closed drawers made Fast Downward run out of time on one phone; the
#: caller's retry without narrowing keeps every place
MAX_PLACES = 6

#: the instance property a subject needs for the predicate to be achievable
_NEEDS: dict[Predicate, str] = {
    Predicate.broken: "breakable", Predicate.switched_on: "toggleable",
    Predicate.switched_off: "toggleable", Predicate.open: "openable", Predicate.closed: "openable",
    Predicate.cooked: "cookable", Predicate.dirty: "dirtyable", Predicate.filled: "canFillWithLiquid",
    Predicate.held: "pickupable", Predicate.inside: "pickupable", Predicate.hot: "pickupable",
    Predicate.cold: "pickupable",
}
#: predicates whose subject a robot must usually carry (to the receptacle, the heater, ...)
_CARRIED = frozenset({Predicate.inside, Predicate.held, Predicate.hot, Predicate.cold, Predicate.cooked})


@dataclass(frozen=True)
class GoalPart:
    """One compiled condition."""

    condition: Condition
    formula: str
    #: objects that may satisfy it (pending pieces included)
    subjects: tuple[str, ...]
    #: receptacles that may hold them (inside)
    places: tuple[str, ...] = ()
    #: wholes that must (or may) be cut for it
    slices: tuple[str, ...] = ()
    satisfied: bool = False
    #: the subjects the formula commits to when it had to choose (N of many)
    chosen: tuple[str, ...] = field(default=())
    #: containers a subject may ride in to reach ``places`` (it cannot go there directly)
    vessels: tuple[str, ...] = field(default=())


class _View:
    """The state plus the pieces its sliceable objects may be cut into."""

    def __init__(self, state: WorldState) -> None:
        self.state = state
        self.pending = pending_pieces(state)
        self.objects: dict[str, ObjectState] = {**state.objects, **self.pending}
        #: the objects each reference may stand for (:func:`_raw_subjects`), found once per view
        self.subjects: dict[ObjectRef, list[ObjectState]] = {}
        #: the receptacles each place reference stands for (:func:`_places`), found once per view
        self.places: dict[ObjectRef, list[str]] = {}

    def type_of_source(self, o: ObjectState) -> str | None:
        return self.objects[o.source].type if o.source is not None and o.source in self.objects else None

    def matches_types(self, o: ObjectState, types: Collection[str]) -> bool:
        # asked of every object of the scene per reference (the reader's feasibility
        # checks compile hundreds of conditions): no set built per call, no method call
        # for the objects that are no piece
        if o.type in types:
            return True
        source = self.objects.get(o.source) if o.source is not None else None
        return source is not None and source.type in types

    def pieces_of(self, whole: str) -> list[str]:
        return [p.id for p in self.objects.values() if p.source == whole]

    def goes_directly(self, otype: str, places: Sequence[str]) -> bool:
        cat = load_catalogue()
        return any(cat.can_place(otype, self.state.objects[p].type) for p in places)

    def vessels(self, o: ObjectState, places: Sequence[str]) -> list[str]:
        """Movable containers that take ``o`` and may go in/on one of ``places``, or
        already are within one (nearest to ``o`` first)."""
        cat = load_catalogue()
        state = self.state
        anchor = o.source if o.id in self.pending and o.source is not None else o.id
        out = []
        for v in state.objects.values():
            if (v.gone or not v.has("receptacle") or v.id in (o.id, anchor) or v.id in places
                    or not cat.can_place(o.type, v.type)
                    or (anchor in state.objects and anchor in state.ancestors(v.id))):
                continue
            within = any(state.is_within(v.id, p) for p in places)
            if within or (v.has("pickupable") and self.goes_directly(v.type, places)):
                out.append(v.id)
        here = state.objects[anchor].position if anchor in state.objects else o.position

        def far(v: str) -> float:
            there = state.objects[v].position
            return math.hypot(there[0] - here[0], there[2] - here[2])

        return sorted(out, key=lambda v: (far(v), v))

    def reaches(self, o: ObjectState, places: Sequence[str]) -> bool:
        """Can ``o`` end up within one of ``places`` (directly, or in a vessel)?"""
        if o.id in self.state.objects and any(self.state.is_within(o.id, p) for p in places):
            return True
        return self.goes_directly(o.type, places) or bool(self.vessels(o, places))


def _pred_atom(pred: Predicate, o: str, places: Sequence[str], robots: Sequence[str],
               liquid: str | None) -> str:
    if pred is Predicate.sliced:
        return f"(sliced {o})"
    if pred is Predicate.broken:
        return f"(broken {o})"  # breaking an egg cracks it: no longer available, still broken
    if pred is Predicate.inside:
        body = " ".join(f"(within {o} {p})" for p in places if p != o)
        core = f"(or {body})" if len(places) > 1 else body
    elif pred is Predicate.held:
        holders = " ".join(f"(holding {r} {o})" for r in robots)
        core = f"(or {holders})" if len(robots) > 1 else holders
    else:
        core = {
            Predicate.broken: f"(broken {o})", Predicate.switched_on: f"(is-on {o})",
            Predicate.switched_off: f"(not (is-on {o}))", Predicate.open: f"(is-open {o})",
            Predicate.closed: f"(not (is-open {o}))", Predicate.hot: f"(hot {o})",
            Predicate.cold: f"(cold {o})", Predicate.cooked: f"(cooked {o})",
            Predicate.clean: f"(not (dirty {o}))", Predicate.dirty: f"(dirty {o})",
            Predicate.filled: {None: f"(filled {o})", "water": f"(has-water {o})",
                               "coffee": f"(has-coffee {o})", "wine": f"(has-wine {o})"}.get(
                liquid, f"(filled {o})"),
        }[pred]
    return f"(and (available {o}) {core})"


#: what :func:`shared_view` gives, for annotations
StateView = _View


def shared_view(state: WorldState) -> _View:
    """A view of ``state`` to pass (``view=``) to several :func:`compile_condition` and
    :func:`slicing_targets` calls made while the state does not change (the offline
    reader's checks of one instruction): the pieces and each reference's objects are
    then found once, not per call."""
    return _View(state)


def _view_of(state: WorldState, view: _View | None) -> _View:
    return view if view is not None and view.state is state else _View(state)


def slicing_targets(conditions: Sequence[Condition], state: WorldState, robots: Sequence[str] = (),
                    view: _View | None = None) -> set[str]:
    """Wholes a goal asks to slice, or whose pieces it names or needs: ``cooked(Bread)``
    (only bread slices cook), ``inside(Bread, Toaster)`` (only slices go in a toaster,
    even in a container), a whole too heavy for every robot of ``robots`` that can pick
    up when its pieces are not."""
    view = _view_of(state, view)
    cat = load_catalogue()
    lifters = [state.robots[r].profile.mass_capacity for r in robots
               if r in state.robots and state.robots[r].profile.can(Skill.PickupObject)]
    lift = max(lifters, default=None)
    out: set[str] = set()
    for cond in conditions:
        ref = cond.subject
        places: list[str] | None = None
        for o in _raw_subjects(ref, view):
            if o.source is not None:
                named = ref.id == o.id or (ref.types and o.type in ref.types)
                if o.id in view.pending and named:
                    out.add(o.source)
                continue
            product = cat.slice_product(o.type)
            if product is None or o.gone:
                continue
            named_piece = bool(ref.types) and product[0] in ref.types and o.type not in ref.types
            if cond.predicate is Predicate.sliced or named_piece:
                out.add(o.id)
                continue
            need = _NEEDS.get(cond.predicate)
            if need is not None and not o.has(need) and need in cat.type(product[0]).properties:
                out.add(o.id)
                continue
            pieces = view.pieces_of(o.id)
            if not pieces:
                continue
            piece = view.objects[pieces[0]]
            if (cond.predicate in _CARRIED and lift is not None and o.mass > lift >= piece.mass
                    and not check_condition(cond, state).holds):
                out.add(o.id)
                continue
            if cond.predicate is Predicate.inside:
                if places is None:
                    try:
                        places = _places(cond, view)
                    except PlanningError:
                        places = []
                if places and not view.reaches(o, places) and view.reaches(piece, places):
                    out.add(o.id)
    return out


def _raw_subjects(ref: ObjectRef, view: _View) -> list[ObjectState]:
    """Objects (and pending pieces) a reference can stand for, before any filtering."""
    found = view.subjects.get(ref)
    if found is None:
        found = view.subjects[ref] = _find_subjects(ref, view)
    return list(found)


def _find_subjects(ref: ObjectRef, view: _View) -> list[ObjectState]:
    if ref.id is not None:
        o = view.objects.get(ref.id)
        if o is None:
            raise UnknownGoalObjectError(f"{view.state.floor_plan} has no object {ref.id!r}")
        return [o, *(view.objects[p] for p in view.pieces_of(o.id))] if o.source is None else [o]
    return [o for o in view.objects.values() if view.matches_types(o, ref.types)]


def _places(cond: Condition, view: _View) -> list[str]:
    assert cond.receptacle is not None
    found = view.places.get(cond.receptacle)
    if found is None:
        found = view.places[cond.receptacle] = _find_places(cond, view)
    return list(found)


def _find_places(cond: Condition, view: _View) -> list[str]:
    assert cond.receptacle is not None
    ref = cond.receptacle
    state = view.state
    if ref.id is not None:
        if ref.id not in state.objects:
            raise UnknownGoalObjectError(f"{state.floor_plan} has no object {ref.id!r}")
        found = [ref.id]
    else:
        types = place_types(ref.types)
        found = [o.id for o in state.objects.values() if not o.gone and view.matches_types(o, types)]
    places = [p for p in found if state.objects[p].has("receptacle")]
    # "in the sink" is also in the basin within it: receptacles within a named
    # non-receptacle count (the checker reads every container around an object)
    places += [d.id for p in found if not state.objects[p].has("receptacle")
               for d in state.descendants(p) if d.has("receptacle") and not d.gone and d.id not in places]
    if not found:
        raise ImpossibleGoalError(f"{cond}: {state.floor_plan} has no {ref}")
    if not places:
        raise ImpossibleGoalError(f"{cond}: {ref} is not a receptacle")
    return places


def _rank(view: _View, robots: Sequence[str], oid: str) -> tuple[float, str]:
    """Promise of a candidate: existing before pending, near a robot, not hidden."""
    state = view.state
    o = view.objects[oid]
    anchor = o.source if oid in view.pending and o.source is not None else oid
    hidden = 1.0 if anchor in state.objects and state.enclosing_closed(anchor) is not None else 0.0
    near = min((state.distance(r, anchor) for r in robots if r in state.robots), default=0.0)
    return (hidden * 5 + near + (3.0 if oid in view.pending else 0.0), oid)


def compile_condition(cond: Condition, state: WorldState, robots: Sequence[str], *,
                      slices: set[str] | None = None, narrow: bool = True, view: _View | None = None) -> GoalPart:
    """Compile one condition for a problem whose acting robots are ``robots``.

    ``slices`` are the wholes the whole goal will cut (their pieces become candidates);
    with ``narrow``, a condition that already holds commits to the objects that satisfy it
    now (small problems; the caller retries without ``narrow`` if that proves unsolvable);
    ``view``: a :func:`shared_view` of ``state``.
    """
    view = _view_of(state, view)
    slices = slices if slices is not None else slicing_targets([cond], state, robots, view)
    pred = cond.predicate
    result = check_condition(cond, state)
    raw = _raw_subjects(cond.subject, view)
    if not raw:
        raise ImpossibleGoalError(f"{cond}: {state.floor_plan} has no {cond.subject}")

    def usable(o: ObjectState) -> bool:
        if pred is Predicate.sliced:
            return o.source is None and o.has("sliceable") and load_catalogue().slice_product(o.type) is not None
        if pred is Predicate.broken and o.gone and o.is_broken:
            return True  # a cracked egg: gone, but the checker counts it as broken
        if o.gone:
            return False
        if o.id in view.pending and o.source not in slices:
            return False
        if pred is Predicate.inside and cond.receptacle is not None and cond.receptacle.id == o.id:
            return False
        need = _NEEDS.get(pred)
        return need is None or o.has(need) or o.id in result.witnesses

    subjects = [o.id for o in raw if usable(o)]
    if not subjects:
        need = _NEEDS.get(pred, "sliceable" if pred is Predicate.sliced else str(pred))
        raise ImpossibleGoalError(f"{cond}: no {cond.subject} in {state.floor_plan} is {need}")
    if pred is Predicate.dirty:
        subjects = [s for s in subjects if s in result.witnesses]
        if not subjects:
            raise ImpossibleGoalError(f"{cond}: no skill makes an object dirty and no {cond.subject} is")
    if pred is Predicate.filled and cond.liquid not in (None, "water", "coffee"):
        subjects = [s for s in subjects if s in result.witnesses]
        if not subjects:
            raise ImpossibleGoalError(f"{cond}: nothing here pours {cond.liquid}")
    if len(subjects) < cond.count:
        raise ImpossibleGoalError(f"{cond}: {state.floor_plan} has only {len(subjects)} {cond.subject}")
    places = _places(cond, view) if pred is Predicate.inside else []
    if narrow and len(places) > MAX_PLACES and cond.receptacle is not None and cond.receptacle.id is None:
        there = {p for p in places if any(o.id in state.objects and state.is_within(o.id, p) for o in raw)}
        places = sorted(places, key=lambda p: (p not in there, _rank(view, robots, p)))[:MAX_PLACES]
    if places:
        # those that can get there (directly, in a vessel) first; if none seems to, let
        # the planner have the last word
        subjects = [s for s in subjects if s in result.witnesses or view.reaches(view.objects[s], places)
                    ] or subjects
        if len(subjects) < cond.count:
            raise ImpossibleGoalError(f"{cond}: {state.floor_plan} has only {len(subjects)} {cond.subject} "
                                      f"that can go in/on {cond.receptacle}")

    holders = list(dict.fromkeys([*robots, *(view.objects[s].held_by for s in subjects
                                              if s in state.objects and state.objects[s].held_by)]))
    if pred is Predicate.held and not holders:
        raise ImpossibleGoalError(f"{cond}: no robot to hold it")

    satisfied = result.holds
    # a witness about to be cut no longer counts: then its pieces must take over
    doomed = any(w in slices for w in result.witnesses)
    if narrow and satisfied and not doomed:
        subjects = list(result.witnesses[:cond.count])
        if pred is Predicate.inside:
            keep = [p for p in places if any(state.is_within(s, p) for s in subjects)]
            places = keep or places
    else:
        subjects.sort(key=lambda s: (s not in result.witnesses, _rank(view, robots, s)))
    cap = max(MAX_CANDIDATES, cond.count + 2)
    subjects = subjects[:cap]

    atoms = {s: _pred_atom(pred, s, places, [h for h in holders if h], cond.liquid) for s in subjects}
    chosen: tuple[str, ...] = ()
    if cond.count == 1:
        formula = atoms[subjects[0]] if len(subjects) == 1 else "(or " + " ".join(atoms.values()) + ")"
    elif math.comb(len(subjects), cond.count) <= MAX_COMBINATIONS:
        groups = ["(and " + " ".join(atoms[s] for s in combo) + ")"
                  for combo in combinations(subjects, cond.count)]
        formula = groups[0] if len(groups) == 1 else "(or " + " ".join(groups) + ")"
    else:
        chosen = tuple(subjects[:cond.count])
        formula = "(and " + " ".join(atoms[s] for s in chosen) + ")"
        subjects = list(chosen)
    # where a subject must get to: the goal's receptacles, or a fridge to cool it (heat
    # has its own pans and pots: pddl.problem._heat_support)
    targets = places if pred is Predicate.inside else (
        [f.id for f in state.of_type(*COLD_SOURCES) if is_cold_source(f)] if pred is Predicate.cold else [])
    vessels: list[str] = []
    if targets and not (narrow and satisfied and not doomed):
        for sid in subjects:
            o = view.objects[sid]
            if sid in result.witnesses or view.goes_directly(o.type, targets):
                continue
            vessels += [v for v in view.vessels(o, targets)[:MAX_VESSELS] if v not in vessels]
        vessels = vessels[:MAX_VESSELS + 1]
    cut: set[str] = set()
    for sid in subjects:
        o = view.objects[sid]
        if pred is Predicate.sliced and not o.is_sliced:
            cut.add(sid)
        elif sid in view.pending and o.source is not None:
            cut.add(o.source)
    return GoalPart(condition=cond, formula=formula, subjects=tuple(subjects), places=tuple(places),
                    slices=tuple(sorted(cut)), satisfied=satisfied, chosen=chosen, vessels=tuple(vessels))


def compile_goal(conditions: Sequence[Condition], state: WorldState, robots: Sequence[str], *,
                 narrow: bool = True) -> list[GoalPart]:
    """Compile conditions that one problem must satisfy together (one view of ``state``
    for all of them: the pieces and each reference's objects found once, not per
    condition; every problem the planner builds comes through here)."""
    view = _View(state)
    slices = slicing_targets(conditions, state, robots, view)
    parts = [compile_condition(c, state, robots, slices=slices, narrow=narrow, view=view) for c in conditions]
    _check_hot_in_fridge(parts, state)
    return parts


def _check_hot_in_fridge(parts: Sequence[GoalPart], state: WorldState) -> None:
    """A fridge cools what it holds (AI2-THOR: an object inside a cold source becomes Cold,
    and Hot and Cold are one temperature), so "hot" and "in the fridge" cannot hold for the
    same object. Raised here, before the search: Fast Downward cannot prove a goal
    unreachable quickly, and would spend its whole time limit on this one."""
    for hot in (p for p in parts if p.condition.predicate is Predicate.hot):
        for cooled in parts:
            places = [state.objects[x] for x in cooled.places if x in state.objects]
            if (cooled.condition.predicate is not Predicate.inside or not places
                    or not all(is_cold_source(f) for f in places)):
                continue
            distinct = set(hot.subjects) | set(cooled.subjects)
            if len(distinct) < hot.condition.count + cooled.condition.count:
                raise ImpossibleGoalError(
                    f"{hot.condition} and {cooled.condition}: {cooled.condition.receptacle} cools what "
                    f"it holds, so the same {hot.condition.subject} cannot be hot in it")
