"""What the compiler needs to know about each plan step, worked out once from the merged
plan: the sync flags it waits for, whether it signals one, the spots it holds and
releases, the literals its Pre and Post conditions check, and which recovery subtrees it
gets. Pure data, shared by the py_trees compiler and the BehaviorTree.CPP exporter so both
describe the same tree.
"""

from __future__ import annotations

import graphlib
import itertools
from collections.abc import Mapping
from dataclasses import dataclass

from emboteam.btc.errors import PlanCompileError
from emboteam.btc.keys import flag_key, ident
from emboteam.btc.recovery import Strategy, strategies_for
from emboteam.btc.spots import lock_plan, predicted_spots
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.pddl import vocabulary
from emboteam.pddl.literal import Literal
from emboteam.world.state import WorldState


@dataclass(frozen=True)
class StepBlueprint:
    step: PlanStep
    #: other robots' steps that must have ended (and been verified) first
    waits: tuple[str, ...]
    #: some other robot waits for this step: write its done flag when it succeeds
    signals: bool
    #: spots the step must hold while it runs (sorted: ordered acquisition)
    holds: tuple[str, ...]
    #: spots released after the step (the end of its robot's run at those spots)
    releases: tuple[str, ...]
    #: literals Pre checks: the plan's preconditions minus those the step itself negates
    pre: tuple[Literal, ...]
    #: literals Post checks: the observable effects
    post: tuple[Literal, ...]
    strategies: tuple[Strategy, ...]

    @property
    def id(self) -> str:
        return self.step.id

    @property
    def robot(self) -> str:
        return self.step.robot


@dataclass(frozen=True)
class PlanBlueprint:
    plan: MergedPlan
    steps: Mapping[str, StepBlueprint]

    def for_robot(self, robot: str) -> list[StepBlueprint]:
        return [self.steps[s.id] for s in self.plan.for_robot(robot)]

    def producers(self) -> set[str]:
        return {s.id for s in self.steps.values() if s.signals}


def _complement(lit: Literal) -> Literal:
    return lit.model_copy(update={"positive": not lit.positive})


def checked_pre(step: PlanStep) -> tuple[Literal, ...]:
    """The preconditions worth checking before the core action.

    A precondition whose complement is one of the step's own effects (``(not (is-open
    Fridge_1))`` for OpenObject) only says the action would change something; when it is
    already false the effect already holds, and the core action's "already open" outcome
    is accepted by Post instead of being treated as a broken precondition.
    """
    effects = set(step.post)
    return tuple(lit for lit in step.pre if _complement(lit) not in effects)


def observed_post(step: PlanStep, robots: frozenset[str] = frozenset()) -> tuple[Literal, ...]:
    """The effects Post checks: the observable ones (``vocabulary.observable``) that do
    not name another robot of the team. Where another robot stands (a slice appears "at"
    whoever was next to the whole) is predicted by a sequential replay of the plan;
    under concurrent execution that robot may have moved on, and it is not this step's
    doing anyway."""
    others = robots - {step.robot}
    return tuple(lit for lit in step.post if vocabulary.observable(lit) and not others.intersection(lit.args))


def cross_robot_waits(plan: MergedPlan) -> dict[str, tuple[str, ...]]:
    """Cross-robot producers of each step, from ``after`` and ``sync`` together; a robot's
    own earlier steps are ordered by its sequence already."""
    known = {s.id: s for s in plan.steps}
    waits: dict[str, list[str]] = {s.id: [] for s in plan.steps}
    pairs = [(p, s.id) for s in plan.steps for p in s.after]
    pairs += [(sp.producer, sp.consumer) for sp in plan.sync]
    for producer, consumer in pairs:
        for sid in (producer, consumer):
            if sid not in known:
                raise PlanCompileError(f"the plan's dependency {producer} -> {consumer} names "
                                       f"unknown step {sid!r}")
        if known[producer].robot == known[consumer].robot:
            continue
        if producer not in waits[consumer]:
            waits[consumer].append(producer)
    return {k: tuple(v) for k, v in waits.items()}


def _check_acyclic(plan: MergedPlan, waits: Mapping[str, tuple[str, ...]]) -> None:
    """Each robot's order plus the cross-robot waits must form a DAG, or the tree would
    wait forever."""
    before: dict[str, set[str]] = {s.id: set() for s in plan.steps}
    for robot in plan.robots:
        for a, b in itertools.pairwise(plan.for_robot(robot)):
            before[b.id].add(a.id)
    for consumer, producers in waits.items():
        before[consumer].update(producers)
    try:
        graphlib.TopologicalSorter(before).prepare()
    except graphlib.CycleError as exc:
        cycle = exc.args[1]
        raise PlanCompileError(f"the plan's dependencies form a cycle through {', '.join(cycle[:6])}") from None


def _check_plan(plan: MergedPlan, state: WorldState | None) -> None:
    ids = [s.id for s in plan.steps]
    if len(ids) != len(set(ids)):
        dup = sorted({i for i in ids if ids.count(i) > 1})
        raise PlanCompileError(f"duplicate step ids {dup}")
    keys = [flag_key(i) for i in ids]
    if len(keys) != len(set(keys)):
        raise PlanCompileError("two step ids differ only in punctuation: their blackboard "
                               "flags would collide")
    robots = set(plan.robots)
    idents = [ident(r) for r in plan.robots]
    if len(idents) != len(set(idents)):
        raise PlanCompileError(f"robot names {sorted(plan.robots)} collide as identifiers")
    for s in plan.steps:
        if s.robot not in robots:
            raise PlanCompileError(f"step {s.id} belongs to {s.robot}, who is not in the plan's "
                                   f"robots {sorted(robots)}")
        for lit in (*s.pre, *s.post):
            known = (lit.predicate in vocabulary.FLUENTS or lit.predicate in vocabulary.STATICS
                     or lit.predicate in vocabulary.CAPABILITIES.values())
            if not known:
                raise PlanCompileError(f"step {s.id} uses unknown PDDL predicate {lit.predicate!r}")
    if state is not None:
        missing = sorted(r for r in robots if r not in state.robots)
        if missing:
            raise PlanCompileError(f"the plan's robots {missing} are not in the team")


def blueprint(plan: MergedPlan, state: WorldState | None = None) -> PlanBlueprint:
    """Work out every step's blueprint; ``state`` (the world when execution starts) lets
    the lock plan predict interaction spots for steps the planner gave no resources."""
    _check_plan(plan, state)
    waits = cross_robot_waits(plan)
    _check_acyclic(plan, waits)
    producers = {p for ps in waits.values() for p in ps}
    locks = lock_plan(plan, predicted_spots(plan, state), waits)
    robots = frozenset(plan.robots)
    out: dict[str, StepBlueprint] = {}
    for s in plan.steps:
        holds = locks.holds.get(s.id, ())
        out[s.id] = StepBlueprint(
            step=s, waits=waits[s.id], signals=s.id in producers, holds=holds,
            releases=locks.releases.get(s.id, ()), pre=checked_pre(s), post=observed_post(s, robots),
            strategies=strategies_for(s.action.skill, waits=bool(waits[s.id]), holds=bool(holds)),
        )
    return PlanBlueprint(plan=plan, steps=out)
