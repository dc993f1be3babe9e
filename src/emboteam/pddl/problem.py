"""PDDL problems rendered from a :class:`WorldState` and goal conditions (never from LLM
text), pruned hard to the objects that matter.

Which objects a problem declares (:func:`relevant_objects`):

- the candidates of every condition and the receptacles an ``inside`` may use;
- what a condition's kind needs: knives to slice, heaters (a microwave or toaster that
  takes the object, else a pan and a burner with its knob) to heat or cook, fridges to
  cool, faucets and their basins to clean or fill with water, a coffee machine for coffee;
- everything enclosing a declared object (to open it, to know it is hidden), the knob of a
  declared burner and the faucet of a declared basin (their state decides what a put does),
  the whole of a declared piece and the pieces of a whole to be cut, what the acting
  robots hold, the Floor when a robot can drop things.

Where an object may be put (``can-place`` facts) is narrowed too: the condition's
receptacles and appliances, the object's current place (to put a tool back) and, for an
object a robot already holds, the nearest place that takes it. Fewer facts, far fewer
ground actions, the same plans for these goals.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from emboteam.pddl import vocabulary
from emboteam.pddl.domain import (
    BASIC_FLUENTS,
    DOMAIN_NAME,
    SCHEMA_BY_NAME,
    USED_STATICS,
    DomainError,
    Universe,
    to_action,
)
from emboteam.pddl.errors import PlannerInputError
from emboteam.pddl.goal_compiler import GoalPart, compile_goal
from emboteam.sim.physics import is_cold_source, settle
from emboteam.world.actions import Action, Skill
from emboteam.world.catalogue import (
    BREWERS,
    BURNERS,
    COLD_SOURCES,
    HEATERS,
    KNIVES,
    WATER_SOURCES,
    load_catalogue,
)
from emboteam.world.goals import Condition, Predicate
from emboteam.world.state import ObjectState, WorldState


@dataclass(frozen=True)
class Problem:
    """A rendered problem and what is needed to read its plans back."""

    name: str
    text: str
    objects: tuple[str, ...]
    robots: tuple[str, ...]
    active: tuple[str, ...]
    parts: tuple[GoalPart, ...]
    can_place: frozenset[tuple[str, str]]
    names: dict[str, str]
    #: the initial facts (``(in Apple_1 Fridge_1)``) and goal formulas of ``text``, kept
    #: apart so the SAS emitter grounds them without parsing the whole problem
    facts: tuple[str, ...] = ()
    goals: tuple[str, ...] = ()

    def universe(self, state: WorldState) -> Universe:
        return Universe(state, self.objects, self.robots, can_place=self.can_place)

    def decode(self, plan: Sequence[str]) -> list[tuple[str, Action]]:
        """Fast Downward's plan lines (``(put robot1 apple_1 fridge_1)``) as simulator
        actions, object names restored to their exact case."""
        out: list[tuple[str, Action]] = []
        for line in plan:
            words = line.strip().strip("()").split()
            if not words:
                continue
            schema = SCHEMA_BY_NAME.get(words[0].lower())
            if schema is None:
                raise PlannerInputError(f"plan step {line!r} uses unknown action {words[0]!r}")
            try:
                args = [self.names[w.lower()] for w in words[1:]]
                out.append(to_action(schema, args))
            except (KeyError, DomainError) as exc:
                raise PlannerInputError(f"cannot read plan step {line!r}: {exc}") from None
        return out


def planning_state(state: WorldState) -> WorldState:
    """The state a plan starts from: a settled copy (the simulator settles side effects
    after the first action, so an unsettled scene would otherwise surprise the plan)."""
    s = state.copy()
    settle(s)
    return s


def _water_support(state: WorldState) -> list[str]:
    out: list[str] = []
    for f in state.objects.values():
        if f.type in WATER_SOURCES and not f.gone:
            basins = [b for b in f.controls if b in state.objects and state.objects[b].has("receptacle")]
            if basins:
                out += [f.id, *basins]
    return out


def _heat_support(state: WorldState, types: set[str], active: Sequence[str] = ()) -> list[str]:
    """Appliances that can heat objects of ``types``: a microwave, toaster or coffee
    machine that takes them, a burner for what goes on a stove (pans, pots, kettles); for
    food that needs a pan, a pan or pot that takes it and a burner (its knobs follow by
    closure). An appliance the ``active`` robots cannot use (a shut microwave and nobody
    who opens) covers nothing: the pan on the stove is then the way."""
    cat = load_catalogue()
    skills = {s for r in active if r in state.robots for s in state.robots[r].profile.skills}

    def usable(h: ObjectState) -> bool:
        if not active:
            return True
        opens = h.type not in cat.must_be_open or h.is_open or Skill.OpenObject in skills
        return opens and (h.is_on or Skill.SwitchOn in skills)

    direct = [h.id for h in state.of_type(*(HEATERS - BURNERS), *BREWERS)
              if any(cat.can_place(t, h.type) for t in types)
              and (h.type not in BREWERS or "Mug" in types)]
    burners = [b.id for b in state.of_type(*BURNERS)]
    stove = burners[:1] if burners and any(cat.can_place(t, "StoveBurner") for t in types) else []
    covered = {t for t in types if any(cat.can_place(t, state.objects[h].type) for h in direct + stove
                                       if usable(state.objects[h]))}
    if covered == types or not burners:
        return direct + stove
    containers = [c for c in state.of_type("Pan", "Pot")
                  if c.has("pickupable") and any(cat.can_place(t, c.type) for t in types - covered)
                  and cat.can_place(c.type, "StoveBurner")]
    return direct + stove + ([containers[0].id, burners[0]] if containers else [])


def _parking(state: WorldState, oid: str, robot: str) -> str | None:
    """The nearest receptacle (not one that must be opened) that takes ``oid``: where a
    robot holding it can put it down."""
    cat = load_catalogue()
    o = state.objects[oid]
    options = [r for r in state.objects.values()
               if r.has("receptacle") and not r.gone and r.id != oid and r.held_by is None
               and r.type not in cat.must_be_open and cat.can_place(o.type, r.type)
               and state.enclosing_closed(r.id) is None and oid not in state.ancestors(r.id)]
    if not options:
        return None
    return min(options, key=lambda r: (state.distance(robot, r.id), r.id)).id


def relevant_objects(state: WorldState, parts: Sequence[GoalPart], active: Sequence[str]
                     ) -> tuple[list[str], dict[str, set[str]]]:
    """Declared objects (pending pieces included) and, per movable object, where it may
    be put."""
    universe_view = Universe(state).view
    objects = universe_view.objects
    cat = load_catalogue()
    declared: dict[str, None] = {}
    dest: dict[str, set[str]] = {}

    def add(ids: Iterable[str]) -> None:
        for i in ids:
            if i in objects:
                declared.setdefault(i, None)

    def allow(oid: str, places: Iterable[str]) -> None:
        dest.setdefault(oid, set()).update(places)

    slices: set[str] = set()
    for part in parts:
        add(part.subjects)
        add(part.places)
        add(part.vessels)
        slices.update(part.slices)
        pred = part.condition.predicate
        support: list[str] = []
        types = {objects[s].type for s in part.subjects}
        if part.satisfied:
            support = []
        elif pred in (Predicate.hot, Predicate.cooked):
            support = _heat_support(state, types, active)
        elif pred is Predicate.cold:
            support = [f.id for f in state.of_type(*COLD_SOURCES) if is_cold_source(f)]
        elif pred is Predicate.clean or (pred is Predicate.filled and part.condition.liquid in (None, "water")):
            support = _water_support(state)
            if pred is Predicate.filled and part.condition.liquid is None:
                support += [c.id for c in state.of_type(*BREWERS)] if "Mug" in types else []
        elif pred is Predicate.filled and part.condition.liquid == "coffee":
            support = [c.id for c in state.of_type(*BREWERS)]
        add(support)
        for s in part.subjects:
            allow(s, part.places)
            allow(s, part.vessels)
            allow(s, [r for r in support if objects[r].has("receptacle")])
        for v in part.vessels:  # a lettuce slice on a plate in the microwave, a knife on one in the fridge
            allow(v, [*part.places, *(r for r in support if objects[r].has("receptacle"))])
        for c in support:
            if objects[c].type in ("Pan", "Pot"):
                allow(c, [b for b in support if objects[b].type in BURNERS])
    if slices:
        add(k.id for k in state.of_type(*KNIVES))
        for w in slices:
            add(p for p in objects if objects[p].source == w)
    for r in active:
        held = state.robots[r].holding
        if held is not None:
            add([held])
            spot = _parking(state, held, r)
            if spot is not None:
                add([spot])
                allow(held, [spot])
        if state.robots[r].profile.can(Skill.DropHandObject):
            add(f.id for f in list(state.of_type("Floor"))[:1])
    # closure: enclosures, controllers, wholes of pieces
    frontier = list(declared)
    while frontier:
        oid = frontier.pop()
        o = objects[oid]
        more: list[str] = []
        if o.source is not None:
            more.append(o.source)
        if oid in state.objects:
            more += state.ancestors(oid)
        if o.type in BURNERS:
            more += [k.id for k in state.of_type("StoveKnob") if oid in k.controls]
        if o.has("receptacle"):
            more += [f.id for f in state.objects.values() if f.type in WATER_SOURCES and oid in f.controls]
        for m in more:
            if m not in declared and m in objects:
                declared[m] = None
                frontier.append(m)
    # every movable object may go back where it is (pieces: where their whole is)
    for oid in declared:
        o = objects[oid]
        home = o.parent if o.source is None or oid in state.objects else objects[o.source].parent
        if home is not None and home in declared:
            allow(oid, [home])
    for oid in list(dest):
        mover = objects.get(oid)
        dest[oid] = {r for r in dest[oid] if r in declared and r != oid and mover is not None
                     and objects[r].has("receptacle") and cat.can_place(mover.type, objects[r].type)}
    return list(declared), dest


def _holders(state: WorldState, objects: Iterable[str]) -> list[str]:
    return [h for o in objects if o in state.objects and (h := state.objects[o].held_by) is not None]


def build_problem(state: WorldState, conditions: Sequence[Condition], robots: Sequence[str], *,
                  name: str = "task", protect: Sequence[Condition] = (), release: bool = True,
                  narrow: bool = True, elsewhere: Sequence[str] = ()) -> Problem:
    """The problem of reaching ``conditions`` (and keeping ``protect``) from ``state`` with
    the acting ``robots``. ``release`` asks acting robots that can put things down to end
    with empty hands (so the next subtask finds knives and hands free). Robots in
    ``elsewhere`` reach nothing at the start (they will have moved by the time the plan
    runs: its first move is a GoToObject)."""
    start = planning_state(state)
    active = [r for r in robots if r in start.robots and not start.robots[r].down]
    parts = compile_goal([*conditions, *protect], start, active, narrow=narrow)
    objects, dest = relevant_objects(start, parts, active)
    robot_names = list(dict.fromkeys([*active, *_holders(start, objects)]))
    for part in parts:
        if part.condition.predicate is Predicate.held:
            robot_names += [h for h in part.formula.replace("(", " ").replace(")", " ").split()
                            if h in start.robots and h not in robot_names]
    can_place = frozenset((o, r) for o, rs in dest.items() for r in rs)
    universe = Universe(start, objects, robot_names, can_place=can_place)

    names: dict[str, str] = {}
    for n in [*robot_names, *objects]:
        if n.lower() in names and names[n.lower()] != n:
            raise PlannerInputError(f"names {names[n.lower()]!r} and {n!r} differ only in case: "
                                    "PDDL names are case-insensitive")
        names[n.lower()] = n

    facts = [f for f in _init_facts(start, universe, robot_names, objects, can_place)
             if not (f.startswith("(at ") and f.split()[1] in elsewhere)]
    for r in active:
        for skill in start.robots[r].profile.skills:
            facts.append(f"({vocabulary.CAPABILITIES[skill.value]} {r})")

    goal = [p.formula for p in parts]
    if release and not any(p.condition.predicate is Predicate.held for p in parts):
        goal += [f"(hand-empty {r})" for r in active
                 if start.robots[r].profile.can(Skill.PutObject) or start.robots[r].profile.can(Skill.DropHandObject)]
    init = sorted(set(facts))
    text = "\n".join([
        f"(define (problem {name}) (:domain {DOMAIN_NAME})",
        "  (:objects " + " ".join(robot_names) + " - robot",
        "            " + " ".join(objects) + " - thing)",
        "  (:init\n    " + "\n    ".join(init) + ")",
        "  (:goal (and\n    " + "\n    ".join(goal or ["(and)"]) + ")))",
    ]) + "\n"
    return Problem(name=name, text=text, objects=tuple(objects), robots=tuple(robot_names),
                   active=tuple(active), parts=tuple(parts), can_place=can_place, names=names,
                   facts=tuple(init), goals=tuple(goal))


def _nearest_can(state: WorldState, robot: str, can: str) -> bool:
    """ThrowObject lands in the nearest GarbageCan in reach: only that one counts as
    reachable for a throw."""
    cans = [g for g in state.of_type("GarbageCan") if state.in_reach(robot, g.id)]
    return bool(cans) and min(cans, key=lambda g: state.distance(robot, g.id)).id == can


def _pairs(pred: str, objects: Sequence[str], universe: Universe,
           can_place: frozenset[tuple[str, str]]) -> Iterable[tuple[str, ...]]:
    """Candidate argument pairs of a binary object predicate: only related objects can
    satisfy one, so the quadratic sweep is skipped where the relation is known."""
    view = universe.view.objects
    declared = set(objects)
    if pred == "in":
        return [(o, p) for o in objects if o in universe.state.objects
                and (p := universe.state.objects[o].parent) in declared]
    if pred == "can-place":
        return sorted(can_place)
    if pred in ("switches", "waters", "controls"):
        return [(o, c) for o in objects for c in view[o].controls if c in declared]
    if pred == "piece-of":
        return [(o, src) for o in objects if (src := view[o].source) is not None and src in declared]
    return [(a, b) for a in objects for b in objects if a != b]


def _init_facts(state: WorldState, universe: Universe, robots: Sequence[str], objects: Sequence[str],
                can_place: frozenset[tuple[str, str]]) -> list[str]:
    """The initial state: basic fluents evaluated on the state, statics of the objects."""
    facts: list[str] = []

    def tuples(kinds: str, pred: str) -> Iterable[tuple[str, ...]]:
        if kinds == "o":
            return ((o,) for o in objects)
        if kinds == "r":
            return ((r,) for r in robots)
        if kinds == "ro":
            return ((r, o) for r in robots for o in objects)
        return _pairs(pred, objects, universe, can_place)

    for pred in BASIC_FLUENTS:
        for args in tuples(vocabulary.FLUENTS[pred][0], pred):
            if pred == "at" and universe.static("garbage", (args[1],)) and not _nearest_can(state, *args):
                continue
            if universe.truth(pred, args):
                facts.append(f"({pred} {' '.join(args)})")
    for pred in USED_STATICS:
        for args in tuples(vocabulary.STATICS[pred][0], pred):
            if universe.static(pred, args):
                facts.append(f"({pred} {' '.join(args)})")
    return facts
