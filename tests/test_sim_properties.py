"""Property tests: random action sequences (random robots, skills and targets, valid or not,
concurrent, with faults) never break the world's structural invariants."""

from __future__ import annotations

import random
import time
from dataclasses import dataclass, field

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from emboteam.sim import Breakdown, FaultConfig, ObjectMove, Simulator
from emboteam.world import (
    Action,
    ActionOutcome,
    ObjectState,
    Skill,
    WorldState,
    load_catalogue,
    load_scene,
    parse_team,
)

SCENES = ("FloorPlan1", "FloorPlan6", "FloorPlan201", "FloorPlan303", "FloorPlan414")
TEAMS = ("1,2", "1,5,26", "23,25,24,1", "7,9", "28,2,2")
HAND_SKILLS = (Skill.PutObject, Skill.ThrowObject, Skill.DropHandObject)

#: the property an object needs for a skill to apply to it: "fitting" steps draw their
#: target among such objects, so random runs reach deep states (things sliced, cooked,
#: carried in containers, shut in fridges) instead of failing at the first check
FITS = {
    Skill.PickupObject: "pickupable", Skill.OpenObject: "openable", Skill.CloseObject: "openable",
    Skill.SwitchOn: "toggleable", Skill.SwitchOff: "toggleable", Skill.SliceObject: "sliceable",
    Skill.BreakObject: "breakable", Skill.CleanObject: "dirtyable", Skill.PushObject: "moveable",
    Skill.PullObject: "moveable",
}


@dataclass
class Step:
    robot: int
    skill: Skill
    target: int
    receptacle: int
    go_first: bool
    use_held: bool
    wait: bool
    fit: bool = True


#: skills weighted towards picking and placing, which build the deepest states
WEIGHTED_SKILLS = [*Skill, *([Skill.PickupObject, Skill.PutObject] * 3), Skill.OpenObject, Skill.SliceObject]

steps = st.builds(
    Step,
    robot=st.integers(0, 3),
    skill=st.sampled_from(WEIGHTED_SKILLS),
    target=st.integers(0, 10_000),
    receptacle=st.integers(0, 10_000),
    go_first=st.integers(0, 9).map(lambda k: k < 8),
    use_held=st.integers(0, 9).map(lambda k: k < 8),
    wait=st.booleans(),
    fit=st.integers(0, 9).map(lambda k: k < 7),
)


@dataclass
class Sealed:
    """What each closed enclosing receptacle held when it was closed: nothing may be
    inside a closed fridge/drawer/box unless it was put there while it was open."""

    contents: dict[str, set[str]] = field(default_factory=dict)

    def start(self, state: WorldState) -> None:
        for rec in _enclosing(state):
            if not rec.is_open:
                self.contents[rec.id] = {d.id for d in state.descendants(rec.id)}

    def observe(self, state: WorldState, outcomes: list[ActionOutcome]) -> None:
        for out in outcomes:
            if out.success and out.action.skill is Skill.CloseObject:
                self.contents[out.action.target] = {d.id for d in state.descendants(out.action.target)}
            elif out.success and out.action.skill is Skill.OpenObject:
                self.contents.pop(out.action.target, None)


def _enclosing(state: WorldState) -> list[ObjectState]:
    must = load_catalogue().must_be_open
    return [o for o in state.objects.values() if o.type in must and o.has("openable")]


def check_invariants(state: WorldState, sealed: Sealed) -> None:
    assert state.invariant_violations() == []
    for o in state.objects.values():
        assert o.parent is None or o.held_by is None, f"{o.id} is in two places"
    for r in state.robots.values():
        held = [o.id for o in state.objects.values() if o.held_by == r.name]
        assert held == ([r.holding] if r.holding else []), f"{r.name} holds {held}"
        if r.holding is not None:
            load = state.objects[r.holding]
            for o in (load, *state.descendants(load.id)):
                assert (o.position[0], o.position[2]) == r.position, f"{o.id} is not with {r.name}"
    for rec in _enclosing(state):
        if rec.is_open:
            continue
        inside = {d.id for d in state.descendants(rec.id)}
        assert inside <= sealed.contents.get(rec.id, set()), \
            f"{inside - sealed.contents.get(rec.id, set())} got into closed {rec.id}"


def _pick(pool: list[str], k: int) -> str:
    return pool[k % len(pool)]


def run_random(floor_plan: str, team_spec: str, seed: int, plan: list[Step], faults: FaultConfig) -> Simulator:
    scene = load_scene(floor_plan)
    team = parse_team(team_spec)
    sim = Simulator(scene, team, seed=seed, faults=faults)
    sealed = Sealed()
    sealed.start(sim.state)
    names = [r.name for r in team]
    cat = load_catalogue()
    wholes = [o.id for o in scene.objects if o.has("sliceable")] or ["Apple_1"]
    for step in plan:
        robot = names[step.robot % len(names)]
        while sim.busy(robot):
            t = sim.next_event_time()
            assert t is not None
            outs = sim.advance(t)
            sealed.observe(sim.state, outs)
            check_invariants(sim.state, sealed)
        state = sim.state
        # targets: every object, pieces that may or may not exist yet, and nonsense
        pool = [*state.objects, f"{_pick(wholes, step.target)}_Slice_1", "Unicorn_1"]
        target = _pick(pool, step.target)
        need = FITS.get(step.skill)
        if step.fit and need is not None:
            fitting = [o for o, s in state.objects.items() if s.has(need) and not s.gone]
            if step.skill is Skill.PickupObject and step.receptacle % 3 == 0:  # a knife, to slice
                fitting = [o for o in fitting if state.objects[o].type in ("Knife", "ButterKnife")] or fitting
            elif step.skill is Skill.PickupObject and step.receptacle % 3 == 1:  # a loaded container
                fitting = [o for o in fitting if state.children(o)] or fitting
            target = _pick(fitting or pool, step.target)
        holding = state.robots[robot].holding
        if step.skill in HAND_SKILLS and holding is not None and step.use_held:
            target = holding
        receptacle = None
        goal = target
        if step.skill is Skill.PutObject:
            recs = [o for o, s in state.objects.items() if s.has("receptacle")] or pool
            if step.fit and target in state.objects:
                allowed = [r for r in recs if cat.can_place(state.objects[target].type, state.objects[r].type)]
                portable = [r for r in allowed if state.objects[r].has("pickupable")]
                recs = (portable if step.receptacle % 2 and portable else allowed) or recs
            receptacle = goal = _pick(recs if step.use_held else pool, step.receptacle)
        elif step.skill is Skill.ThrowObject and step.fit:
            goal = _pick([o for o, s in state.objects.items() if s.type == "GarbageCan"] or pool, step.receptacle)
        if step.go_first and goal in state.objects:
            sim.start(robot, Action(skill=Skill.GoToObject, target=goal))
            while sim.busy(robot):
                t = sim.next_event_time()
                assert t is not None
                outs = sim.advance(t)
                sealed.observe(sim.state, outs)
                check_invariants(sim.state, sealed)
        sim.start(robot, Action(skill=step.skill, target=target, receptacle=receptacle))
        if step.wait:
            t = sim.next_event_time()
            assert t is not None
            outs = sim.advance(t)
            sealed.observe(sim.state, outs)
            check_invariants(sim.state, sealed)
    outs = sim.run_until_idle()
    sealed.observe(sim.state, outs)
    check_invariants(sim.state, sealed)
    return sim


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(floor_plan=st.sampled_from(SCENES), team=st.sampled_from(TEAMS), seed=st.integers(0, 2**16),
       plan=st.lists(steps, min_size=20, max_size=60))
def test_random_sequences_keep_the_invariants(floor_plan: str, team: str, seed: int, plan: list[Step]) -> None:
    run_random(floor_plan, team, seed, plan, FaultConfig())


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(floor_plan=st.sampled_from(SCENES), team=st.sampled_from(TEAMS), seed=st.integers(0, 2**16),
       plan=st.lists(steps, min_size=20, max_size=60), p=st.sampled_from([0.1, 0.3]),
       down_at=st.floats(0, 60), move_at=st.floats(0, 60), move_pick=st.integers(0, 10_000))
def test_faults_keep_the_invariants(floor_plan: str, team: str, seed: int, plan: list[Step], p: float,
                                    down_at: float, move_at: float, move_pick: int) -> None:
    scene = load_scene(floor_plan)
    movable = [o.id for o in scene.objects if o.has("pickupable")]
    faults = FaultConfig(
        action_failure=p, occlusion=p / 2,
        breakdowns=(Breakdown(robot=parse_team(team)[0].name, at=down_at),),
        moves=(ObjectMove(object=_pick(movable, move_pick), at=move_at),),
    )
    run_random(floor_plan, team, seed, plan, faults)


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**16), plan=st.lists(steps, min_size=5, max_size=30))
def test_replaying_a_sequence_is_deterministic(seed: int, plan: list[Step]) -> None:
    faults = FaultConfig.level(0.2)
    a = run_random("FloorPlan1", "1,2", seed, plan, faults)
    b = run_random("FloorPlan1", "1,2", seed, plan, faults)
    assert a.outcomes == b.outcomes and a.events == b.events


def test_thousand_random_actions_run_fast() -> None:
    """settle() runs after every action: a 1000-action run on the largest scene must stay
    cheap (measured about 0.1 s; the bound leaves room for a loaded machine)."""
    rng = random.Random(0)
    plan = [Step(robot=rng.randrange(4), skill=rng.choice(WEIGHTED_SKILLS), target=rng.randrange(10_000),
                 receptacle=rng.randrange(10_000), go_first=rng.random() < 0.8, use_held=rng.random() < 0.8,
                 wait=rng.random() < 0.5, fit=rng.random() < 0.7) for _ in range(1000)]
    largest = "FloorPlan16"  # 90 objects, the most of any floor plan
    assert len(load_scene(largest).objects) == max(len(load_scene(f"FloorPlan{i}").objects) for i in range(1, 31))
    started = time.perf_counter()
    sim = run_random(largest, "1,2,3", 0, plan, FaultConfig())
    elapsed = time.perf_counter() - started
    assert len(sim.outcomes) >= 1000
    assert sum(o.success for o in sim.outcomes) > 300, "the random run must do real work"
    assert elapsed < 10.0, f"1000 random actions took {elapsed:.2f} s"
