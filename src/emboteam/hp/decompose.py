"""A bare goal -> subtasks, for replanning and generated tasks.

Conditions that may be satisfied by a common object (``sliced(Apple)`` and
``inside(Apple, Fridge)``: cutting the apple changes what must go in the fridge) stay in
one subtask; the rest become independent subtasks the allocator spreads over the team.
"""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.pddl.goal_compiler import compile_condition, shared_view, slicing_targets
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.goals import Condition, Goal, Predicate
from emboteam.world.state import WorldState


def group_indices(conditions: Sequence[Condition], state: WorldState, robots: Sequence[str]) -> list[list[int]]:
    """Indices of conditions grouped by shared candidate objects (union-find), in order."""
    view = shared_view(state)  # the state does not change here: one view for every condition
    slices = slicing_targets(conditions, state, robots, view)
    parent = list(range(len(conditions)))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    def union(i: int, j: int) -> None:
        parent[find(i)] = find(j)

    # subjects, movable receptacles or vessels named (``inside(Egg_1, Pan_1)``: the plan
    # may move the pan too; ``cold(Pan_1)`` carries it away with the egg), and subjects of
    # open/closed, which link only to other subjects (``closed(Box)`` does not move the box
    # things go into)
    subj: dict[str, int] = {}
    place: dict[str, int] = {}
    doors: dict[str, int] = {}

    def link(i: int, anchor: str, among: Sequence[dict[str, int]], mine: dict[str, int]) -> None:
        for d in among:
            if anchor in d:
                union(i, d[anchor])
        mine.setdefault(anchor, i)

    for i, cond in enumerate(conditions):
        part = compile_condition(cond, state, robots, slices=slices, view=view)
        door = cond.predicate in (Predicate.open, Predicate.closed)
        for oid in part.subjects:
            anchor = oid.split("_Slice_")[0]
            link(i, anchor, (subj, doors) if door else (subj, place, doors), doors if door else subj)
        movable = [p for p in (*part.places, *part.vessels) if p in state.objects and state.objects[p].has("pickupable")]
        for p in movable if len(part.places) <= 2 else [v for v in movable if v in part.vessels]:
            link(i, p, (subj, place), place)
    groups: dict[int, list[int]] = {}
    for i in range(len(conditions)):
        groups.setdefault(find(i), []).append(i)
    return list(groups.values())


def group_conditions(conditions: Sequence[Condition], state: WorldState, robots: Sequence[str]
                     ) -> list[list[Condition]]:
    """Conditions grouped by shared candidate objects, in goal order."""
    return [[conditions[i] for i in g] for g in group_indices(conditions, state, robots)]


def decompose_goal(goal: Goal, state: WorldState, *, instruction: str = "") -> TaskSpec:
    """One subtask per group of related conditions, no robot, no dependencies."""
    robots = [r for r, rs in state.robots.items() if not rs.down]
    groups = group_conditions(goal.conditions, state, robots)
    subtasks = tuple(
        Subtask(id=f"g{i}", description=" & ".join(str(c) for c in conds), goal=tuple(conds))
        for i, conds in enumerate(groups, 1))
    return TaskSpec(instruction=instruction or str(goal), subtasks=subtasks)
