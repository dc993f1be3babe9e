"""The one PDDL domain of the THOR skill set, mirroring ``sim/rules.py`` and
``sim/physics.py``, and the grounding of its actions into plan-step literals.

Design (docs/planning.md has the long form):

- One domain for every team. What a robot may do is a *capability* fact in the problem
  (``(can-pickup robot5)``), not a per-robot domain, so a joint multi-robot problem, a
  capability-restricted single-robot problem and the allocation probes all share one
  domain text (and one cache of translated domains in Fast Downward's eyes).
- Object properties are static predicates written by the problem from the scene
  (``(pickupable Apple_1)``, ``(can-place Apple_1 Fridge_1)``, ``(can-lift robot5 Apple_1)``).
- Containment is ``in`` (direct); ``within`` (transitive), ``hidden`` (inside a closed
  receptacle), ``carried`` (held, or inside something held) and the three "place"
  predicates (a put there cools, heats or waters) are derived predicates (axioms).
- AI2-THOR's side effects (heating, cooking, cooling, running water, coffee, knobs that
  switch burners, pieces a slice spawns) are conditional effects.
- Where the simulator's outcome depends on something the symbolic state does not model
  (how close a robot stands), the domain is *conservative*: ``at`` holds only where the
  robot went (or was in reach at the start), so every plan valid here runs in the
  simulator; the converse need not hold.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import cache, lru_cache

from emboteam.errors import EmboTeamError
from emboteam.pddl import vocabulary
from emboteam.pddl.literal import Literal
from emboteam.pddl.recorded import Recorded, reused
from emboteam.pddl.schema import (
    A,
    Atom,
    Effect,
    Generator,
    Implies,
    N,
    Param,
    Schema,
    Truth,
    bindings,
)
from emboteam.sim.rules import piece_ids
from emboteam.world.actions import Action, Skill
from emboteam.world.catalogue import load_catalogue
from emboteam.world.state import REACH, ObjectState, WorldState

DOMAIN_NAME = "emboteam-thor"

R: Param = ("?r", "robot")


def _visible(o: str = "?o") -> tuple[Atom, ...]:
    """sim.rules._visible: exists, not inside a closed receptacle, not with another robot
    (conservatively: not carried at all), within reach."""
    return (A(f"available {o}"), N(f"hidden {o}"), N(f"carried {o}"), A(f"at ?r {o}"))


def _temperature(x: str, *, hot: bool) -> tuple[Atom, ...]:
    """Temperature is one value: turning Hot drops Cold and vice versa."""
    return (A(f"hot {x}"), N(f"cold {x}")) if hot else (A(f"cold {x}"), N(f"hot {x}"))


def _arrival(obj: str, place: str) -> tuple[Effect, ...]:
    """What settling does to ``obj`` and everything within it when ``obj`` arrives in/on
    ``place`` (physics.settle: cold in a fridge, heat and cooking in a running heater,
    cleaning and filling under running water)."""
    x: Param = ("?x", "thing")
    out: list[Effect] = []
    for subject, vars_, inside in ((obj, (), ()), ("?x", (x,), (A(f"within ?x {obj}"),))):
        out += [
            Effect(_temperature(subject, hot=False), (A(f"chilled-place {place}"), *inside), vars_),
            Effect(_temperature(subject, hot=True), (A(f"heated-place {place}"), *inside), vars_),
            Effect((A(f"cooked {subject}"),),
                   (A(f"heated-place {place}"), *inside, A(f"cookable {subject}")), vars_),
            Effect((N(f"dirty {subject}"),), (A(f"watered-place {place}"), *inside), vars_),
            Effect((A(f"filled {subject}"), A(f"has-water {subject}")),
                   (A(f"watered-place {place}"), *inside, A(f"fillable {subject}"),
                    N(f"filled {subject}")), vars_),
        ]
    return tuple(out)


def _pieces(o: str, extra: tuple[Atom, ...] = ()) -> tuple[Effect, ...]:
    """rules._cut: the declared pieces of ``o`` appear where it was, inherit its
    temperature and cooking, and settle there; robots that reached ``o`` reach them."""
    p: Param = ("?p", "thing")
    q: Param = ("?q", "thing")
    r2: Param = ("?r2", "robot")
    is_piece = (*extra, A(f"piece-of ?p {o}"))
    return (
        Effect((A("available ?p"), A("sliced ?p")), is_piece, (p,)),
        Effect((A("in ?p ?q"),), (*is_piece, A(f"in {o} ?q")), (p, q)),
        Effect((A("hot ?p"),), (*is_piece, A(f"hot {o}")), (p,)),
        Effect((A("cold ?p"),), (*is_piece, A(f"cold {o}")), (p,)),
        Effect((A("cooked ?p"),), (*is_piece, A(f"cooked {o}")), (p,)),
        Effect(_temperature("?p", hot=True), (*is_piece, A(f"in {o} ?q"), A("heated-place ?q")), (p, q)),
        Effect((A("cooked ?p"),), (*is_piece, A(f"in {o} ?q"), A("heated-place ?q"),
                                    A("cookable ?p")), (p, q)),
        Effect(_temperature("?p", hot=False), (*is_piece, A(f"in {o} ?q"), A("chilled-place ?q")),
               (p, q)),
        Effect((A("at ?r2 ?p"),), (*is_piece, A(f"at ?r2 {o}")), (p, r2)),
    )


OBJ: Param = ("?o", "thing")
X: Param = ("?x", "thing")
B: Param = ("?b", "thing")

SCHEMAS: tuple[Schema, ...] = (
    Schema("goto", Skill.GoToObject, (R, OBJ),
           (A("can-goto ?r"), A("available ?o"), N("carried ?o")),
           (Effect((A("at ?r ?o"),)),
            Effect((N("at ?r ?x"),), (N("= ?x ?o"), A("at ?r ?x")), (X,))),
           target="?o"),
    Schema("pickup", Skill.PickupObject, (R, OBJ),
           (A("can-pickup ?r"), A("pickupable ?o"), *_visible(), A("hand-empty ?r"), A("can-lift ?r ?o")),
           (Effect((A("holding ?r ?o"), N("hand-empty ?r"))),
            Effect((N("in ?o ?x"),), (A("in ?o ?x"),), (X,)),
            Effect((N("at ?r2 ?o"),), (N("= ?r2 ?r"), A("at ?r2 ?o")), (("?r2", "robot"),)),
            Effect((N("at ?r2 ?x"),), (A("within ?x ?o"), N("= ?r2 ?r"), A("at ?r2 ?x")),
                   (X, ("?r2", "robot")))),
           target="?o"),
    Schema("put", Skill.PutObject, (R, OBJ, ("?c", "thing")),
           (A("can-put ?r"), A("holding ?r ?o"), A("receptacle ?c"), *_visible("?c"),
            A("can-place ?o ?c"), Implies((), (A("must-open ?c"),), A("is-open ?c"))),
           (Effect((N("holding ?r ?o"), A("hand-empty ?r"), A("in ?o ?c"), A("at ?r ?o"))),
            *_arrival("?o", "?c"),
            Effect((A("filled ?o"), A("has-coffee ?o")),
                   (A("brews ?c"), A("is-on ?c"), A("fillable ?o"), N("filled ?o"))),
            Effect(_temperature("?o", hot=True), (A("brews ?c"), A("is-on ?c"), A("mug ?o")))),
           target="?o", receptacle="?c"),
    Schema("open", Skill.OpenObject, (R, OBJ),
           (A("can-open ?r"), A("openable ?o"), *_visible(), N("is-open ?o"),
            Implies((), (A("interlocked ?o"),), N("is-on ?o"))),
           (Effect((A("is-open ?o"),)),),
           target="?o"),
    Schema("close", Skill.CloseObject, (R, OBJ),
           (A("can-close ?r"), A("openable ?o"), *_visible(), A("is-open ?o")),
           (Effect((N("is-open ?o"),)),),
           target="?o"),
    Schema("switch-on", Skill.SwitchOn, (R, OBJ),
           (A("can-switch-on ?r"), A("toggleable ?o"), *_visible(), N("is-on ?o"), N("broken ?o"),
            Implies((), (A("interlocked ?o"),), N("is-open ?o"))),
           (Effect((A("is-on ?o"),)),
            Effect((A("is-on ?b"),), (A("switches ?o ?b"),), (B,)),
            Effect(_temperature("?x", hot=True), (A("heats ?o"), A("within ?x ?o")), (X,)),
            Effect((A("cooked ?x"),), (A("heats ?o"), A("within ?x ?o"), A("cookable ?x")), (X,)),
            Effect(_temperature("?x", hot=True), (A("switches ?o ?b"), A("heats ?b"), A("within ?x ?b")),
                   (B, X)),
            Effect((A("cooked ?x"),), (A("switches ?o ?b"), A("heats ?b"), A("within ?x ?b"),
                                        A("cookable ?x")), (B, X)),
            Effect((A("filled ?x"), A("has-coffee ?x")),
                   (A("brews ?o"), A("in ?x ?o"), A("fillable ?x"), N("filled ?x")), (X,)),
            Effect(_temperature("?x", hot=True), (A("brews ?o"), A("in ?x ?o"), A("mug ?x")), (X,)),
            Effect((N("dirty ?x"),), (A("waters ?o ?b"), A("within ?x ?b")), (B, X)),
            Effect((A("filled ?x"), A("has-water ?x")),
                   (A("waters ?o ?b"), A("within ?x ?b"), A("fillable ?x"), N("filled ?x")), (B, X))),
           target="?o"),
    Schema("switch-off", Skill.SwitchOff, (R, OBJ),
           (A("can-switch-off ?r"), A("toggleable ?o"), *_visible(), A("is-on ?o"),
            # a burner burns while any of its knobs is on: only switch a knob off when it
            # is the last one on, so the burner's state is certain (conservative)
            Implies((B, ("?k", "thing")), (A("switches ?o ?b"), A("switches ?k ?b"), N("= ?k ?o")),
                    N("is-on ?k"))),
           (Effect((N("is-on ?o"),)),
            Effect((N("is-on ?b"),), (A("switches ?o ?b"),), (B,))),
           target="?o"),
    Schema("slice", Skill.SliceObject, (R, OBJ, ("?k", "thing")),
           (A("can-slice ?r"), A("sliceable ?o"), *_visible(), N("sliced ?o"),
            A("holding ?r ?k"), A("knife ?k")),
           (Effect((A("sliced ?o"), N("available ?o"))), *_pieces("?o")),
           target="?o"),
    Schema("break", Skill.BreakObject, (R, OBJ),
           (A("can-break ?r"), A("breakable ?o"), *_visible(), N("broken ?o"),
            # breaking a knob that is on would switch its burner: not modelled, not allowed
            Implies((B,), (A("switches ?o ?b"),), N("is-on ?o"))),
           (Effect((A("broken ?o"),)),
            Effect((N("is-on ?o"),), (A("toggleable ?o"), A("is-on ?o"))),
            Effect((A("sliced ?o"), N("available ?o")), (A("cracks ?o"),)),
            *_pieces("?o", (A("cracks ?o"),))),
           target="?o"),
    Schema("clean", Skill.CleanObject, (R, OBJ),
           (A("can-clean ?r"), A("dirtyable ?o"), *_visible(), A("dirty ?o")),
           (Effect((N("dirty ?o"),)),),
           target="?o"),
    Schema("throw", Skill.ThrowObject, (R, OBJ, ("?g", "thing")),
           (A("can-throw ?r"), A("holding ?r ?o"), A("garbage ?g"), A("available ?g"), A("at ?r ?g")),
           (Effect((N("holding ?r ?o"), A("hand-empty ?r"), A("in ?o ?g"), A("at ?r ?o"))),),
           target="?o"),
    Schema("drop", Skill.DropHandObject, (R, OBJ, ("?f", "thing")),
           (A("can-drop ?r"), A("holding ?r ?o"), A("floor ?f")),
           (Effect((N("holding ?r ?o"), A("hand-empty ?r"), A("in ?o ?f"), A("at ?r ?o"))),),
           target="?o"),
    Schema("push", Skill.PushObject, (R, OBJ),
           (A("can-push ?r"), A("moveable ?o"), *_visible()), (), target="?o"),
    Schema("pull", Skill.PullObject, (R, OBJ),
           (A("can-pull ?r"), A("moveable ?o"), *_visible()), (), target="?o"),
)

SCHEMA_BY_NAME: dict[str, Schema] = {s.name: s for s in SCHEMAS}
SCHEMA_BY_SKILL: dict[Skill, Schema] = {s.skill: s for s in SCHEMAS}

#: derived predicates: hand-written axioms, evaluated in Python by vocabulary.FLUENTS
DERIVED: dict[str, str] = {
    "within": """(:derived (within ?x - thing ?y - thing)
    (or (in ?x ?y) (exists (?z - thing) (and (in ?x ?z) (within ?z ?y)))))""",
    "hidden": """(:derived (hidden ?x - thing)
    (exists (?y - thing) (and (within ?x ?y) (must-open ?y) (not (is-open ?y)))))""",
    "carried": """(:derived (carried ?x - thing)
    (or (exists (?r - robot) (holding ?r ?x)) (exists (?y - thing) (and (in ?x ?y) (carried ?y)))))""",
    "chilled-place": """(:derived (chilled-place ?c - thing)
    (or (cools ?c) (exists (?f - thing) (and (cools ?f) (within ?c ?f)))))""",
    "heated-place": """(:derived (heated-place ?c - thing)
    (exists (?h - thing) (and (heats ?h) (is-on ?h) (or (= ?h ?c) (within ?c ?h)))))""",
    "watered-place": """(:derived (watered-place ?c - thing)
    (exists (?f - thing ?b - thing) (and (waters ?f ?b) (is-on ?f) (or (= ?b ?c) (within ?c ?b)))))""",
}

#: fluents the problem's initial state lists (the derived ones are computed by the planner)
BASIC_FLUENTS: tuple[str, ...] = tuple(p for p in vocabulary.FLUENTS if p not in DERIVED and p != "robot-up")
#: static predicates the domain uses (``controls`` is covered by ``switches``/``waters``)
USED_STATICS: tuple[str, ...] = tuple(p for p in vocabulary.STATICS if p != "controls")

_KIND = {"r": "robot", "o": "thing"}


def _declaration(name: str, kinds: str) -> str:
    names = ("?a", "?b", "?c")
    args = " ".join(f"{names[i]} - {_KIND[k]}" for i, k in enumerate(kinds))
    return f"({name} {args})" if args else f"({name})"


@cache
def domain_pddl() -> str:
    """The domain text (constant: every problem uses it, which keeps cache keys stable)."""
    preds = [_declaration(n, k) for n, (k, _) in vocabulary.FLUENTS.items() if n != "robot-up"]
    preds += [_declaration(n, vocabulary.STATICS[n][0]) for n in USED_STATICS]
    preds += [_declaration(c, "r") for c in vocabulary.CAPABILITIES.values()]
    return "\n".join([
        f"(define (domain {DOMAIN_NAME})",
        "  (:requirements :strips :typing :negative-preconditions :equality :disjunctive-preconditions",
        "   :existential-preconditions :universal-preconditions :conditional-effects :derived-predicates)",
        "  (:types robot thing)",
        "  (:predicates\n    " + "\n    ".join(preds) + ")",
        *("  " + d for d in DERIVED.values()),
        *(s.pddl() for s in SCHEMAS),
        ")",
    ]) + "\n"


# ---- the objects a problem (or a step's grounding) ranges over -------------------------

class DomainError(EmboTeamError):
    """An action the domain cannot ground (unknown skill arguments, missing knife...)."""


#: pending pieces by what they are computed from (every problem, goal compilation and
#: universe asks for them, mostly about the same few states)
_PIECES: dict[tuple[object, ...], dict[str, ObjectState]] = {}


def pending_pieces(state: WorldState, wholes: Sequence[str] | None = None) -> dict[str, ObjectState]:
    """The pieces slicing (or cracking) each whole *would* spawn, as they would be born:
    declared ahead so a plan can name them (``Apple_1_Slice_2``). The result is shared
    between calls with equal inputs: treat its objects as read-only."""
    cat = load_catalogue()
    ids = wholes if wholes is not None else list(state.objects)
    cut: list[ObjectState] = []
    for oid in ids:
        o = state.objects.get(oid)
        if o is None or o.source is not None or o.is_sliced:
            continue
        # the flag first: it rules out most objects at a set lookup (planning asks this
        # hundreds of times a plan, over every object of the scene)
        if not (o.has("sliceable") or o.type == "Egg") or cat.slice_product(o.type) is None:
            continue
        cut.append(o)
    key = (state.floor_plan, *((o.id, o.type, o.properties, o.mass, o.position) for o in cut))
    hit = _PIECES.get(key)
    if hit is None:
        hit = _pieces_of(cut)
        if len(_PIECES) > 512:
            _PIECES.clear()
        _PIECES[key] = hit
    return {p: piece for p, piece in hit.items() if p not in state.objects}


def _pieces_of(wholes: Sequence[ObjectState]) -> dict[str, ObjectState]:
    cat = load_catalogue()
    out: dict[str, ObjectState] = {}
    for o in wholes:
        product = cat.slice_product(o.type)
        if product is None:
            continue
        ptype, n = product
        props = cat.type(ptype).properties | {"pickupable"}
        for pid in piece_ids(o.id, n):
            out[pid] = ObjectState(id=pid, type=ptype, properties=props, mass=round(o.mass / n, 4),
                                   position=o.position, parent=None, is_sliced=True, source=o.id)
    return out


class Universe:
    """Objects, robots and static facts one grounding ranges over.

    ``objects`` are those of the problem (or every object of the state plus the pieces it
    may spawn); static facts come from the vocabulary evaluated on a *view* of the state
    that includes the not-yet-cut pieces, so ``(cookable Bread_1_Slice_1)`` is known
    before the bread is sliced. ``can_place`` optionally narrows placement to the pairs a
    problem declared.
    """

    def __init__(self, state: WorldState, objects: Sequence[str] | None = None,
                 robots: Sequence[str] | None = None, *,
                 can_place: frozenset[tuple[str, str]] | None = None) -> None:
        self.state = state
        pieces = pending_pieces(state)
        self.view = WorldState(floor_plan=state.floor_plan, objects={**state.objects, **pieces},
                               robots=state.robots)
        self.objects: tuple[str, ...] = tuple(objects) if objects is not None else tuple(self.view.objects)
        self._allowed = frozenset(self.objects)
        self.robots: tuple[str, ...] = tuple(robots) if robots is not None else tuple(
            r for r, rs in state.robots.items() if not rs.down)
        self.can_place = can_place
        self._memo: dict[tuple[str, tuple[str, ...]], bool] = {}
        #: groundings by (schema, binding), each with the answers of the state it depended
        #: on (:mod:`emboteam.pddl.recorded`); shared with the views :meth:`at` makes
        self.groundings: dict[tuple[str, tuple[tuple[str, str], ...]], list[Recorded[Grounding]]] = {}

    def static(self, pred: str, args: tuple[str, ...]) -> bool:
        key = (pred, args)
        hit = self._memo.get(key)
        if hit is None:
            if pred == "can-place" and self.can_place is not None:
                hit = args in self.can_place
            elif pred == "sliceable":
                o = self.view.objects.get(args[0])
                hit = o is not None and o.has("sliceable") and load_catalogue().slice_product(o.type) is not None
            elif pred in vocabulary.STATICS:
                hit = _call(vocabulary.STATICS[pred][1], self.view, args)
            else:
                hit = vocabulary.evaluate(Literal(predicate=pred, args=args), self.view)
            self._memo[key] = hit
        return hit

    def truth(self, pred: str, args: tuple[str, ...]) -> bool:
        """Positive truth of a ground atom: statics here, fluents on the live state."""
        entry = vocabulary.FLUENTS.get(pred)
        if entry is not None:
            return _call(entry[1], self.state, args)
        return self.static(pred, args)

    def fluent(self, evaluator: vocabulary.Evaluator, args: tuple[str, ...]) -> bool:
        """A fluent's evaluator on the live state (:func:`_call`)."""
        return _call(evaluator, self.state, args)

    def at(self, state: WorldState) -> Universe:
        """The same objects and (memoised) statics over another state of the same episode:
        statics never change, so a plan's steps share one universe."""
        clone = object.__new__(Universe)
        clone.__dict__.update(self.__dict__)
        clone.state = state
        return clone

    def domain(self, type_: str) -> Sequence[str]:
        return self.robots if type_ == "robot" else self.objects

    def generate(self, atom: Atom, binding: Mapping[str, str], var: str) -> Sequence[str] | None:
        """The few values of ``var`` that may satisfy ``atom`` (containment, pieces,
        controls), so quantified effects do not sweep every object of the scene."""
        if not atom.positive or len(atom.args) != 2:
            return None
        a, b = (binding.get(x, x) for x in atom.args)
        return self.values(atom.pred, a, b, var)

    def values(self, pred: str, a: str, b: str, var: str) -> list[str] | None:
        """:meth:`generate` for ``(pred a b)`` with its arguments bound as far as they are."""
        s = self.state
        if pred == "at" and not a.startswith("?") and b == var:
            # what a robot reaches (goto forgets it all): one distance test per object,
            # not a grounding pass per object; the condition is still tested on each
            if a not in s.robots:
                return []
            # WorldState.in_reach, inlined: the robot's position read once, not per object
            x, z = s.robots[a].position
            objects = s.objects
            return [o for o in self.objects if (t := objects.get(o)) is not None
                    and (t.held_by == a or math.hypot(t.position[0] - x, t.position[2] - z) <= REACH)]
        if pred == "at" and a == var and not b.startswith("?"):
            if b not in s.objects:
                return []
            return [r for r in self.robots if r in s.robots and s.in_reach(r, b)]
        allowed = self._allowed
        if pred in ("within", "in") and a == var and not b.startswith("?"):
            found = s.descendants(b) if pred == "within" else s.children(b)
            return [o.id for o in found if o.id in allowed] if b in s.objects else []
        if pred in ("within", "in") and b == var and not a.startswith("?"):
            if a not in s.objects:
                return []
            chain = s.ancestors(a) if pred == "within" else [p for p in [s.objects[a].parent] if p]
            return [x for x in chain if x in allowed]
        if pred == "piece-of" and a == var and not b.startswith("?"):
            return [p for p in self.objects if p in self.view.objects and self.view.objects[p].source == b]
        if pred in ("switches", "waters", "controls") and b == var and not a.startswith("?"):
            o = self.view.objects.get(a)
            return [c for c in o.controls if c in allowed] if o is not None else []
        if pred in ("switches", "waters", "controls") and a == var and not b.startswith("?"):
            return [o.id for o in self.view.objects.values() if b in o.controls and o.id in allowed]
        return None


def _call(fn: vocabulary.Evaluator, state: WorldState, args: tuple[str, ...]) -> bool:
    """An evaluator on ground arguments; a missing object or robot makes it false (as
    :func:`vocabulary.evaluate` reads it), without building a Literal per fact."""
    try:
        return bool(fn(state, *args))
    except KeyError:
        return False


# ---- grounding --------------------------------------------------------------------------

def _literal(atom: Atom) -> Literal:
    return _literal_of(atom.pred, atom.args, atom.positive)


@lru_cache(maxsize=1 << 16)
def _literal_of(predicate: str, args: tuple[str, ...], positive: bool) -> Literal:
    # built from our own schemas (strings, a tuple of strings, a bool): validating each of
    # the thousands a plan's grounding makes would only repeat what the types say. Shared
    # per atom (a Literal is frozen): a plan grounds the same few thousand literals tens of
    # thousands of times, and a lookup by a plain tuple costs a fraction of model_construct
    return Literal.model_construct(predicate=predicate, args=args, positive=positive)


def action_binding(robot: str, action: Action, state: WorldState) -> tuple[Schema, dict[str, str]]:
    """The schema and parameter values of a simulator action done by ``robot``; the
    knife of a slice, the garbage can of a throw and the floor of a drop come from the
    state, as the simulator picks them."""
    schema = SCHEMA_BY_SKILL[action.skill]
    binding = {"?r": robot, schema.target: action.target}
    if schema.receptacle is not None:
        if action.receptacle is None:
            raise DomainError(f"{action} names no receptacle")
        binding[schema.receptacle] = action.receptacle
    extra = {p for p, _ in schema.params} - set(binding)
    if "?k" in extra:
        held = state.robots[robot].holding if robot in state.robots else None
        if held is None:
            raise DomainError(f"{robot} holds no knife to {action}")
        binding["?k"] = held
    if "?g" in extra:
        cans = sorted((g for g in state.of_type("GarbageCan")),
                      key=lambda g: (not state.in_reach(robot, g.id), state.distance(robot, g.id), g.id))
        if not cans:
            raise DomainError(f"{state.floor_plan} has no GarbageCan for {action}")
        binding["?g"] = cans[0].id
    if "?f" in extra:
        floors = [f.id for f in state.of_type("Floor")]
        if not floors:
            raise DomainError(f"{state.floor_plan} has no Floor for {action}")
        binding["?f"] = floors[0]
    return schema, binding


@dataclass(frozen=True)
class Grounding:
    """One step grounded on the state before it.

    ``fired`` are the effect literals that apply (no-ops included) and ``evaluated`` the
    conditions looked at to decide so, each with its binding and the names of its
    quantified variables: the raw material of the merge's read/write analysis.
    """

    pre: tuple[Literal, ...]
    post: tuple[Literal, ...]
    fired: tuple[tuple[Atom, frozenset[str]], ...]
    evaluated: tuple[tuple[Atom, frozenset[str]], ...]


def ground(schema: Schema, binding: Mapping[str, str], universe: Universe) -> Grounding:
    """Ground preconditions and the effects that fire, evaluated on ``universe.state``
    (the state just before the step).

    ``pre`` lists every precondition literal (universal ones expanded); ``post`` lists the
    positive effects and the negative effects that change something (a delete of an
    already-false fact says nothing worth checking). Equalities are left out. A grounding
    of the same step on an earlier state of the universe is reused when this state gives
    every answer it was computed from (:mod:`emboteam.pddl.recorded`).
    """
    key = (schema.name, tuple(binding.items()))
    return reused(universe.groundings, key, universe,
                  lambda rec: _ground(schema, binding, universe.domain, rec.truth, rec.generate))


def _ground(schema: Schema, binding: Mapping[str, str], domain: Callable[[str], Sequence[str]],
            truth: Truth, generate: Generator) -> Grounding:
    """:func:`ground` with the state's answers from ``truth`` and ``generate``."""
    evaluated: list[tuple[Atom, frozenset[str]]] = []

    def observe(atom: Atom, b: Mapping[str, str], quantified: frozenset[str]) -> None:
        if atom.pred != "=":
            # quantified variables, bound (their value) or not yet (the variable itself)
            evaluated.append((atom.bind(b), frozenset(b.get(v, v) for v in atom.variables() & quantified)))

    pre: list[Literal] = []
    for item in schema.pre:
        if isinstance(item, Atom):
            if item.pred != "=":
                pre.append(_literal(item.bind(binding)))
            continue
        for b in bindings(item.vars, item.guard, binding, domain, truth, None, generate):
            pre.append(_literal(item.then.bind(b)))
    post: dict[Literal, None] = {}
    fired: list[tuple[Atom, frozenset[str]]] = []
    for eff in schema.effects:
        for b in bindings(eff.vars, eff.when, binding, domain, truth, observe, generate):
            quantified = frozenset(b[v] for v, _ in eff.vars)
            for atom in eff.then:
                g = atom.bind(b)
                fired.append((g, quantified & frozenset(g.args)))
                # a delete is kept when its fact holds now (holds(g.negate(), ...), without
                # building the negated atom)
                if g.positive or (g.args[0] == g.args[1] if g.pred == "=" else truth(g.pred, g.args)):
                    post.setdefault(_literal(g), None)
    # an add and a delete of one fact: the add wins (PDDL semantics in Fast Downward)
    adds = {(lit.predicate, lit.args) for lit in post if lit.positive}
    out = tuple(lit for lit in post if lit.positive or (lit.predicate, lit.args) not in adds)
    return Grounding(pre=tuple(dict.fromkeys(pre)), post=out, fired=tuple(fired),
                     evaluated=tuple(evaluated))


def ground_action(robot: str, action: Action, state: WorldState, *, universe: Universe | None = None
                  ) -> Grounding:
    """:func:`ground` for a simulator action (see :func:`step_literals`)."""
    if robot not in state.robots:
        raise DomainError(f"no robot {robot!r} in the team")
    for oid in (action.target, action.receptacle):
        if oid is not None and oid not in state.objects:
            raise DomainError(f"{action}: no object {oid!r} in {state.floor_plan}")
    schema, binding = action_binding(robot, action, state)
    return ground(schema, binding, universe or Universe(state))


def step_literals(robot: str, action: Action, state: WorldState, *, universe: Universe | None = None
                  ) -> tuple[tuple[Literal, ...], tuple[Literal, ...]]:
    """The grounded PDDL preconditions and effects of ``robot`` doing ``action`` in
    ``state`` (the state just before it): ``(pre, post)``.

    ``pre`` must hold for the step to run as planned; ``post`` holds right after it
    (:func:`emboteam.pddl.vocabulary.observable` says which of them a Post check should
    look at). Raises :class:`DomainError` when the action cannot be grounded.
    """
    g = ground_action(robot, action, state, universe=universe)
    return g.pre, g.post


def to_action(schema: Schema, args: Sequence[str]) -> tuple[str, Action]:
    """(robot, simulator action) of a ground PDDL action with the schema's arguments."""
    if len(args) != len(schema.params):
        raise DomainError(f"{schema.name} takes {len(schema.params)} arguments, got {list(args)}")
    values = {p: a for (p, _), a in zip(schema.params, args, strict=True)}
    receptacle = values[schema.receptacle] if schema.receptacle is not None else None
    return values["?r"], Action(skill=schema.skill, target=values[schema.target], receptacle=receptacle)
