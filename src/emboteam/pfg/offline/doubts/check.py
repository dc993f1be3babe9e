"""A candidate reading is checked like the reader's own: every condition names things the
scene has and can take that state (the goal checker), the goal compiler can compile it
(AI2-THOR's placement rules), the team has the skills it needs, and no two of its end
states are opposite states of one object (the reader's own contradiction rule: a doubt
that adds "the light on" to a reading that has it off makes no reading), and no thing the
scene has one of is wanted in two places.

Conditions are checked one at a time and remembered (:class:`FeasibilityCheck`): the
candidates of one instruction share most of their conditions, and the team check is the
costly part, so each condition is checked once per instruction.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

from emboteam.pddl.errors import ImpossibleGoalError
from emboteam.pddl.goal_compiler import StateView, compile_condition, shared_view, slicing_targets
from emboteam.pfg.offline.consistency import opposed
from emboteam.sim.capability import analyse_condition
from emboteam.world.checker import GoalValidationError, validate_goal
from emboteam.world.goals import Condition, Goal, Predicate
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState


class FeasibilityCheck:
    """Whether goals are ones the scene, the placement rules and the team allow; the
    reader's own conditions (``checked``) count as checked."""

    def __init__(self, scene: Scene, state: WorldState, team: Sequence[RobotProfile],
                 checked: Sequence[Condition] = ()) -> None:
        self.scene, self.state, self.team = scene, state, tuple(team)
        self.robots = list(state.robots)
        self.base = tuple(checked)
        self.known: dict[Condition, bool] = dict.fromkeys(checked, True)
        # the wholes the reading cuts (slicing_targets is a union over conditions: the
        # reading's part is computed once)
        self._base_slices: set[str] | None = None
        self._team_known: dict[Condition, bool] = {}
        # one view of the state for all the checks (the state does not change meanwhile)
        self._view: StateView | None = None

    def condition(self, c: Condition) -> bool:
        if c not in self.known:
            self.known[c] = self._check(c)
        return self.known[c]

    def _check(self, c: Condition) -> bool:
        try:
            validate_goal(Goal(conditions=(c,)), self.scene)
            if self._view is None or self._base_slices is None:
                self._view = shared_view(self.state)
                self._base_slices = slicing_targets(list(self.base), self.state, self.robots, self._view)
            slices = self._base_slices | slicing_targets([c], self.state, self.robots, self._view)
            compile_condition(c, self.state, self.robots, slices=slices, narrow=False, view=self._view)
        except (GoalValidationError, ImpossibleGoalError):
            return False
        return True

    def team_can(self, goals: tuple[Condition, ...]) -> bool:
        """Whether the team has the skills for the goals' new conditions (the costly part,
        a few ms a condition: asked only of the candidates that may run or be offered)."""
        return not self.team or all(self._team_can(c) for c in goals if c not in self.base)

    def _team_can(self, c: Condition) -> bool:
        # remembered per condition, like :meth:`condition`: the close candidates share
        # most of their conditions, and the state and team are fixed for this check
        if c not in self._team_known:
            self._team_known[c] = analyse_condition(c, self.state).team_method(self.team) is not None
        return self._team_known[c]

    def __call__(self, goals: tuple[Condition, ...]) -> bool:
        return all(self.condition(c) for c in goals) and consistent(goals) and self.one_place(goals)

    def one_place(self, goals: Sequence[Condition]) -> bool:
        """No thing the scene has one of is wanted in two places at once (a doubt that
        keeps the candle where it is, and another that moves it to the drawer)."""
        places: dict[str, set[tuple[str, ...]]] = {}
        for c in goals:
            if c.predicate is Predicate.inside and c.receptacle is not None and len(c.subject.types) == 1:
                places.setdefault(c.subject.types[0], set()).add(c.receptacle.types or (str(c.receptacle.id),))
        # a type with none yet (slices) or several may be in several places
        return all(len(where) < 2 or len(list(self.state.of_type(t))) != 1 for t, where in places.items())


def consistent(goals: Sequence[Condition]) -> bool:
    """No two end states that exclude each other (on and off, open and closed of one object)."""
    return not any(opposed(a, b) for a, b in itertools.combinations(goals, 2))


def feasible(goals: tuple[Condition, ...], scene: Scene, state: WorldState, team: Sequence[RobotProfile]) -> bool:
    """One goal checked on its own (no reading to share the work with)."""
    check = FeasibilityCheck(scene, state, team)
    return check(goals) and check.team_can(goals)
