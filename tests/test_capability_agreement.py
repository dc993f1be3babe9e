"""The capability model agrees with the simulator, and its views agree with the model.

In the style of ``test_pddl_agreement``: for every predicate and every appliance, the
conditions below are analysed by ``emboteam.sim.capability`` and *every* method it
proposes is executed in the simulator (steps bound to robots, a GoToObject before each);
the condition must then hold. The planner's view (``hp/requirements.py``) must agree with
the model: a role it calls certain is needed by every method the model proposes, and the
appliance it plans a visit to is one some method uses. The appliance lists themselves
agree with the catalogue's AI2-THOR property flags.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from emboteam.errors import EmboTeamError
from emboteam.hp.requirements import need_of
from emboteam.sim.capability import Method, Role, analyse_condition
from emboteam.sim.simulator import Simulator
from emboteam.world.actions import Skill
from emboteam.world.catalogue import (
    BREWERS,
    BURNERS,
    COLD_SOURCES,
    HEATERS,
    INTERLOCKED,
    WATER_SOURCES,
    load_catalogue,
)
from emboteam.world.checker import check_condition
from emboteam.world.goals import Condition, ObjectRef, Predicate
from emboteam.world.robots import RobotProfile, parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import ObjectState, WorldState
from witness import WitnessFailed, run_method

#: two kitchens (every kitchen appliance), a living room, a bathroom with a shower head
SCENES = ("FloorPlan1", "FloorPlan6", "FloorPlan201", "FloorPlan401")
#: two robots with every skill (no SMART-LLM profile has CleanObject), lifting 100 kg:
#: the rules, not the team, decide
TEAM = tuple(p.model_copy(update={"skills": frozenset(Skill)}) for p in parse_team("1,2"))
#: candidate subjects per (scene, predicate): enough to reach every appliance
PER_PREDICATE = 6
#: conditions no action of the simulator makes true (it has no way to dirty an object)
NO_METHOD = {Predicate.dirty}
APPLIANCES = HEATERS | BREWERS | COLD_SOURCES | WATER_SOURCES | INTERLOCKED | BURNERS


def _state(fp: str, cond: Condition | None = None) -> tuple[WorldState, tuple[RobotProfile, ...]]:
    """The scene's initial state; for ``clean(X)``, X made dirty first (nothing starts dirty)."""
    team = TEAM
    state = WorldState.from_scene(load_scene(fp), team)
    if cond is not None and cond.predicate is Predicate.clean and cond.subject.id in state.objects:
        state.objects[cond.subject.id].is_dirty = True
    return state, team


def _subjects(state: WorldState, pred: Predicate) -> list[ObjectState]:
    """Objects a condition of ``pred`` can be about, appliance-friendly types first."""
    cat = load_catalogue()
    need = {Predicate.sliced: "sliceable", Predicate.broken: "breakable", Predicate.switched_on: "toggleable",
            Predicate.switched_off: "toggleable", Predicate.open: "openable", Predicate.closed: "openable",
            Predicate.cooked: "cookable", Predicate.filled: "canFillWithLiquid", Predicate.clean: "dirtyable",
            Predicate.dirty: "dirtyable"}.get(pred, "pickupable")
    objs = [o for o in state.objects.values() if not o.gone and o.source is None and o.has(need)]

    def appliances_taking(o: ObjectState) -> int:
        """How many appliances take it, or the pieces it cuts into (bread slices: the toaster)."""
        piece = cat.slice_product(o.type)
        types = {o.type, piece[0]} if piece else {o.type}
        return -sum(1 for a in state.objects.values()
                    if a.type in APPLIANCES and any(cat.can_place(t, a.type) for t in types))
    return sorted(objs, key=lambda o: (appliances_taking(o), o.mass, o.id))[:PER_PREDICATE]


def _conditions(state: WorldState) -> Iterator[Condition]:
    cat = load_catalogue()
    for pred in Predicate:
        if pred is Predicate.inside:
            continue
        for o in _subjects(state, pred):
            liquids: tuple[str | None, ...] = ("water", "coffee") if pred is Predicate.filled else (None,)
            for liquid in liquids:
                yield Condition(predicate=pred, subject=ObjectRef(id=o.id), liquid=liquid)
    # inside: every receptacle type of the scene (appliances included), the lightest object it takes
    seen: set[str] = set()
    movable = sorted((o for o in state.objects.values() if o.has("pickupable") and not o.gone),
                     key=lambda o: (o.mass, o.id))
    for r in sorted(state.objects.values(), key=lambda o: o.id):
        if not r.has("receptacle") or r.type in seen or r.type == "Floor":
            continue
        o = next((m for m in movable if m.id != r.id and cat.can_place(m.type, r.type)
                  and not state.is_within(m.id, r.id) and not state.is_within(r.id, m.id)), None)
        if o is not None:
            seen.add(r.type)
            yield Condition(predicate=Predicate.inside, subject=ObjectRef(id=o.id), receptacle=ObjectRef(id=r.id))


def _cases() -> list[tuple[str, Condition]]:
    out = []
    for fp in SCENES:
        state, _ = _state(fp)
        out += [(fp, c) for c in _conditions(state) if not check_condition(c, _state(fp, c)[0]).holds]
    return out


CASES = _cases()


def _used_ids(method: Method) -> set[str]:
    ids = {s.near for s in method.steps} | {s.action.target for s in method.steps}
    ids |= {s.action.receptacle for s in method.steps if s.action.receptacle}
    return ids | set(method.label.split())


def _run(fp: str, cond: Condition, method: Method) -> Simulator:
    state, team = _state(fp, cond)
    sim = Simulator(load_scene(fp), team, state=state)
    run_method(sim, method, team)
    return sim


@pytest.mark.parametrize(("fp", "cond"), CASES, ids=[f"{fp}:{c}" for fp, c in CASES])
def test_every_proposed_method_makes_the_condition_true_in_the_simulator(fp: str, cond: Condition) -> None:
    state, _ = _state(fp, cond)
    analysis = analyse_condition(cond, state)
    if cond.predicate in NO_METHOD:
        assert not analysis.methods, f"{cond}: the simulator has no action for it"
        return
    for method in analysis.methods:
        try:
            sim = _run(fp, cond, method)
        except WitnessFailed as exc:
            pytest.fail(f"{cond}: {method} does not run: {exc}")
        assert check_condition(cond, sim.state).holds, f"{cond}: {method} ran but it does not hold"
        assert sim.state.invariant_violations() == []


def _implied(role: Role, method: Method) -> bool:
    """A role of the planner's view that ``method`` needs too: some robot of the method has
    the skills of one of its options and lifts at least as much."""
    return any(any(opt <= q.skills for opt in role.options) and q.lift >= role.lift for q in method.roles)


@pytest.mark.parametrize(("fp", "cond"), CASES, ids=[f"{fp}:{c}" for fp, c in CASES])
def test_the_planners_view_agrees_with_the_model(fp: str, cond: Condition) -> None:
    state, team = _state(fp, cond)
    methods = [m for m in analyse_condition(cond, state).methods if m.steps]
    try:
        need = need_of(cond, state, [p.name for p in team])
    except EmboTeamError:
        assert not methods, f"{cond}: the planner's view rejects what the model can do: {methods[0]}"
        return
    if not methods:
        return
    for alt in need.alternatives:
        for role in alt:
            if not role.certain:
                continue
            missed = [m for m in methods if not _implied(role, m)]
            if missed and all(_cuts(m) for m in missed):
                # open (docs/architecture.md): the goal compiler the planner's view reads
                # (pddl/goal_compiler.py) does not count the pieces of an object named by id;
                # the checker and the model do, so a team that could move a slice is rejected
                pytest.xfail(f"{cond}: {role.name} is certain only without pieces: {missed[0]}")
            assert not missed, f"{cond}: {role.name} is not certain: {missed[0]} does without it"
    appliances = [v for v in need.visits if v in state.objects and state.objects[v].type in APPLIANCES]
    for appliance in appliances:
        assert any(appliance in _used_ids(m) for m in methods), \
            f"{cond}: the planner plans a visit to {appliance}, no method of the model uses it"


def _cuts(method: Method) -> bool:
    return any(s.action.skill in (Skill.SliceObject, Skill.BreakObject) for s in method.steps)


def test_every_predicate_and_every_appliance_is_exercised() -> None:
    predicates = {c.predicate for _, c in CASES}
    assert predicates == set(Predicate)
    used: set[str] = set()
    for fp, cond in CASES:
        state, _ = _state(fp, cond)
        for m in analyse_condition(cond, state).methods:
            used |= {state.objects[i].type for i in _used_ids(m) if i in state.objects}
    assert used >= APPLIANCES, sorted(APPLIANCES - used)


def test_the_appliance_lists_agree_with_ai2thor_flags() -> None:
    cat = load_catalogue()
    flagged_heat = {t for t in cat.types if cat.type(t).has("isHeatSource")}
    flagged_cold = {t for t in cat.types if cat.type(t).has("isColdSource")}
    assert flagged_heat == HEATERS | BREWERS
    assert flagged_cold == COLD_SOURCES
    assert BURNERS <= HEATERS and INTERLOCKED <= HEATERS and not HEATERS & BREWERS
    assert all(t in cat.types for t in WATER_SOURCES)


def test_one_role_concept() -> None:
    """Planner roles and solvability roles are one class: no module defines another."""
    import ast
    from pathlib import Path

    import emboteam

    root = Path(emboteam.__file__).resolve().parent
    defining = sorted(str(p.relative_to(root)) for p in root.rglob("*.py")
                      if any(isinstance(n, ast.ClassDef) and n.name == "Role" for n in ast.walk(ast.parse(p.read_text()))))
    assert defining == ["sim/capability.py"]


def test_a_closed_toilet_does_not_hide_what_stands_on_it() -> None:
    # as in the simulator: only what things go *in* hides them. The importer flagged a
    # team without OpenObject as unable to move a spray bottle off a toilet (blind sets
    # 15 and 16 hit it), although the oracle solves the task with that team
    state = WorldState.from_scene(load_scene("FloorPlan420"), parse_team("13,25"))
    bottle = next(o for o in state.objects.values() if o.type == "SprayBottle")
    assert state.objects[state.ancestors(bottle.id)[0]].type == "Toilet"
    analysis = analyse_condition(Condition.parse("inside(SprayBottle, SideTable)"), state)
    assert analysis.team_method(parse_team("13,25")) is not None
    assert all(s.action.skill is not Skill.OpenObject for m in analysis.methods for s in m.steps
               if state.objects.get(s.action.target) is not None and state.objects[s.action.target].type == "Toilet")
