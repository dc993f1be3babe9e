"""The capability model: what it takes to make a condition true in a scene, under the
simulator's rules. Next to ``sim/rules.py`` and ``sim/physics.py`` because it is their
consequence; every other answer to the question is a view of it (docs/architecture.md):
the benchmark's solvability claims and the SMART-LLM importer's flags read
:func:`analyse_goal`; the planner's allocation and time estimates (``hp/requirements.py``)
build their roles from :class:`Role` and the appliances the helpers here pick; the
appliances and heat/cold/water sources come from the catalogue only.
``tests/test_capability_agreement.py`` runs what the model proposes in the simulator, for
every predicate and every appliance.

For every goal condition we enumerate the *methods* that make it true in the symbolic
simulator (``sim/rules.py``, ``sim/physics.py``): an apple gets into a fridge by someone
opening the fridge and someone carrying the apple (or a slice of it) there; a potato gets
cooked in a microwave (open, carry, close, switch on, as the door and the power
interlock), in a pan or pot on a burner whose knob is on, and so on. A method is a list
of grounded :class:`Step`\\ s, each tagged with a *role*; the steps of one role must be
done by one robot (whoever picks the knife up is the one who slices), so a role needs a
set of skills and the strength to lift the heaviest object it picks up.

- A single robot *can* achieve a condition only if it covers every role of some method.
  For the designs in MACE-THOR this is exact: every way the simulator offers to reach a
  condition is enumerated, so a robot that covers no method provably cannot do it.
- A team can achieve a condition if every role of some method is covered by a member.
  That is necessary, not sufficient (one hand each, order, a robot that cannot put a
  knife down); the suite's tests therefore also *execute* the chosen methods in the
  simulator (``tests/test_bench_suite_solvability.py``).

Limits, stated so the negative claims can be trusted where they are used: conditions are
analysed one at a time on the given state; for a count-N condition the N candidates come
from one method family (one destination, one route), cheapest in skills or lightest
first, so a mix of routes is not considered; carrying a container moves what is in it,
but pieces not yet cut are never carried that way. MACE-THOR's single-robot claims rest on
a skill or a strength that every route needs, which these limits do not touch.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from emboteam.sim.physics import is_cold_source
from emboteam.sim.rules import piece_ids
from emboteam.world.actions import Action, Skill
from emboteam.world.catalogue import (
    BREWERS,
    BURNERS,
    COLD_SOURCES,
    HEATERS,
    INTERLOCKED,
    KNIVES,
    WATER_SOURCES,
    load_catalogue,
    place_types,
)
from emboteam.world.checker import check_condition, matches
from emboteam.world.goals import Condition, Goal, ObjectRef, Predicate
from emboteam.world.robots import RobotProfile
from emboteam.world.state import ObjectState, WorldState


@dataclass(frozen=True, slots=True)
class Step:
    """One grounded action of a method, for the robot playing ``role``."""

    role: str
    action: Action
    near: str  #: the object the robot stands at (its GoToObject target)
    lift: float = 0.0  #: kg picked up by this step

    def __str__(self) -> str:
        return f"{self.role}: {self.action}"


@dataclass(frozen=True, slots=True)
class Role:
    """A job one robot must do: any one of ``options`` (skills it must all have), lifting
    ``lift`` kg. The methods here give one option per role; the planner's coarser view
    (``hp/requirements.py``) gives several, and marks ``certain`` the roles every way of
    satisfying the condition needs (only those may reject a team outright)."""

    name: str
    options: tuple[frozenset[Skill], ...]
    lift: float = 0.0
    certain: bool = False

    @classmethod
    def of(cls, name: str, *options: Iterable[Skill], lift: float = 0.0, certain: bool = False) -> Role:
        return cls(name, tuple(frozenset(o) for o in options), lift, certain)

    @property
    def skills(self) -> frozenset[Skill]:
        """The skills of the first option (a method's role has just one)."""
        return self.options[0]

    def covered_by(self, robot: RobotProfile) -> bool:
        return robot.mass_capacity >= self.lift and any(opt <= robot.skills for opt in self.options)

    def shortfall(self, robot: RobotProfile) -> list[str]:
        """What the robot lacks for this role (empty if it covers it), by the closest option."""
        lacking = min(([s.value for s in Skill if s in opt - robot.skills] for opt in self.options), key=len)
        if self.lift > robot.mass_capacity:
            lacking.append(f"lifting {self.lift:g} kg (max {robot.mass_capacity:g})")
        return lacking


@dataclass(frozen=True, slots=True)
class Method:
    """One way to make a condition true: steps in an executable order."""

    label: str
    steps: tuple[Step, ...]

    @property
    def roles(self) -> tuple[Role, ...]:
        skills: dict[str, set[Skill]] = {}
        lift: dict[str, float] = {}
        for s in self.steps:
            skills.setdefault(s.role, {Skill.GoToObject}).add(s.action.skill)
            lift[s.role] = max(lift.get(s.role, 0.0), s.lift)
        return tuple(Role(n, (frozenset(skills[n]),), lift[n]) for n in skills)

    @property
    def skills(self) -> frozenset[Skill]:
        """Every skill the method needs, whoever plays which role."""
        return frozenset().union(*(r.skills for r in self.roles))

    @property
    def lift(self) -> float:
        return max((r.lift for r in self.roles), default=0.0)

    def signature(self) -> frozenset[tuple[str, frozenset[Skill], float]]:
        return frozenset((r.name, r.skills, r.lift) for r in self.roles)

    def binding(self, team: Sequence[RobotProfile]) -> dict[str, RobotProfile] | None:
        """A team member for every role (the first that covers it), or None."""
        out: dict[str, RobotProfile] = {}
        for role in self.roles:
            robot = next((r for r in team if role.covered_by(r)), None)
            if robot is None:
                return None
            out[role.name] = robot
        return out

    def __str__(self) -> str:
        return f"{self.label}: " + "; ".join(str(s) for s in self.steps)


@dataclass(frozen=True, slots=True)
class ConditionAnalysis:
    """The methods for one condition (none: impossible; an empty one: holds already)."""

    condition: Condition
    methods: tuple[Method, ...]

    @property
    def holds(self) -> bool:
        return any(not m.steps for m in self.methods)

    def team_method(self, team: Sequence[RobotProfile]) -> Method | None:
        return next((m for m in self.methods if m.binding(team) is not None), None)

    def solo_method(self, robot: RobotProfile) -> Method | None:
        return next((m for m in self.methods if m.binding([robot]) is not None), None)

    def gap(self, robot: RobotProfile) -> str:
        """What ``robot`` alone lacks for the closest method (``robot23 lacks PickupObject``)."""
        if not self.methods:
            return "no way to achieve it in this scene"
        best: list[str] | None = None
        for m in self.methods:
            gaps = sorted({g for role in m.roles for g in role.shortfall(robot)})
            if best is None or len(gaps) < len(best):
                best = gaps
        return f"{robot.name} lacks " + ", ".join(best or ["nothing"])

    def why_not(self, robot: RobotProfile) -> str:
        """Why ``robot`` alone cannot achieve the condition."""
        return f"{self.condition}: {self.gap(robot)}"


@dataclass(frozen=True, slots=True)
class GoalAnalysis:
    conditions: tuple[ConditionAnalysis, ...]

    def team_can(self, team: Sequence[RobotProfile]) -> bool:
        """Every condition has a method the team covers (necessary for solvability)."""
        return all(c.team_method(team) is not None for c in self.conditions)

    def robot_can(self, robot: RobotProfile) -> bool:
        """Could this robot alone cover every condition? False proves it cannot."""
        return all(c.solo_method(robot) is not None for c in self.conditions)

    def gaps(self, robot: RobotProfile) -> list[str]:
        return [c.why_not(robot) for c in self.conditions if c.solo_method(robot) is None]


# ---- candidates ---------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class _Cand:
    """An object that could satisfy a condition: one that exists, or a piece-to-be."""

    id: str
    type: str
    mass: float
    whole: str | None = None  #: for a piece not cut yet: the whole it comes from

    @property
    def exists(self) -> bool:
        return self.whole is None


def _candidates(ref: ObjectRef, state: WorldState) -> list[_Cand]:
    cat = load_catalogue()
    out: list[_Cand] = []
    for o in state.objects.values():
        if o.gone:
            continue
        if matches(ref, o, state):
            out.append(_Cand(o.id, o.type, o.mass))
        product = cat.slice_product(o.type)
        if product is None or o.is_sliced or not o.has("sliceable"):
            continue
        piece_type, n = product
        if ref.id == o.id or piece_type in ref.types or o.type in ref.types:
            out.extend(_Cand(pid, piece_type, round(o.mass / n, 4), o.id) for pid in piece_ids(o.id, n))
    return out


def _type_has(type_name: str, prop: str) -> bool:
    cat = load_catalogue()
    return type_name in cat.types and cat.type(type_name).has(prop)


# ---- the method builder -------------------------------------------------------------------

_Alt = tuple[str, tuple[Step, ...]]  # (family label, steps) for one candidate


def _join(*parts: Sequence[Step]) -> tuple[Step, ...]:
    """Concatenate step lists, dropping repeats (two routes that open the same cabinet
    open it once)."""
    out: list[Step] = []
    for part in parts:
        out += [s for s in part if s not in out]
    return tuple(out)


class _Builder:
    """Enumerates step lists on one state. Families group alternatives that may be
    combined for count-N conditions (same destination, same route)."""

    def __init__(self, state: WorldState) -> None:
        self.s = state
        self.cat = load_catalogue()

    # -- primitives --
    def _obj(self, oid: str) -> ObjectState:
        return self.s.objects[oid]

    def access(self, oid: str) -> list[Step]:
        """Open every closed container around an object that hides it, outermost first
        (an interlocked appliance that runs must be switched off before its door opens). As
        in the simulator (``WorldState.enclosing_closed``), only what things go *in* hides
        them: a closed toilet does not hide what stands on its tank."""
        steps: list[Step] = []
        for rid in reversed(self.s.ancestors(oid)):
            r = self._obj(rid)
            if r.type in self.cat.must_be_open and not r.is_open:
                steps += self.open(rid)
        return steps

    def open(self, oid: str) -> list[Step]:
        o = self._obj(oid)
        steps: list[Step] = []
        if o.type in INTERLOCKED and o.is_on:
            steps.append(Step("switcher", Action(skill=Skill.SwitchOff, target=oid), oid))
        steps.append(Step("opener", Action(skill=Skill.OpenObject, target=oid), oid))
        return steps

    def open_for_put(self, rid: str) -> list[Step]:
        r = self._obj(rid)
        steps = self.access(rid)
        if r.type in self.cat.must_be_open and not r.is_open:
            steps += self.open(rid)
        return steps

    def carry(self, oid: str, mass: float, rid: str, role: str = "carrier") -> list[Step]:
        return [Step(role, Action(skill=Skill.PickupObject, target=oid), oid, mass),
                Step(role, Action(skill=Skill.PutObject, target=oid, receptacle=rid), rid)]

    def switch(self, oid: str, on: bool) -> list[Step]:
        o = self._obj(oid)
        if o.is_on == on:
            return []
        steps: list[Step] = []
        if on and o.type in INTERLOCKED and o.is_open:
            steps.append(Step("opener", Action(skill=Skill.CloseObject, target=oid), oid))
        skill = Skill.SwitchOn if on else Skill.SwitchOff
        return [*steps, Step("switcher", Action(skill=skill, target=oid), oid)]

    def knives(self) -> list[ObjectState]:
        return [k for k in self.s.objects.values() if k.type in KNIVES and not k.gone and k.held_by is None]

    def cut(self, whole: str) -> list[list[Step]]:
        """Ways to cut a whole into pieces: slice it holding a knife, or (an Egg) break it."""
        w = self._obj(whole)
        alts: list[list[Step]] = []
        reach = self.access(whole)
        for k in self.knives():
            alts.append(self.access(k.id) + reach + [
                Step("slicer", Action(skill=Skill.PickupObject, target=k.id), k.id, k.mass),
                Step("slicer", Action(skill=Skill.SliceObject, target=whole), whole)])
        if w.type == "Egg" and w.has("breakable"):
            alts.append([*reach, Step("breaker", Action(skill=Skill.BreakObject, target=whole), whole)])
        return alts

    def obtain(self, c: _Cand) -> list[list[Step]]:
        """Ways to make a candidate available to act on."""
        if c.exists:
            return [self.access(c.id)]
        assert c.whole is not None
        return self.cut(c.whole)

    def movers(self, c: _Cand) -> list[tuple[str, str, float]]:
        """What can be carried to bring a candidate somewhere: itself, or a pickupable
        container it sits in (carrying a plate carries the apple on it). Only what can be
        picked up moves."""
        movable = self._obj(c.id).has("pickupable") if c.exists else _type_has(c.type, "pickupable")
        out = [(c.id, c.type, c.mass)] if movable else []
        if c.exists:
            for rid in self.s.ancestors(c.id):
                r = self._obj(rid)
                if r.has("pickupable"):
                    out.append((r.id, r.type, r.mass))
        return out

    def within(self, c: _Cand, rid: str) -> bool:
        return c.exists and self.s.is_within(c.id, rid)

    def bring(self, c: _Cand, rid: str) -> list[list[Step]]:
        """Ways to get a candidate in/on receptacle ``rid`` (``[[]]``: it is there)."""
        if self.within(c, rid):
            return [[]]
        r = self._obj(rid)
        if r.gone or r.id == c.id or (c.exists and self.s.is_within(rid, c.id)):
            return []
        alts: list[list[Step]] = []
        for mover, mtype, mass in self.movers(c):
            if not self.cat.can_place(mtype, r.type) or mover == rid:
                continue
            prep = self.obtain(c) if mover == c.id else [self.access(mover)]
            for p in prep:
                alts.append(p + self.open_for_put(rid) + self.carry(mover, mass, rid))
        return alts

    def throw(self, c: _Cand, can: str) -> list[list[Step]]:
        """ThrowObject lands the held object in the garbage can whatever its placement rules."""
        pick = Step("carrier", Action(skill=Skill.PickupObject, target=c.id), c.id, c.mass)
        toss = Step("carrier", Action(skill=Skill.ThrowObject, target=c.id), can)
        return [[*p, pick, toss] for p in self.obtain(c)]

    def of_types(self, *types: str) -> list[ObjectState]:
        return [o for o in self.s.objects.values() if o.type in types and not o.gone]

    def knob_for(self, burner: str) -> ObjectState | None:
        return next((k for k in self.of_types("StoveKnob") if burner in k.controls), None)

    def burner_of(self, oid: str) -> str | None:
        return next((a for a in self.s.ancestors(oid) if self._obj(a).type in BURNERS), None)

    def water_sources(self) -> list[ObjectState]:
        return [f for f in self.of_types(*WATER_SOURCES) if f.has("toggleable") and f.controls]

    # -- per-predicate alternatives for one candidate --
    def place(self, c: _Cand, where: tuple[str, ...]) -> list[_Alt]:
        alts: list[_Alt] = []
        for r in self.of_types(*place_types(where)):
            alts += [(f"put in {r.id}", _join(a)) for a in self.bring(c, r.id)]
            if r.type == "GarbageCan" and not self.within(c, r.id):
                alts += [(f"throw in {r.id}", _join(a)) for a in self.throw(c, r.id)]
        return alts

    def heat(self, c: _Cand, cook: bool) -> list[_Alt]:
        alts: list[_Alt] = []
        for m in self.of_types(*sorted(HEATERS & INTERLOCKED)):
            for a in self.bring(c, m.id):
                # the door is open after a delivery (or was): close it, then power on
                door = [Step("opener", Action(skill=Skill.CloseObject, target=m.id), m.id)] \
                    if a or m.is_open else []
                stopped = any(s.action.skill is Skill.SwitchOff for s in a)
                power = [] if m.is_on and not stopped else \
                    [Step("switcher", Action(skill=Skill.SwitchOn, target=m.id), m.id)]
                alts.append((f"microwave {m.id}", _join(a, door, power)))
        plain = sorted(HEATERS - INTERLOCKED - BURNERS) + ([] if cook else sorted(BREWERS))
        for t in self.of_types(*plain):
            alts += [(f"{t.type} {t.id}", _join(a, self.switch(t.id, True))) for a in self.bring(c, t.id)]
        vessels = tuple(sorted({v for b in BURNERS for v in self.cat.receptacle_whitelist.get(b, ())}))  # Pan, Pot, Kettle
        for burner in self.of_types(*BURNERS):
            knob = self.knob_for(burner.id)
            if knob is None:
                continue
            on = self.switch(knob.id, True)
            if c.type in vessels:
                alts += [(f"stove {burner.id}", _join(a, on)) for a in self.bring(c, burner.id)]
                continue
            for vessel in self.of_types(*vessels):
                at = self.burner_of(vessel.id)
                if vessel.id == c.id or (at is not None and at != burner.id):
                    continue
                to_burner = [[]] if at == burner.id else \
                    self.bring(_Cand(vessel.id, vessel.type, vessel.mass), burner.id)
                alts += [(f"stove {burner.id} in {vessel.id}", _join(a, b, on))
                         for a in self.bring(c, vessel.id) for b in to_burner]
        return alts

    def water(self, c: _Cand) -> list[_Alt]:
        """Running water reaches everything within the places a faucet controls (a sink
        and its basin): bring the candidate there, turn the faucet on."""
        alts: list[_Alt] = []
        for faucet in self.water_sources():
            on = self.switch(faucet.id, True)
            for place in faucet.controls:
                if place not in self.s.objects or not (self.within(c, place) or self._obj(place).has("receptacle")):
                    continue
                alts += [(f"water in {place}", _join(a, on)) for a in self.bring(c, place)]
        return alts

    def unary(self, c: _Cand, pred: Predicate, liquid: str | None) -> list[_Alt]:
        """Alternatives for one candidate of a one-argument condition."""
        o = self.s.objects.get(c.id)
        reach = [self.access(c.id)] if o is not None else []
        name = pred.value
        if pred in (Predicate.switched_on, Predicate.switched_off):
            if o is None or not o.has("toggleable") or (pred is Predicate.switched_on and o.is_broken):
                return []
            return [(name, _join(r, self.switch(c.id, pred is Predicate.switched_on))) for r in reach]
        if pred in (Predicate.open, Predicate.closed):
            if o is None or not o.has("openable"):
                return []
            if o.is_open == (pred is Predicate.open):
                return [(name, ())]
            if pred is Predicate.open:
                return [(name, _join(r, self.open(c.id))) for r in reach]
            return [(name, _join(r, [Step("closer", Action(skill=Skill.CloseObject, target=c.id), c.id)]))
                    for r in reach]
        if pred is Predicate.broken:
            if o is not None and o.is_broken:
                return [(name, ())]
            if not _type_has(c.type, "breakable"):
                return []
            return [(name, _join(p, [Step("breaker", Action(skill=Skill.BreakObject, target=c.id), c.id)]))
                    for p in self.obtain(c)]
        if pred is Predicate.held:
            if o is not None and o.held_by is not None:
                return [(name, ())]
            return [(name, _join(p, [Step("holder", Action(skill=Skill.PickupObject, target=c.id), c.id,
                                           c.mass)])) for p in self.obtain(c)]
        if pred is Predicate.hot:
            if o is not None and o.temperature == "Hot":
                return [(name, ())]
            return self.heat(c, cook=False)
        if pred is Predicate.cooked:
            if o is not None and o.is_cooked:
                return [(name, ())]
            return self.heat(c, cook=True) if _type_has(c.type, "cookable") else []
        if pred is Predicate.cold:
            if o is not None and o.temperature == "Cold":
                return [(name, ())]
            return [(f"fridge {f.id}", _join(a)) for f in self.of_types(*COLD_SOURCES)
                    if is_cold_source(f) for a in self.bring(c, f.id)]
        if pred is Predicate.clean:
            if o is None or not o.is_dirty:
                return [(name, ())]
            scrub = [("scrub", _join(r, [Step("cleaner", Action(skill=Skill.CleanObject, target=c.id), c.id)]))
                     for r in reach]
            return self.water(c) + scrub
        if pred is Predicate.dirty:
            return [(name, ())] if o is not None and o.is_dirty else []
        if pred is Predicate.filled:
            if o is not None and o.liquid is not None:
                return [(name, ())] if liquid in (None, o.liquid) else []
            if not _type_has(c.type, "canFillWithLiquid"):
                return []
            alts: list[_Alt] = []
            if liquid in (None, "water"):
                alts += self.water(c)
            if liquid in (None, "coffee"):
                for cm in self.of_types(*BREWERS):
                    alts += [(f"coffee {cm.id}", _join(a, self.switch(cm.id, True)))
                             for a in self.bring(c, cm.id)]
            return alts
        raise AssertionError(pred)

    def sliced(self, c: _Cand) -> list[_Alt]:
        o = self._obj(c.id)
        if o.is_sliced:
            return [("sliced", ())]
        if not o.has("sliceable") or self.cat.slice_product(o.type) is None:
            return []
        return [("sliced", _join(a)) for a in self.cut(c.id)]


# ---- the appliances the planner's estimate picks (hp/requirements.py) -----------------------


def heater_for(state: WorldState, type_name: str | None, *, cook: bool) -> str | None:
    """The appliance to heat an object of ``type_name`` in: the first heater that takes it
    directly (microwave, toaster), else, to make it hot, a brewer (a Mug in a coffee
    machine), else the first stove burner (in a pan or pot)."""
    cat = load_catalogue()
    direct = HEATERS - BURNERS
    for pool in (direct, frozenset() if cook else BREWERS):
        for h in state.objects.values():
            if h.type in pool and type_name is not None and cat.can_place(type_name, h.type):
                return h.id
    burners = list(state.of_type(*BURNERS))
    return burners[0].id if burners else None


def cold_source(state: WorldState) -> str | None:
    """The first object that cools what is in it (a fridge flagged ``isColdSource``)."""
    return next((f.id for f in state.of_type(*COLD_SOURCES) if is_cold_source(f)), None)


def brewer(state: WorldState) -> str | None:
    """The first coffee machine."""
    return next((c.id for c in state.of_type(*BREWERS)), None)


def water_basin(state: WorldState) -> tuple[str | None, str | None]:
    """The first water source and a receptacle its water reaches (a faucet and its basin)."""
    for f in state.objects.values():
        if f.type in WATER_SOURCES:
            for b in f.controls:
                if b in state.objects and state.objects[b].has("receptacle"):
                    return f.id, b
    return None, None


# ---- combining candidates -----------------------------------------------------------------


def _requirement(steps: Iterable[Step]) -> tuple[int, float]:
    skills = {s.action.skill for s in steps}
    return (len(skills), max((s.lift for s in steps), default=0.0))


def _combine(per_cand: list[tuple[_Cand, list[_Alt]]], count: int) -> list[Method]:
    """Methods for ``count`` distinct candidates: per family, the cheapest and the lightest
    ``count`` candidates (a whole and the pieces it would be cut into exclude each other)."""
    families: dict[str, list[tuple[_Cand, tuple[Step, ...]]]] = {}
    for cand, alts in per_cand:
        for family, steps in alts:
            families.setdefault(family, []).append((cand, steps))
    orders = (lambda o: (_requirement(o[1]), o[0].mass), lambda o: (_requirement(o[1])[1], o[0].mass))
    methods: list[Method] = []
    for family, options in families.items():
        for order in orders:
            chosen: list[tuple[Step, ...]] = []
            ids: set[str] = set()
            whole_kept: set[str] = set()  # wholes counted as themselves
            whole_cut: set[str] = set()  # wholes counted through their pieces
            for cand, steps in sorted(options, key=order):
                if cand.id in ids or cand.id in whole_cut or (cand.whole or "") in whole_kept:
                    continue
                ids.add(cand.id)
                if cand.whole is None:
                    whole_kept.add(cand.id)
                else:
                    whole_cut.add(cand.whole)
                chosen.append(steps)
                if len(chosen) == count:
                    methods.append(Method(family, _join(*chosen)))
                    break
    # one method per role signature, fewest steps first
    methods.sort(key=lambda m: (len(m.steps), m.label))
    seen: set[frozenset[tuple[str, frozenset[Skill], float]]] = set()
    unique: list[Method] = []
    for m in methods:
        if m.signature() not in seen:
            seen.add(m.signature())
            unique.append(m)
    return unique


def analyse_condition(cond: Condition, state: WorldState) -> ConditionAnalysis:
    """Every way (up to role signature) to make ``cond`` true from ``state``."""
    if check_condition(cond, state).holds:
        return ConditionAnalysis(cond, (Method("holds already", ()),))
    b = _Builder(state)
    if cond.predicate is Predicate.sliced:
        cands = [c for c in _candidates(cond.subject, state) if c.exists and state.objects[c.id].source is None]
        per_cand = [(c, b.sliced(c)) for c in cands]
    elif cond.predicate is Predicate.inside:
        assert cond.receptacle is not None
        where = cond.receptacle
        per_cand = []
        for c in _candidates(cond.subject, state):
            if where.id is not None:
                alts = [(f"put in {where.id}", _join(a)) for a in b.bring(c, where.id)] if where.id in state.objects \
                    else []
                if where.id in state.objects and state.objects[where.id].type == "GarbageCan":
                    alts += [(f"throw in {where.id}", _join(a)) for a in b.throw(c, where.id)]
            else:
                alts = b.place(c, where.types)
            per_cand.append((c, alts))
    else:
        per_cand = [(c, b.unary(c, cond.predicate, cond.liquid)) for c in _candidates(cond.subject, state)]
    return ConditionAnalysis(cond, tuple(_combine(per_cand, cond.count)))


def analyse_goal(goal: Goal, state: WorldState) -> GoalAnalysis:
    return GoalAnalysis(tuple(analyse_condition(c, state) for c in goal.conditions))
