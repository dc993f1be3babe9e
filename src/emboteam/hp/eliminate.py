"""Action elimination: drop the steps of a sequential plan that its goal does not need.

lama-first minimises the number of actions only approximately and never seconds, and its
plans carry steps the goal does not need: a drive to an object already within reach (the
domain's conservative ``at`` makes it drive to every object it touches), a door closed
and opened again, a second microwave run; and plans made apart for two robots each run
the microwave where one run heats both things. A plan's makespan is made of those
seconds, so they are worth removing before the plan is merged, and it is cheap to do on
the symbolic state, with no planner call.

This is Action Elimination (Fink and Yang 1992; Nakhost and Müller, ICAPS 2010): for
each step in turn, remove it and every later step that can no longer run without it (a
step whose action the simulator's rules reject where it now stands), and keep the
shorter plan when it still reaches everything the original reached. Every kept plan is
a subsequence of the original, replayed in full with the simulator's rules
(:func:`emboteam.sim.rules.check_action`), so it is valid by construction; "still
reaches" means:

- every condition in ``goals`` that holds after the original plan holds after the new one
  (the unit's own goals and the goals accepted earlier that the planner protects);
- every robot ends holding what it held at the end of the original (the problem asks the
  acting robots to end with empty hands);
- no robot's nominal seconds grow (navigation is Manhattan distance over the robot's
  speed, so skipping a stop never lengthens a drive; the check keeps that honest).

The bound the benchmark reports is taken over the plan's own actions, so a shorter plan
lowers it too: elimination is measured on makespans, not on that ratio.

Removing a step replays the rest of the plan, so a pass costs O(n^2) rule checks for a
plan of n steps; two things keep it to milliseconds: only removals that can pay off are
tried (:func:`_worth_trying`), and a replay stops as soon as it rejoins the original run
(:func:`_without`). Plans longer than :data:`MAX_STEPS` are left as they are unless a
``window`` bounds each replay (the planner's whole accepted sequence). The
planner replays the result with every PDDL precondition checked too, as it does any
plan, and falls back to the original plan if that fails.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from emboteam.hp.merge import nominal_seconds
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.actions import Action, Skill
from emboteam.world.checker import condition_holds
from emboteam.world.goals import Condition
from emboteam.world.state import WorldState

#: longer plans are not searched (O(n^2) rule checks per pass)
MAX_STEPS = 160
#: most passes over the plan (a removal can make an earlier step removable: the drive to
#: a fridge the robot no longer closes)
MAX_PASSES = 3
#: the same with a ``window`` (a pass over a long sequence)
WINDOWED_PASSES = 2
#: steps that need no reach (the held object goes where the robot stands)
_HANDS_ONLY = frozenset({Skill.DropHandObject, Skill.ThrowObject})

#: toggles whose effect a later step of the other kind undoes (closed, then opened again)
_INVERSE = {Skill.OpenObject: Skill.CloseObject, Skill.CloseObject: Skill.OpenObject,
            Skill.SwitchOn: Skill.SwitchOff, Skill.SwitchOff: Skill.SwitchOn}

#: what a windowed elimination tries to remove (in its second pass, the drives only: the
#: first may have removed what the robot drove to)
_WINDOWED = frozenset({Skill.GoToObject, *_INVERSE})
_DRIVES = frozenset({Skill.GoToObject})

Plan = list[tuple[str, Action]]
Seconds = dict[str, float]


@dataclass
class _Trace:
    """A plan run from a state: the state before each step where a removal is tried or a
    replay compared (None elsewhere: copying ~100 objects per step is most of the cost),
    the state at the end, and each robot's nominal seconds before each step (and at the
    end)."""

    before: list[WorldState | None]
    end: WorldState
    spent: list[Seconds]
    marks: _Marks

    @property
    def total(self) -> Seconds:
        return self.spent[-1]


def eliminate(state: WorldState, actions: Sequence[tuple[str, Action]], goals: Sequence[Condition], *,
              window: int | None = None) -> Plan:
    """A subsequence of ``actions`` (a plan that runs from ``state``) that reaches every
    condition of ``goals`` the original reaches, leaves every robot's hand as the original
    does and costs no robot more nominal seconds; the original when no step can go or when
    the plan does not run. ``window``: a removal whose replay has not rejoined the
    original run within this many steps is given up (long plans: the replay of a removal
    that fails would otherwise run to the end), and only drives and toggles (opening,
    closing, switching) are tried, then the drives once more; None: replay to the end. The windowed
    form is for a sequence of plans eliminated one by one already: the cycles left
    between them are appliances each plan runs (a pickup repeated across plans is a tool
    passed on, which the goal needs)."""
    kept, _ = eliminate_steps(state, actions, goals, window=window)
    return [actions[k] for k in kept]


def eliminate_steps(state: WorldState, actions: Sequence[tuple[str, Action]], goals: Sequence[Condition], *,
                    window: int | None = None) -> tuple[list[int], frozenset[int]]:
    """:func:`eliminate` as the indices (into ``actions``) of the steps kept, and those of
    the kept steps that may now start from another state than in the original: those
    between a removed step and the point where the replay rejoined the original run.
    Every other kept step starts from the very state it started from before, so what was
    computed for it there (its grounding) still holds."""
    plan: Plan = list(actions)
    ids = list(range(len(plan)))  # each step's index in ``actions``
    if not plan or (window is None and len(plan) > MAX_STEPS):
        return ids, frozenset()
    trace = _run(state, plan, {})
    if trace is None:
        return ids, frozenset()  # the plan does not run as given: not ours to fix
    aim = _Aim.of(plan, goals, trace.end)
    search = _Search(plan, ids, trace)
    for n in range(MAX_PASSES if window is None else WINDOWED_PASSES):
        allowed = _WINDOWED if n == 0 else _DRIVES  # windowed: the toggles were all tried
        if not _pass(search, aim, window, allowed):
            break
    return search.ids, frozenset(search.moved.intersection(search.ids))


#: what :func:`_without` finds: the steps kept, the end state, the seconds, where it rejoined
_Found = tuple[list[int], WorldState, Seconds, int | None]


@dataclass(frozen=True)
class _Aim:
    """What every kept plan must still do, taken once from the original run: reach the
    conditions of the goals it reached, leave every robot's hand as it did."""

    robots: list[str]
    wanted: list[Condition]
    hands: dict[str, str | None]

    @classmethod
    def of(cls, plan: Plan, goals: Sequence[Condition], end: WorldState) -> _Aim:
        robots = sorted({r for r, _ in plan})
        wanted = [c for c in goals if condition_holds(c, end)]
        return cls(robots, wanted, _holdings(end, robots))

    def kept_by(self, found: _Found, trace: _Trace) -> bool:
        """Does the replay ``found`` still do it, with no robot's seconds grown over
        ``trace`` (the plan it was cut from)? A replay that rejoined the original run
        reaches what that run reaches, so its goals need no check."""
        _, end, seconds, k = found
        return (_holdings(end, self.robots) == self.hands
                and all(seconds.get(r, 0.0) <= trace.total.get(r, 0.0) + 1e-9 for r in self.robots)
                and (k is not None or all(condition_holds(c, end) for c in self.wanted)))


@dataclass
class _Search:
    """The plan as cut so far: its steps, their indices into the original, its run, and
    the indices of the steps that may start from another state than in the original."""

    plan: Plan
    ids: list[int]
    trace: _Trace
    moved: set[int] = field(default_factory=set)

    def tried(self, i: int, window: int | None, allowed: frozenset[Skill]) -> bool:
        """Is removing step ``i`` worth a replay? (its state is kept, a windowed search
        allows its skill, and :func:`_worth_trying` says it may pay off)"""
        at = self.trace.before[i]
        if at is None or (window is not None and self.plan[i][1].skill not in allowed):
            return False
        return _worth_trying(self.plan, i, at, self.trace.marks)

    def remove(self, i: int, found: _Found) -> None:
        """Keep the replay ``found`` of the plan without step ``i``."""
        keep, _, _, k = found
        cand = [self.plan[j] for j in keep]
        self.moved.update(self.ids[i:len(self.plan) if k is None else k + 1])
        self.ids = [self.ids[j] for j in keep]
        self.trace = _retrace(self.plan, cand, i, k, self.trace)
        self.plan = cand


def _pass(search: _Search, aim: _Aim, window: int | None, allowed: frozenset[Skill]) -> bool:
    """One pass over the plan, front to back, removing every step it can; whether it
    removed any (a removal can make an earlier step removable: another pass)."""
    removed_any = False
    i = 0
    while i < len(search.plan):
        if search.tried(i, window, allowed):
            found = _without(search.plan, i, search.trace, window)
            if found is not None and aim.kept_by(found, search.trace):
                search.remove(i, found)
                removed_any = True
                continue  # the step now at i is new: try it too
        i += 1
    return removed_any


def _holdings(state: WorldState, robots: Sequence[str]) -> dict[str, str | None]:
    return {r: state.robots[r].holding for r in robots}


def _touches(a: Action) -> tuple[str, ...]:
    return tuple(x for x in (a.target, a.receptacle) if x is not None)


@dataclass(frozen=True)
class _Marks:
    """Where removals are tried in a plan: ``repeated[k]``, step k's skill (or, for a
    toggle, the opposite one) is applied to its object again later; ``cyclic``, the
    objects of such steps (a replay is compared with the original after touching one)."""

    repeated: tuple[bool, ...]
    cyclic: frozenset[str]
    #: the last step acting on each object, and each robot's last drive: a replay is
    #: compared with the original only at such steps
    last_touch: dict[str, int]
    last_drive: dict[str, int]

    @classmethod
    def of(cls, plan: Plan) -> _Marks:
        seen: set[tuple[Skill, str]] = set()
        repeated = [False] * len(plan)
        for k in range(len(plan) - 1, -1, -1):
            a = plan[k][1]
            repeated[k] = (a.skill, a.target) in seen or (_INVERSE.get(a.skill), a.target) in seen
            seen.add((a.skill, a.target))
        cyclic = frozenset(x for k, (_, a) in enumerate(plan) if repeated[k] for x in _touches(a))
        last_touch: dict[str, int] = {}
        last_drive: dict[str, int] = {}
        for k, (robot, a) in enumerate(plan):
            for x in _touches(a):
                last_touch[x] = k
            if a.skill is Skill.GoToObject:
                last_drive[robot] = k
        return cls(tuple(repeated), cyclic, last_touch, last_drive)

    def needed(self, plan: Plan, k: int) -> bool:
        """Is the state before step ``k`` needed: a removal is tried there, or a replay
        compared there (after a drive, or after a step on an object of a cycle)?"""
        if plan[k][1].skill is Skill.GoToObject or self.repeated[k]:
            return True
        if k == 0:
            return True
        prev = plan[k - 1][1]
        return prev.skill is Skill.GoToObject or any(x in self.cyclic for x in _touches(prev))


def _apply(s: WorldState, robot: str, a: Action) -> None:
    """:func:`apply_action` on a state whose robot records are shared with the states kept
    (``copy(share_robots=True)``): the acting robot's record is copied first, the others
    are not written. A 32-robot state costs a third less to copy so."""
    s.own_robot(robot)
    apply_action(s, robot, a)


def _run(state: WorldState, plan: Plan, spent: Seconds, offset: int = 0, whole: Plan | None = None
         ) -> _Trace | None:
    """Run ``plan`` from ``state`` (not modified), ``spent`` the seconds so far; None if a
    step cannot run. ``whole``/``offset``: ``plan`` is ``whole[offset:]`` (which states
    to keep depends on the whole plan)."""
    whole = whole if whole is not None else plan
    marks = _Marks.of(whole)
    s = state.copy(share_robots=True)
    before: list[WorldState | None] = []
    seconds = [dict(spent)]
    for j, (robot, a) in enumerate(plan):
        before.append(s.copy(share_robots=True) if j == 0 or marks.needed(whole, offset + j) else None)
        if check_action(s, robot, a) is not None:
            return None
        now = dict(seconds[-1])
        now[robot] = now.get(robot, 0.0) + nominal_seconds(s, robot, a)
        _apply(s, robot, a)
        seconds.append(now)
    return _Trace(before, s, seconds, marks)


def _without(plan: Plan, i: int, trace: _Trace, window: int | None
             ) -> _Found | None:
    """``plan`` without step ``i`` and the later steps that cannot run without it (the
    indices of the steps kept), its final state, each robot's nominal seconds, and the
    step after which the run rejoined the original (None: it did not); None when it has
    not rejoined within ``window`` steps.

    The replay is compared with the original run after a drive of a robot whose step was
    skipped (GoToObject sets its position, and its held object's, whatever it did before)
    and after a step on an object a skipped step acted on (the microwave switched on
    again); when the states are equal the rest of the plan runs as it did, so the replay
    stops there: a redundant drive costs one comparison, not a replay.
    """
    start = trace.before[i]
    assert start is not None
    s = start.copy(share_robots=True)
    seconds = dict(trace.spent[i])
    keep = list(range(i))
    skipped = {plan[i][0]}
    objects = set(_touches(plan[i][1]))
    marks = trace.marks
    # beyond the window the replay must rejoin, and it can only do so at a drive of a
    # skipped robot or a step on a skipped step's object: past the last of those it fails
    bounded = window is not None and len(plan) - 1 - i > window
    horizon = max([marks.last_drive.get(plan[i][0], -1), *(marks.last_touch.get(x, -1) for x in objects)])
    for k in range(i + 1, len(plan)):
        if (window is not None and k - i > window) or (bounded and k > horizon):
            return None
        robot, a = plan[k]
        if check_action(s, robot, a) is not None:
            skipped.add(robot)
            objects.update(_touches(a))
            horizon = max([horizon, marks.last_drive.get(robot, -1), *(marks.last_touch.get(x, -1) for x in _touches(a))])
            continue
        seconds[robot] = seconds.get(robot, 0.0) + nominal_seconds(s, robot, a)
        _apply(s, robot, a)
        keep.append(k)
        if (a.skill is Skill.GoToObject and robot in skipped) or any(x in objects for x in _touches(a)):
            then = trace.before[k + 1] if k + 1 < len(plan) else trace.end
            if then is not None and s.robots == then.robots and s.objects == then.objects:
                for r, total in trace.total.items():  # the rest as in the original
                    seconds[r] = seconds.get(r, 0.0) + total - trace.spent[k + 1].get(r, 0.0)
                return keep + list(range(k + 1, len(plan))), trace.end, seconds, k
    return keep, s, seconds, None


def _retrace(plan: Plan, cand: Plan, i: int, k: int | None, trace: _Trace) -> _Trace:
    """The trace of ``cand`` (``plan`` without step i and some of the steps after it),
    reusing ``trace`` (``plan``'s) before step i and, when the run rejoined the original
    after step ``k``, after it."""
    start = trace.before[i]
    assert start is not None
    if k is None:
        tail = _run(start, cand[i:], trace.spent[i], i, cand)
        assert tail is not None  # cand ran in _without
        return _Trace(trace.before[:i] + tail.before, tail.end, trace.spent[:i] + tail.spent, tail.marks)
    mid_len = len(cand) - i - (len(plan) - k - 1)
    mid = _run(start, cand[i:i + mid_len], trace.spent[i], i, cand)
    assert mid is not None
    # from step k+1 of the old plan on, states are the old ones; seconds shift by what was saved
    saved = {r: trace.spent[k + 1].get(r, 0.0) - mid.spent[-1].get(r, 0.0) for r in trace.total}
    rest = [{r: v - saved.get(r, 0.0) for r, v in sp.items()} for sp in trace.spent[k + 2:]]
    after = trace.before[k + 1:] if k + 1 < len(plan) else []
    if after and after[0] is None:
        after[0] = mid.end  # compared there: equal to the old state
    return _Trace(trace.before[:i] + mid.before + after, trace.end, trace.spent[:i] + mid.spent + rest,
                  mid.marks)


def _worth_trying(plan: Plan, i: int, state: WorldState, marks: _Marks) -> bool:
    """Whether removing step ``i`` (``state`` is the state before it) can pay off without
    a replay that is bound to fail:

    - a drive to where the robot's next steps (up to its next drive) can all reach from
      where it stands already: the conservative ``at`` of the domain makes lama-first
      drive to every object it touches, however close;
    - a step whose effect the plan makes again or undoes later (the same skill on the
      same object: the microwave switched on again, the apple picked up again; a door
      closed that is opened again), the cycles lama-first leaves in; removing it makes
      the steps undoing it fail, and those are dropped with it.

    Any other step is what the goal needs, or its removal takes the rest of the robot's
    plan with it: the replay would run to the end to find the goal unmet."""
    robot, a = plan[i]
    if a.skill is not Skill.GoToObject:
        return marks.repeated[i]
    for r, b in plan[i + 1:]:
        if r != robot:
            continue
        if b.skill is Skill.GoToObject:
            break
        need = b.receptacle if b.skill is Skill.PutObject else b.target
        if b.skill in _HANDS_ONLY or need not in state.objects:
            continue
        if not state.in_reach(robot, need):
            return False
    return True
