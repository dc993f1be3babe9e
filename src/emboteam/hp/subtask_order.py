"""Subtask dependencies (``s2.depends_on = ("s1",)``) as *causal* orderings in the merge.

"Slice the lettuce, then put it in the fridge" asks that the lettuce go into the fridge
after it was sliced, not that the robot putting it there stand still until the slicer
has dropped its knife. For a dependency s1 -> s2 (direct or transitive), a step of s2
waits for s1's *achievers* (for each condition of s1's goal, the step after which it last
became true before s2's steps) only when it

(a) makes one of s2's goal conditions true: s2's goal comes about after s1's ("then");
(b) makes one of s1's goal conditions false: s1's goal must have held before it is
    undone (rinse the lettuce in the sink *before* taking it out to put it on the
    counter, when the rinse is an intermediate, ``final=False`` subtask);
(c) reads something s1's steps produce: that is a causal link, already ordered by the
    merge's read/write analysis (:mod:`emboteam.hp.dependencies`).

Its other steps (driving to the fridge, opening it, fetching a tool) may run while s1 is
still under way. A robot's own steps keep their planned order.

Which conditions a step makes true or false is found by replaying the merged sequence on
the symbolic state and checking every condition involved before and after each step
(``world.checker``, the same check that scores the episode).

A dependency can be made *strict* (every step of s2's planning unit waits for the last
step of each robot in s1's unit: the ordering the merge used before this module); the
planner does that for a dependency whose causal version fails in the simulator.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field

from emboteam.hp.merge import GroundedStep
from emboteam.pfg.taskspec import TaskSpec
from emboteam.sim.rules import apply_action
from emboteam.world.checker import condition_holds
from emboteam.world.goals import Condition
from emboteam.world.state import WorldState


@dataclass(frozen=True)
class Dependency:
    """Subtask ``later`` depends on ``earlier`` (directly or through others); the
    ``*_group`` fields are the planning units their steps carry (``GroundedStep.group``)."""

    earlier: str
    later: str
    earlier_group: str
    later_group: str
    earlier_goal: tuple[Condition, ...]
    later_goal: tuple[Condition, ...]

    def __str__(self) -> str:
        return f"{self.earlier} -> {self.later}"


@dataclass
class DependencyWaits:
    """Per step, the earlier steps (of other robots) its subtask dependencies make it wait
    for, and why (keyed by (producer, consumer) index)."""

    preds: list[set[int]]
    reasons: dict[tuple[int, int], str] = field(default_factory=dict)


@dataclass(frozen=True)
class GoalChange:
    """The conditions (by text) one step makes true and makes false."""

    made_true: frozenset[str] = frozenset()
    made_false: frozenset[str] = frozenset()


def subtask_dependencies(spec: TaskSpec, unit_of: Mapping[str, str]) -> tuple[Dependency, ...]:
    """Every (transitive) dependency between planned subtasks of different units, in
    spec order. A dependency inside one unit needs no ordering: the unit's own plan
    already reaches the goals in a valid order."""
    out: list[Dependency] = []
    for t in spec.subtasks:
        group = unit_of.get(t.id)
        if group is None:
            continue
        for a in ancestors(spec, t.id):
            earlier_group = unit_of.get(a)
            if earlier_group is None or earlier_group == group:
                continue
            out.append(Dependency(earlier=a, later=t.id, earlier_group=earlier_group, later_group=group,
                                  earlier_goal=spec.subtask(a).goal, later_goal=t.goal))
    return tuple(out)


def goal_changes(start: WorldState, steps: Sequence[GroundedStep], conditions: Collection[Condition]
                 ) -> list[GoalChange]:
    """Replay ``steps`` from ``start`` (not modified) and record which of ``conditions``
    each step turns true or false. The steps are the merged sequence, valid when run in
    order (the merge grounded them that way), so every action applies."""
    unique = {str(c): c for c in conditions}
    if not unique:
        return [GoalChange() for _ in steps]
    state = start.copy()
    holds = {k: condition_holds(c, state) for k, c in unique.items()}
    out: list[GoalChange] = []
    for s in steps:
        apply_action(state, s.robot, s.action)
        now = {k: condition_holds(c, state) for k, c in unique.items()}
        out.append(GoalChange(made_true=frozenset(k for k in unique if now[k] and not holds[k]),
                              made_false=frozenset(k for k in unique if holds[k] and not now[k])))
        holds = now
    return out


def dependency_waits(start: WorldState, steps: Sequence[GroundedStep], deps: Sequence[Dependency],
                     strict: Collection[Dependency] = ()) -> DependencyWaits:
    """The waits the subtask dependencies add to the merge: causal ones (rules (a) and
    (b) of the module docstring) for each dependency, strict ones for those in
    ``strict``. Waits between steps of one robot are left out (its order holds them)."""
    waits = DependencyWaits(preds=[set() for _ in steps])
    relaxed = [d for d in deps if d not in strict]
    if relaxed:
        _causal(start, steps, relaxed, waits)
    for d in deps:
        if d in strict:
            _strict(steps, d, waits)
    return waits


def _causal(start: WorldState, steps: Sequence[GroundedStep], deps: Sequence[Dependency],
            waits: DependencyWaits) -> None:
    changes = goal_changes(start, steps, [c for d in deps for c in (*d.earlier_goal, *d.later_goal)])
    first: dict[str, int] = {}
    for j, s in enumerate(steps):
        first.setdefault(s.group, j)
    for d in deps:
        begin = first.get(d.later_group)
        if begin is None:
            continue  # the later subtask had nothing to do
        earlier = list(dict.fromkeys(str(c) for c in d.earlier_goal))  # in goal order: stable reasons
        later = list(dict.fromkeys(str(c) for c in d.later_goal))
        achievers: dict[int, str] = {}
        for key in earlier:  # the last step before s2's that made each condition true
            i = next((i for i in range(begin - 1, -1, -1) if key in changes[i].made_true), None)
            if i is not None:
                achievers[i] = key if i not in achievers else f"{achievers[i]}, {key}"
        if not achievers:
            continue  # s1's goal held without any step making it so: nothing to wait for
        for j in range(begin, len(steps)):
            s = steps[j]
            if s.group != d.later_group:
                continue
            achieves = [k for k in later if k in changes[j].made_true]
            undoes = [k for k in earlier if k in changes[j].made_false]
            if not achieves and not undoes:
                continue
            why = (f"{d.later}'s {', '.join(achieves)}" if achieves
                   else f"{d.later} undoes {', '.join(undoes)}")
            for i, conds in achievers.items():
                if steps[i].robot == s.robot:
                    continue
                waits.preds[j].add(i)
                waits.reasons.setdefault((i, j), f"{why} after {d.earlier}'s {conds}")


def _strict(steps: Sequence[GroundedStep], d: Dependency, waits: DependencyWaits) -> None:
    """Every step of the later unit waits for the last step, per robot, of the earlier
    unit (the ordering before causal dependencies; kept as the fall-back)."""
    last: dict[str, int] = {}
    for i, s in enumerate(steps):
        if s.group == d.earlier_group:
            last[s.robot] = i
    for j, s in enumerate(steps):
        if s.group != d.later_group:
            continue
        for robot, i in last.items():
            if robot != s.robot and i < j:
                waits.preds[j].add(i)
                waits.reasons.setdefault((i, j), f"subtask {d.later} depends on {d.earlier} (strict)")


def ancestors(spec: TaskSpec, sid: str) -> list[str]:
    """Transitive dependencies of a subtask, in spec order."""
    seen: set[str] = set()
    frontier = list(spec.subtask(sid).depends_on)
    while frontier:
        d = frontier.pop()
        if d not in seen:
            seen.add(d)
            frontier += spec.subtask(d).depends_on
    return [t.id for t in spec.subtasks if t.id in seen]
