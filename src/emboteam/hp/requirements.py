"""The planner's view of the capability model (``sim/capability.py``): the *roles* robots
must fill to achieve a condition (carry the apple, open the fridge, switch on the
microwave), each a bundle of skills one robot must have together, plus a mass to lift.
Used to allocate robots before planning, to explain why a team cannot do something, and
to estimate how long a subtask keeps a robot busy.

The roles are the model's :class:`~emboteam.sim.capability.Role`, and the appliances
(which one heats, cools, waters) are the ones the model picks, so the planner and the
benchmark's solvability claims read the same rules (``tests/test_capability_agreement.py``
checks this view against the model). The view is coarse and fast:
it looks at the most promising candidate object (the one the goal compiler ranks first)
and is an estimate; Fast Downward has the last word. Only roles every way of satisfying
the condition needs (``certain``) may reject a team outright.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from functools import lru_cache

from emboteam.pddl.errors import ImpossibleGoalError, MissingSkillError
from emboteam.pddl.goal_compiler import GoalPart, StateView, compile_condition
from emboteam.sim.capability import Role, brewer, cold_source, heater_for, water_basin
from emboteam.sim.durations import ACTION_SECONDS, navigation_seconds
from emboteam.world.actions import Skill
from emboteam.world.catalogue import HEATERS, INTERLOCKED, load_catalogue
from emboteam.world.goals import Condition, Predicate
from emboteam.world.robots import RobotProfile
from emboteam.world.state import WorldState

S = Skill


@dataclass(frozen=True)
class Need:
    """The roles of one condition: any one alternative, all of its roles."""

    condition: Condition
    alternatives: tuple[tuple[Role, ...], ...]
    #: objects a robot will drive to, in order (navigation estimate)
    visits: tuple[str, ...] = ()
    #: seconds of manipulation expected
    work: float = 0.0
    part: GoalPart | None = field(default=None, compare=False)

    @property
    def satisfied(self) -> bool:
        return self.alternatives == ((),)


def _role(what: str, *options: Iterable[Skill], mass: float = 0.0, certain: bool = False) -> Role:
    return Role.of(what, *options, lift=mass, certain=certain)


def _mass(state: WorldState, part: GoalPart, oid: str) -> float:
    o = state.objects.get(oid)
    if o is not None:
        return o.mass
    whole = oid.split("_Slice_")[0]
    product = load_catalogue().slice_product(state.objects[whole].type) if whole in state.objects else None
    return round(state.objects[whole].mass / product[1], 4) if product else 0.0


def _anchor(state: WorldState, oid: str) -> str:
    """Where an object (or the whole a pending piece comes from) is."""
    return oid if oid in state.objects else oid.split("_Slice_")[0]


def _opener(state: WorldState, oid: str) -> list[Role]:
    hider = state.enclosing_closed(_anchor(state, oid)) if _anchor(state, oid) in state.objects else None
    return [_role(f"open {hider}", [S.OpenObject])] if hider else []


def _cutter(state: WorldState, oid: str) -> list[Role]:
    """A piece not cut yet: someone slices its whole first (with a knife in hand)."""
    if oid in state.objects:
        return []
    whole = _anchor(state, oid)
    crack = [[S.BreakObject]] if whole in state.objects and state.objects[whole].type == "Egg" else []
    return [_role(f"slice {whole}", [S.SliceObject, S.PickupObject], *crack)]


def _type_of(state: WorldState, oid: str) -> str | None:
    """The type of an object, or of the piece a pending slice will be."""
    if oid in state.objects:
        return state.objects[oid].type
    whole = state.objects.get(_anchor(state, oid))
    product = load_catalogue().slice_product(whole.type) if whole is not None else None
    return product[0] if product else None


@dataclass(frozen=True)
class _Subject:
    """What every predicate's rule reads about a condition: computed once in
    :func:`need_of`, so that the rules stay small and see the same facts."""

    cond: Condition
    state: WorldState
    part: GoalPart
    #: the most promising candidate object (the goal compiler ranks it first)
    s: str
    mass: float
    #: the lightest candidate: a robot unable to lift even that one certainly fails
    lightest: float
    carry: Role
    opener: list[Role]

    def need(self, roles: Sequence[Role], visits: tuple[str, ...], work: float) -> Need:
        """A need with one alternative."""
        return Need(self.cond, (tuple(roles),), visits, work, self.part)


def _held(x: _Subject) -> Need:
    roles = [_role(f"hold {x.s}", [S.PickupObject], mass=x.lightest, certain=True), *x.opener,
             *_cutter(x.state, x.s)]
    return x.need(roles, (x.s,), ACTION_SECONDS[S.PickupObject])


def _place_openers(state: WorldState, place: str) -> list[Role]:
    """Open what hides the place, and the place itself if it must be open to put into."""
    roles = _opener(state, place)
    p = state.objects[place]
    if p.type in load_catalogue().must_be_open and not p.is_open:
        roles.append(_role(f"open {place}", [S.OpenObject]))
    return roles


def _inside(x: _Subject) -> Need:
    state, s = x.state, x.s
    place = x.part.places[0] if x.part.places else None
    options = [[S.PickupObject, S.PutObject]]
    if place is not None and state.objects[place].type == "GarbageCan":
        options.append([S.PickupObject, S.ThrowObject])
    roles = [_role(f"carry {s}", *options, mass=x.mass), *x.opener, *_cutter(state, s),
             _role(f"move {x.cond.subject}", [S.PickupObject], mass=x.lightest, certain=True)]
    if place is not None:
        roles += _place_openers(state, place)
    a = ACTION_SECONDS
    return x.need(roles, (s, place) if place else (s,), a[S.PickupObject] + a[S.PutObject])


def _sliced(x: _Subject) -> Need:
    state, s = x.state, x.s
    egg = state.objects[s].type == "Egg"
    options = [[S.SliceObject, S.PickupObject]]
    if egg:
        options.append([S.BreakObject])
    roles = [_role(f"slice {s}", *options), *x.opener]
    if not egg:
        roles.append(_role(f"slice {x.cond.subject}", [S.SliceObject], certain=True))
    knives = [k.id for k in state.of_type("Knife", "ButterKnife")]
    return x.need(roles, (*knives[:1], s), ACTION_SECONDS[S.PickupObject] + ACTION_SECONDS[S.SliceObject])


#: predicates one action of one skill on the object achieves
_SINGLE = {Predicate.broken: S.BreakObject, Predicate.switched_on: S.SwitchOn,
           Predicate.switched_off: S.SwitchOff, Predicate.open: S.OpenObject,
           Predicate.closed: S.CloseObject}


def _single(x: _Subject) -> Need:
    skill = _SINGLE[x.cond.predicate]
    roles = [_role(f"{skill.value} {x.s}", [skill], certain=True), *x.opener]
    o = x.state.objects[x.s]
    if x.cond.predicate is Predicate.switched_on and o.type in INTERLOCKED and o.is_open:
        roles.append(_role(f"close {x.s}", [S.CloseObject]))
    return x.need(roles, (x.s,), ACTION_SECONDS[skill])


def _heater_roles(state: WorldState, h: str) -> list[Role]:
    """Switch the heater on (by its own switch or the stove knob controlling it), and
    open and close it when its door interlocks with its power."""
    ho = state.objects[h]
    switch = h if ho.has("toggleable") else next(
        (k.id for k in state.of_type("StoveKnob") if h in k.controls), h)
    roles = [] if ho.is_on else [_role(f"switch on {switch}", [S.SwitchOn])]
    if ho.type in INTERLOCKED:
        roles += [_role(f"open {h}", [S.OpenObject]), _role(f"close {h}", [S.CloseObject])]
    return roles


def _heated(x: _Subject) -> Need:
    state, s = x.state, x.s
    heater = heater_for(state, _type_of(state, s), cook=x.cond.predicate is Predicate.cooked)
    chain = state.ancestors(_anchor(state, s)) if _anchor(state, s) in state.objects else []
    inside = next((h for h in chain if state.objects[h].type in HEATERS), None)
    roles = [] if inside else [x.carry, *x.opener]
    h = inside or heater
    if h is not None:
        roles += _heater_roles(state, h)
    if s not in state.objects:  # a piece: cut the whole first
        roles.append(_role(f"slice {_anchor(state, s)}", [S.SliceObject, S.PickupObject]))
    return x.need(roles, (s, h) if h else (s,), 4.0)


def _cold(x: _Subject) -> Need:
    fridge = cold_source(x.state)
    roles = [x.carry, *x.opener, *_cutter(x.state, x.s)]
    if fridge is not None and not x.state.objects[fridge].is_open:
        roles.append(_role(f"open {fridge}", [S.OpenObject]))
    return x.need(roles, (x.s, fridge) if fridge else (x.s,), 3.5)


def _watered(x: _Subject) -> Need:
    state, s, pred = x.state, x.s, x.cond.predicate
    faucet, basin = water_basin(state)
    if pred is Predicate.filled and x.cond.liquid == "coffee":
        faucet = basin = brewer(state)
    roles = [x.carry, *x.opener]
    if faucet is not None and not state.objects[faucet].is_on:
        roles.append(_role(f"switch on {faucet}", [S.SwitchOn]))
    alternatives = [tuple(roles)]
    if pred is Predicate.clean:
        alternatives.insert(0, (_role(f"clean {s}", [S.CleanObject]), *x.opener))
    return Need(x.cond, tuple(alternatives), (s, basin) if basin else (s,), 3.0, x.part)


#: the rule for each predicate (a predicate without one needs nothing: ``need_of``)
_RULES: dict[Predicate, Callable[[_Subject], Need]] = {
    Predicate.held: _held, Predicate.inside: _inside, Predicate.sliced: _sliced,
    **dict.fromkeys(_SINGLE, _single),
    Predicate.hot: _heated, Predicate.cooked: _heated, Predicate.cold: _cold,
    Predicate.clean: _watered, Predicate.filled: _watered,
}


def need_of(cond: Condition, state: WorldState, robots: Sequence[str], view: StateView | None = None) -> Need:
    """Roles for ``cond`` from ``state`` (raises the goal compiler's typed errors): the
    facts every rule reads, then the predicate's rule from ``_RULES``. ``view``: a
    :func:`~emboteam.pddl.goal_compiler.shared_view` of ``state``, for a caller asking
    about many conditions of one state (the planner: every condition of the task)."""
    part = compile_condition(cond, state, robots, view=view)
    if part.satisfied:
        return Need(cond, ((),), part=part)
    s = part.subjects[0]
    mass = _mass(state, part, s)
    x = _Subject(cond, state, part, s, mass=mass, lightest=min(_mass(state, part, o) for o in part.subjects),
                 carry=_role(f"carry {s}", [S.PickupObject, S.PutObject], mass=mass), opener=_opener(state, s))
    rule = _RULES.get(cond.predicate)
    return rule(x) if rule is not None else Need(cond, ((),), part=part)


def covers(profiles: Sequence[RobotProfile], need: Need) -> bool:
    """Can these robots together fill every role of some alternative?"""
    return any(all(any(role.covered_by(p) for p in profiles) for role in alt) for alt in need.alternatives)


def _missing(need: Need, role: Role, profiles: Sequence[RobotProfile], names: str) -> Exception:
    """The error for a certain role no robot covers: too heavy for the robots that have
    the skills, else the missing skill (named, so a user knows which robot to add)."""
    skills = sorted({s.value for opt in role.options for s in opt})
    able = [p for p in profiles if any(opt <= p.skills for opt in role.options)]
    if able and role.lift > 0:
        return ImpossibleGoalError(
            f"{need.condition}: every {need.condition.subject} here weighs {role.lift:g} kg "
            f"or more; the robots that can pick up ({', '.join(p.name for p in able)}) lift at "
            f"most {max(p.mass_capacity for p in able):g} kg")
    return MissingSkillError(
        f"{need.condition} needs {' + '.join(skills)}, which no robot of the team ({names}) has",
        skill=skills[0], condition=str(need.condition))


def _held_at_once(needs: Sequence[Need]) -> int:
    """Objects held at once: conditions whose candidates are pairwise disjoint need
    different objects, hence different hands (a greedy packing is a lower bound)."""
    held = sorted((n for n in needs if n.condition.predicate is Predicate.held and n.part is not None),
                  key=lambda n: len(n.part.subjects) if n.part else 0)
    taken: set[str] = set()
    required = 0
    for n in held:
        assert n.part is not None
        pool = set(n.part.subjects)
        if not pool & taken:
            taken |= pool
            required += n.condition.count
    return required


def check_team(needs: Sequence[Need], profiles: Sequence[RobotProfile]) -> None:
    """Reject a goal the team certainly cannot reach, naming the skill and the condition;
    also too many objects to hold for the robots that can pick up."""
    names = ", ".join(p.name for p in profiles)
    for need in needs:
        for role in (r for alt in need.alternatives for r in alt):
            if role.certain and not any(role.covered_by(p) for p in profiles):
                raise _missing(need, role, profiles, names)
    required = _held_at_once(needs)
    hands = sum(1 for p in profiles if p.can(S.PickupObject))
    if required > hands:
        raise ImpossibleGoalError(f"the goal has {required} objects held at once, but only {hands} robot(s) "
                                  f"of the team ({names}) can pick up")


def estimate(state: WorldState, robot: str, needs: Sequence[Need]) -> float:
    """Seconds ``robot`` would be busy with ``needs``: driving along their visits from
    where it stands, plus their manipulation."""
    r = state.robots[robot]
    pos = (r.position[0], r.position[1])  # hashable whatever the caller built (see _drive_seconds)
    total = 0.0
    for need in needs:
        for oid in need.visits:
            anchor = _anchor(state, oid)
            if anchor not in state.objects:
                continue
            o = state.objects[anchor]
            dest = (o.position[0], o.position[2])
            total += _drive_seconds(pos, dest, r.profile.speed, state.floor_plan)
            pos = dest
        total += need.work
    return total


@lru_cache(maxsize=1 << 16)
def _drive_seconds(a: tuple[float, float], b: tuple[float, float], speed: float, floor_plan: str) -> float:
    """:func:`navigation_seconds`, memoised: the allocator estimates every cluster for
    every robot (96 x 32 in the largest sweep cell), the same few hundred drives again and
    again, and the navigation's own caches sit behind several calls."""
    return navigation_seconds(a, b, speed, floor_plan)
