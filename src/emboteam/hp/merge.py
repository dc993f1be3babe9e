"""Per-subtask (or joint) action sequences -> one partially ordered multi-robot plan.

The input is a sequence that is valid when run step by step (subtask plans in the order
they were planned, each from the state its predecessors leave, or Fast Downward's joint
plan). :func:`ground_sequence` replays it on the symbolic state, grounding every step's
PDDL preconditions/effects and read/write footprint; :func:`order` then keeps only the
orderings that matter:

- ``formal``: a step waits for another robot's step when they race on a state variable
  (causal links, threats and write conflicts, :mod:`emboteam.hp.dependencies`), and for
  what its subtask dependencies ask: by default every step of the subtasks its subtask
  depends on; the planner passes the causal version instead
  (:mod:`emboteam.hp.subtask_order`: only the steps that reach the subtask's goal or undo
  its dependency's goal wait for the dependency). Redundant (transitively implied) waits are dropped, so each
  remaining one is a sync point;
- ``concatenate``: only the subtask dependencies (the paper's no-HP ablation);
- ``sequential``: every step waits for the one before it (one robot at a time: the
  always-valid last resort).

Interaction spots (``WorldState.spot_of``) are resources, not orderings: two robots may
use the fridge in either order, one at a time.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass
from typing import Literal as TypingLiteral

from emboteam.hp.dependencies import Footprint, footprint
from emboteam.hp.plan import MergedPlan, PlanStep, SyncPoint
from emboteam.pddl import vocabulary
from emboteam.pddl.domain import DomainError, Universe, ground_action
from emboteam.pddl.literal import Literal
from emboteam.sim.durations import action_seconds, navigation_seconds
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.actions import Action, Skill
from emboteam.world.state import WorldState

MergeMode = TypingLiteral["formal", "concatenate", "sequential"]


@dataclass(frozen=True)
class SeqStep:
    """One step of a sequential plan, before merging; ``group`` is the planning unit it
    came from (subtask dependencies are enforced between units)."""

    robot: str
    action: Action
    subtask: str
    group: str = ""


@dataclass(frozen=True)
class GroundedStep:
    robot: str
    action: Action
    subtask: str
    group: str
    pre: tuple[Literal, ...]
    post: tuple[Literal, ...]
    footprint: Footprint
    spot: str | None
    seconds: float


class StepFailure(Exception):
    """A step of a sequence cannot run where it stands (not a user error: the planner
    reacts by replanning or falling back)."""

    def __init__(self, index: int, step: SeqStep, why: str) -> None:
        super().__init__(f"step {index + 1} {step.robot}: {step.action}: {why}")
        self.index = index
        self.step = step
        self.why = why


def nominal_seconds(state: WorldState, robot: str, action: Action) -> float:
    """How long the step takes from ``state`` (navigation from where the robot stands)."""
    if action.skill is Skill.GoToObject:
        r = state.robots[robot]
        o = state.objects[action.target]
        dest = state.robots[o.held_by].position if o.held_by else (o.position[0], o.position[2])
        return navigation_seconds(r.position, dest, r.profile.speed, state.floor_plan)
    return action_seconds(action.skill)


def advance(state: WorldState, step: SeqStep, index: int = 0, *, strict: bool = True,
            universe: Universe | None = None) -> GroundedStep:
    """Ground one step on ``state`` and apply it (in place). With ``strict``, every PDDL
    precondition must hold too, not only the simulator's rule: the behavior tree checks
    them before acting. ``universe`` (made for an earlier state of the same episode)
    saves recomputing static facts."""
    failure = check_action(state, step.robot, step.action)
    if failure is not None:
        raise StepFailure(index, step, f"{failure.reason}: {failure.message}")
    try:
        g = ground_action(step.robot, step.action, state,
                          universe=universe.at(state) if universe is not None else None)
    except DomainError as exc:
        raise StepFailure(index, step, str(exc)) from None
    if strict:
        unmet = [str(lit) for lit in g.pre if not vocabulary.evaluate(lit, state)]
        if unmet:
            raise StepFailure(index, step, f"preconditions {', '.join(unmet)} do not hold")
    fp = footprint(step.robot, g, state)
    spot = None if step.action.skill is Skill.GoToObject else state.spot_of(
        step.action.receptacle or step.action.target)
    seconds = nominal_seconds(state, step.robot, step.action)
    apply_action(state, step.robot, step.action)
    return GroundedStep(step.robot, step.action, step.subtask, step.group or step.subtask, g.pre, g.post, fp, spot, seconds)


def ground_sequence(state: WorldState, steps: Sequence[SeqStep], *, strict: bool = True
                    ) -> tuple[list[GroundedStep], WorldState]:
    """Replay ``steps`` on a copy of ``state``; the grounded steps and the final state.
    Raises :class:`StepFailure` at the first step that cannot run."""
    s = state.copy()
    universe = Universe(s)
    return [advance(s, step, i, strict=strict, universe=universe) for i, step in enumerate(steps)], s


def _conflict_preds(steps: Sequence[GroundedStep]) -> list[set[int]]:
    """For each step, the earlier steps of other robots it races with (enough of them
    that the transitive closure covers every racing pair: per variable, the last writer,
    and the readers and updaters since)."""
    last_writer: dict[str, int] = {}
    readers: dict[str, list[int]] = {}
    updaters: dict[str, list[int]] = {}
    preds: list[set[int]] = []
    for j, s in enumerate(steps):
        fp = s.footprint
        cand: set[int] = set()
        for v in fp.reads | fp.writes | fp.updates:
            if v in last_writer:
                cand.add(last_writer[v])
        for v in fp.reads | fp.writes:
            cand.update(updaters.get(v, ()))
        for v in fp.writes | fp.updates:
            cand.update(readers.get(v, ()))
        for v in fp.reads:
            readers.setdefault(v, []).append(j)
        for v in fp.updates:
            updaters.setdefault(v, []).append(j)
        for v in fp.writes:
            last_writer[v] = j
            readers[v] = []
            updaters[v] = []
        preds.append({i for i in cand if steps[i].robot != s.robot})
    return preds


def _dependency_preds(steps: Sequence[GroundedStep], depends_on: Mapping[str, Sequence[str]]
                      ) -> list[set[int]]:
    """Each step waits for the last step, per robot, of every group its group depends on
    (``depends_on`` maps a group to the groups that must finish first)."""
    last: dict[str, dict[str, int]] = {}
    for i, s in enumerate(steps):
        last.setdefault(s.group, {})[s.robot] = i
    preds: list[set[int]] = [set() for _ in steps]
    for j, s in enumerate(steps):
        for dep in depends_on.get(s.group, ()):
            for robot, i in last.get(dep, {}).items():
                if robot != s.robot and i < j:
                    preds[j].add(i)
    return preds


def _reduce(steps: Sequence[GroundedStep], preds: list[set[int]]) -> list[list[int]]:
    """Drop waits implied by others (or by the robot's own order): transitive reduction
    over the DAG of robot chains plus cross-robot waits, with bitsets of ancestors."""
    prev: dict[str, int] = {}
    anc = [0] * len(steps)
    kept: list[list[int]] = []
    for j, s in enumerate(steps):
        direct = set(preds[j])
        if s.robot in prev:
            direct.add(prev[s.robot])
        reach = 0
        for p in direct:
            reach |= anc[p] | (1 << p)
        anc[j] = reach
        keep = [i for i in sorted(preds[j])
                if not any((anc[p] >> i) & 1 for p in direct if p != i)]
        kept.append(keep)
        prev[s.robot] = j
    return kept


def order(steps: Sequence[GroundedStep], depends_on: Mapping[str, Sequence[str]],
          mode: MergeMode = "formal", *, dependency_waits: Sequence[Collection[int]] | None = None
          ) -> list[list[int]]:
    """Cross-robot waits of each step (indices of earlier steps), reduced.

    ``dependency_waits`` (per step, earlier steps to wait for) replaces the whole-group
    ordering ``depends_on`` implies, e.g. with :func:`emboteam.hp.subtask_order.dependency_waits`.
    """
    if mode == "sequential":
        return [[j - 1] if j and steps[j - 1].robot != s.robot else [] for j, s in enumerate(steps)]
    if dependency_waits is None:
        preds = _dependency_preds(steps, depends_on)
    else:
        preds = [{i for i in w if i < j and steps[i].robot != steps[j].robot}
                 for j, w in enumerate(dependency_waits)]
    if mode == "formal":
        for j, extra in enumerate(_conflict_preds(steps)):
            preds[j] |= extra
    return _reduce(steps, preds)


def _reason(a: GroundedStep, b: GroundedStep, depends_on: Mapping[str, Sequence[str]],
            dependency: str | None = None) -> str:
    fa, fb = a.footprint, b.footprint
    causal = sorted((fa.writes | fa.updates) & fb.reads)
    if causal:
        return "needs " + ", ".join(causal[:4])
    clash = sorted((fa.writes & (fb.writes | fb.updates)) | (fa.updates & fb.writes))
    if clash:
        return "after its change to " + ", ".join(clash[:4])
    threat = sorted(fa.reads & (fb.writes | fb.updates))
    if threat:
        return "must not change " + ", ".join(threat[:4]) + " before it is used"
    if dependency:
        return dependency
    if a.group in depends_on.get(b.group, ()):
        return f"subtask {b.subtask} depends on {a.subtask}"
    return "ordered"


def assemble(steps: Sequence[GroundedStep], waits: Sequence[Sequence[int]], robots: Sequence[str],
             depends_on: Mapping[str, Sequence[str]], reasons: Mapping[tuple[int, int], str] | None = None
             ) -> MergedPlan:
    """The MergedPlan (times and statistics left for the caller to fill). ``reasons``
    names why a (producer, consumer) wait exists when it is no race on a state variable
    (a subtask dependency)."""
    reasons = reasons or {}
    counters: dict[str, int] = {}
    ids: list[str] = []
    for s in steps:
        counters[s.robot] = counters.get(s.robot, 0) + 1
        ids.append(f"{s.robot}.{counters[s.robot]}")
    out: list[PlanStep] = []
    sync: list[SyncPoint] = []
    for j, s in enumerate(steps):
        after = tuple(ids[i] for i in waits[j])
        for i in waits[j]:
            sync.append(SyncPoint(producer=ids[i], consumer=ids[j],
                                  reason=_reason(steps[i], s, depends_on, reasons.get((i, j)))))
        out.append(PlanStep(id=ids[j], robot=s.robot, action=s.action, subtask=s.subtask, after=after,
                            resources=(s.spot,) if s.spot else (), pre=s.pre, post=s.post))
    return MergedPlan(robots=tuple(robots), steps=tuple(out), sync=tuple(sync))
