"""Visit merging: do a step on the robot's other visit to the same object.

lama-first counts actions, not seconds, and often drives to an object only to do one
thing there and comes back later: to cool a pan with the fridge closed it drives to the
fridge, opens it, drives to the pan, picks it up and drives back to put it in, where
picking the pan up first and opening the fridge on arrival saves two drives (11 s of
29 s in FloorPlan1). Action elimination (:mod:`emboteam.hp.eliminate`) cannot see this:
every step is needed, only in another place in the plan.

For each step a robot drove to do (a ``GoToObject`` of its object just before it), the
step is moved to that robot's next visit to the same object (just before its next step
there), or to its previous visit (just after its last step there); then the drives that
lead straight to another drive are dropped (and, once a move is kept, whatever else
action elimination finds idle). The result is replayed with the simulator's rules from the
plan's start, must reach every goal the original reaches, leave every robot's hand as
the original does, cost no robot more nominal seconds and cost the team fewer; the first
move that does is kept and the search starts again (at most :data:`MAX_MOVES`). The
planner then replays the unit with every PDDL precondition, as any plan, and falls back
to the plan before this pass if that fails. Units that wait for another subtask are left
alone: what their robot does before the wait costs nothing (it opens the fridge while
another robot cuts the slice it will put there), and a move that saves work there can
make the plan end later.

Written here rather than taken from a library: it is a neighbourhood of plan
*reordering* (Bäckström 1998 studies its complexity; plan-space optimisers such as
Do and Kambhampati's post-processing deorder partial-order plans) on this project's
simulator rules, and no maintained Python package does it over our state.
"""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.hp.eliminate import Plan, eliminate
from emboteam.hp.merge import nominal_seconds
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.actions import Action, Skill
from emboteam.world.checker import condition_holds
from emboteam.world.goals import Condition
from emboteam.world.state import WorldState

#: moves kept per plan (each a replay and an elimination)
MAX_MOVES = 4
#: longer plans are left as they are (a pass costs O(n^2) rule checks)
MAX_STEPS = 80
#: seconds the team must save for a move to be kept
MIN_GAIN = 0.5


def merge_visits(state: WorldState, actions: Sequence[tuple[str, Action]], goals: Sequence[Condition]) -> Plan:
    """``actions`` (a plan that runs from ``state``) with steps moved to other visits of
    their robot to the same object where that saves seconds (module docstring); the
    original when nothing does or the plan does not run."""
    plan: Plan = list(actions)
    if not plan or len(plan) > MAX_STEPS:
        return plan
    base = _run(state, plan)
    if base is None:
        return plan
    end, spent = base
    robots = sorted({r for r, _ in plan})
    wanted = [c for c in goals if condition_holds(c, end)]
    hands = {r: end.robots[r].holding for r in robots}
    limit = dict(spent)  # no robot may come to spend more than in the original
    best = sum(spent.values())
    for _ in range(MAX_MOVES):
        for cand in _moves(plan):
            cand = _without_idle_drives(cand)
            run = _run(state, cand)
            if run is None:
                continue
            end, seconds = run
            if (sum(seconds.values()) < best - MIN_GAIN
                    and all(seconds.get(r, 0.0) <= limit.get(r, 0.0) + 1e-9 for r in robots)
                    and {r: end.robots[r].holding for r in robots} == hands
                    and all(condition_holds(c, end) for c in wanted)):
                plan, best = cand, sum(seconds.values())
                break
        else:
            break
    if len(plan) != len(actions):
        plan = eliminate(state, plan, goals)  # once, on the plan kept: what else the moves made idle
    return plan


def _without_idle_drives(plan: Plan) -> Plan:
    """``plan`` without the drives a robot's next step is another drive of (a move took
    away the step it drove to do)."""
    out: Plan = []
    for k, (robot, a) in enumerate(plan):
        if a.skill is Skill.GoToObject:
            nxt = next((b for r, b in plan[k + 1:] if r == robot), None)
            if nxt is not None and nxt.skill is Skill.GoToObject:
                continue
        out.append((robot, a))
    return out


def _moves(plan: Plan) -> list[Plan]:
    """Every plan with one step the robot drove to do moved to the robot's next or
    previous visit to its object."""
    out: list[Plan] = []
    for i, (robot, a) in enumerate(plan):
        if a.skill is Skill.GoToObject or i == 0:
            continue
        before = plan[i - 1]
        if before[0] != robot or before[1].skill is not Skill.GoToObject or before[1].target != a.target:
            continue
        mine = [k for k, (r, b) in enumerate(plan) if r == robot and k not in (i - 1, i)
                and b.skill is not Skill.GoToObject and a.target in (b.target, b.receptacle)]
        later = [k for k in mine if k > i]
        if later:
            k = later[0]
            out.append([*plan[:i], *plan[i + 1:k], plan[i], *plan[k:]])
        earlier = [k for k in mine if k < i - 1]
        if earlier:
            k = earlier[-1]
            out.append([*plan[:k + 1], plan[i], *plan[k + 1:i], *plan[i + 1:]])
    return out


def _run(state: WorldState, plan: Plan) -> tuple[WorldState, dict[str, float]] | None:
    """The end state and each robot's nominal seconds (None: a step cannot run). Not
    ``eliminate._run``: that one keeps copies of the states where removals are tried,
    which a reordered plan has no use for."""
    s = state.copy()
    spent: dict[str, float] = {}
    for robot, a in plan:
        if check_action(s, robot, a) is not None:
            return None
        spent[robot] = spent.get(robot, 0.0) + nominal_seconds(s, robot, a)
        apply_action(s, robot, a)
    return s, spent
