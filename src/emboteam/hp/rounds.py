"""The pieces of a planning round: planning units, clusters of related subtasks, robots
to retry with, repairs for plans made for an earlier state, and which subtask a step
serves. Used by :mod:`emboteam.hp.planner`."""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field

from emboteam.hp.decompose import group_indices
from emboteam.hp.merge import GroundedStep, SeqStep
from emboteam.hp.requirements import need_of
from emboteam.pfg.taskspec import Subtask
from emboteam.world.actions import Action, Skill
from emboteam.world.catalogue import INTERLOCKED, load_catalogue
from emboteam.world.goals import Condition
from emboteam.world.state import RobotState, WorldState


@dataclass
class Unit:
    """Subtasks Fast Downward plans in one call, for these robots."""

    id: str
    subtasks: list[Subtask]
    robots: tuple[str, ...]
    narrow: bool = True
    protect: list[Condition] = field(default_factory=list)

    @property
    def conditions(self) -> list[Condition]:
        return [c for t in self.subtasks for c in t.goal]

    def describe(self) -> str:
        return ", ".join(t.id for t in self.subtasks)


@dataclass
class Attempt:
    """How a subtask is to be planned next (after failures)."""

    narrow: bool = True
    #: robots to plan with after the assigned ones failed (empty: the assigned ones)
    wide: tuple[str, ...] = ()
    #: planned alone (a unit holding it was too big for the planner's limits)
    solo: bool = False
    #: goals accepted earlier that its plans broke: kept in its problem
    protect: dict[str, Condition] = field(default_factory=dict)
    tries: int = 0


def make_units(ready: Sequence[Subtask], assigned: Mapping[str, tuple[str, ...]], attempts: Mapping[str, Attempt],
               counter: Iterator[int], cluster: Mapping[str, str], max_conditions: int) -> list[Unit]:
    """This round's planning units: ready subtasks grouped by their robots, whole
    clusters of related subtasks at a time, up to ``unit_conditions`` conditions, and at
    most one unit per robot (a robot's next unit is planned from where its previous one
    leaves it, next round)."""
    groups: dict[tuple[tuple[str, ...], bool], dict[str, list[Subtask]]] = {}
    for t in ready:
        a = attempts[t.id]
        robots = a.wide or assigned[t.id]
        key = t.id if a.solo else cluster.get(t.id, t.id)
        groups.setdefault((robots, a.narrow and not a.wide), {}).setdefault(key, []).append(t)
    units: list[Unit] = []
    busy: set[str] = set()
    for (robots, narrow), linked in sorted(groups.items(), key=lambda kv: len(kv[0][0])):
        if busy.intersection(robots):
            continue
        chunk: list[Subtask] = []
        for members in linked.values():
            solo = any(attempts[t.id].solo for t in members)
            size = sum(len(t.goal) for t in chunk)
            if chunk and (solo or size + sum(len(t.goal) for t in members) > max_conditions):
                break
            chunk += members
            if solo:
                break
        units.append(Unit(f"u{next(counter)}", chunk, robots, narrow))
        busy.update(robots)
    for u in units:
        u.protect = list({k: c for t in u.subtasks for k, c in attempts[t.id].protect.items()}.values())
    return units


def attribute(actions: Sequence[tuple[str, Action]], unit: Unit, state: WorldState) -> list[str]:
    """Which subtask each step serves: the first subtask whose goal names an object the
    step touches; steps touching none (fetching a knife) go with their robot's next step."""
    owners: list[tuple[str, set[str]]] = []
    for t in unit.subtasks:
        objs: set[str] = set()
        for c in t.goal:
            for ref in (c.subject, c.receptacle):
                if ref is None:
                    continue
                if ref.id is not None:
                    objs.add(ref.id)
                else:
                    objs.update(o.id for o in state.objects.values() if o.type in ref.types)
        owners.append((t.id, objs))
    found: list[str | None] = []
    for _, a in actions:
        touched = {x.split("_Slice_")[0] for x in (a.target, a.receptacle) if x} | {
            x for x in (a.target, a.receptacle) if x}
        found.append(next((tid for tid, objs in owners if touched & objs), None))
    out: list[str] = [""] * len(actions)
    default = unit.subtasks[0].id if unit.subtasks else unit.id
    nxt: dict[str, str] = {}
    for i in range(len(actions) - 1, -1, -1):
        robot = actions[i][0]
        tid = found[i]
        if tid is not None:
            nxt[robot] = tid
        out[i] = tid or nxt.get(robot, "")
    last: dict[str, str] = {}
    for i, (robot, _) in enumerate(actions):
        out[i] = out[i] or last.get(robot, default)
        last[robot] = out[i]
    return out


def clusters(subtasks: Sequence[Subtask], state: WorldState, team: Sequence[str]) -> list[Subtask]:
    """Independent subtasks that may act on a common object (``sliced(Apple)``,
    ``inside(Apple, Fridge)``) are allocated and planned together: apart, each plan would
    be made for an apple the other changes. Subtasks naming different robots stay apart.
    Each cluster is returned as one subtask whose id joins its members' with ``+``."""
    by_robot: dict[str | None, list[Subtask]] = {}
    for t in subtasks:
        by_robot.setdefault(t.robot, []).append(t)
    out: list[Subtask] = []
    for robot, members in by_robot.items():
        conds = [c for t in members for c in t.goal]
        owner = [k for k, t in enumerate(members) for _ in t.goal]
        merged: dict[int, list[int]] = {}
        home = list(range(len(members)))
        for linked in group_indices(conds, state, list(team)):
            ks = sorted({home[owner[i]] for i in linked})
            for k in range(len(members)):
                if home[k] in ks:
                    home[k] = ks[0]
        for k in range(len(members)):
            merged.setdefault(home[k], []).append(k)
        for ks in merged.values():
            group = [members[k] for k in ks]
            if len(group) == 1:
                out.append(group[0])
                continue
            out.append(Subtask(id="+".join(t.id for t in group), description=" & ".join(t.description for t in group),
                               robot=robot, goal=tuple(c for t in group for c in t.goal)))
    return out


def helpers(u: Unit, state: WorldState, team: Sequence[str], accepted: Sequence[GroundedStep],
             per_role: int = 2, cap: int = 6) -> tuple[str, ...]:
    """Robots to retry a unit with: its own, plus the least loaded robots able to fill
    each of its roles (a whole 32-robot team would make a problem too big to solve)."""
    load = {r: sum(g.seconds for g in accepted if g.robot == r) for r in team}
    out = list(u.robots)
    for c in u.conditions:
        need = need_of(c, state, team)
        for alt in need.alternatives:
            for role in alt:
                able = sorted((r for r in team if role.covered_by(state.robots[r].profile)),
                              key=lambda r: (load[r], r))
                out += [r for r in able[:per_role] if r not in out]
    return tuple(out[:max(cap, len(u.robots))]) if len(team) > cap else tuple(team)


def polish(actions: Sequence[tuple[str, Action]]) -> list[tuple[str, Action]]:
    """Drop a robot's GoToObject when its next own step is another GoToObject.

    lama-first's plans are not optimal and often drive a robot somewhere it then leaves
    without acting. Such a hop only moves the robot, and the next hop moves it again, so the
    state after the second is the same without the first; other robots' steps never depend
    on where this robot stands. Anything it might have relied on is re-checked when the
    plan is replayed (and a missing approach is restored by :func:`preparations`).
    """
    keep = [True] * len(actions)
    last_goto: dict[str, int] = {}
    for i, (robot, action) in enumerate(actions):
        prev = last_goto.pop(robot, None)
        if action.skill is Skill.GoToObject:
            if prev is not None:
                keep[prev] = False
            last_goto[robot] = i
    return [a for a, k in zip(actions, keep, strict=True) if k]


def _reach(state: WorldState, step: SeqStep) -> list[Action]:
    """Go back within reach of the step's object (where it still lies, not held)."""
    a = step.action
    need = a.receptacle if a.skill is Skill.PutObject else a.target
    if a.skill in (Skill.DropHandObject, Skill.ThrowObject) or need not in state.objects:
        return []
    place = state.objects[need]
    if place.gone or place.held_by is not None or state.in_reach(step.robot, need):
        return []
    return [Action(skill=Skill.GoToObject, target=need)]


def _reopen(state: WorldState, step: SeqStep, robot: RobotState) -> list[Action]:
    """Open the receptacle a put goes into, which another robot closed after this plan
    was made (or opened first, so this plan's own opening was skipped); a running
    interlocked appliance is switched off first."""
    a = step.action
    rec = state.objects.get(a.receptacle) if a.skill is Skill.PutObject and a.receptacle else None
    if (rec is None or rec.type not in load_catalogue().must_be_open or rec.is_open
            or not robot.profile.can(Skill.OpenObject)):
        return []
    off = rec.type in INTERLOCKED and rec.is_on and robot.profile.can(Skill.SwitchOff)
    return [*([Action(skill=Skill.SwitchOff, target=rec.id)] if off else []),
            Action(skill=Skill.OpenObject, target=rec.id)]


def _interlock(state: WorldState, step: SeqStep, robot: RobotState) -> list[Action]:
    """The door/power interlock: switch a running appliance off before opening it, close
    it before switching it on."""
    a = step.action
    target = state.objects.get(a.target)
    if target is None or target.type not in INTERLOCKED:
        return []
    out: list[Action] = []
    if a.skill is Skill.OpenObject and target.is_on and robot.profile.can(Skill.SwitchOff):
        out.append(Action(skill=Skill.SwitchOff, target=target.id))
    if a.skill is Skill.SwitchOn and target.is_open and robot.profile.can(Skill.CloseObject):
        out.append(Action(skill=Skill.CloseObject, target=target.id))
    return out


def preparations(state: WorldState, step: SeqStep) -> list[Action]:
    """Actions that make a step of a plan made for an earlier state runnable again: go
    back within reach of its object, open a receptacle another robot closed before putting
    into it, switch a running microwave off before opening it, close it before switching
    it on (the door/power interlock). Validated like any step."""
    robot = state.robots.get(step.robot)
    if robot is None or step.action.skill is Skill.GoToObject:
        return []
    return [*_reach(state, step), *_reopen(state, step, robot), *_interlock(state, step, robot)]


def already_done(state: WorldState, action: Action) -> bool:
    """An open/close/switch whose effect already holds (a unit planned in parallel did it
    first): skipping it keeps the rest of the plan valid, as its effect is in place."""
    o = state.objects.get(action.target)
    if o is None:
        return False
    return ((action.skill is Skill.OpenObject and o.is_open) or (action.skill is Skill.CloseObject and not o.is_open)
            or (action.skill is Skill.SwitchOn and o.is_on) or (action.skill is Skill.SwitchOff and not o.is_on))
