"""Which tasks of a suite a named disturbance can happen in.

``--breakdown robot2@0.3`` can only break a robot the task's team has, ``--moves
Apple_1@0.5`` only move an object its floor plan has. A task it cannot happen in is *not
applicable*: it is not run, not counted in SR, and listed with its reason in the tables
and the ``--json`` summary (a task that ran and failed is something else). A spec that
matches no task of the suite at all is a typo, refused before anything runs (exit 2).
``random`` picks from each task's own team or plan, so it applies everywhere.
"""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.sim.disturbances import RANDOM, Disturbances, DisturbanceSpecError
from emboteam.task import BenchTask
from emboteam.world.robots import parse_team, robot_profile
from emboteam.world.scene import load_scene


def _objects(task: BenchTask) -> set[str]:
    return {o.id for o in load_scene(task.floor_plan).objects}


def _present(object_id: str, objects: set[str]) -> bool:
    """An object of the floor plan, or a slice piece one of them may be cut into (as the
    simulator accepts it)."""
    whole, sep, _ = object_id.partition("_Slice_")
    return object_id in objects or (bool(sep) and whole in objects)


def reasons(spec: Disturbances, task: BenchTask) -> list[str]:
    """Why each named disturbance of ``spec`` cannot happen in ``task`` (empty: it applies)."""
    found: list[str] = []
    team = [p.name for p in parse_team(list(task.robots))]
    for b in spec.breakdowns:
        if b.robot != RANDOM and robot_profile(b.robot).name not in team:
            found.append(f"--breakdown {b}: {robot_profile(b.robot).name} is not in its team ({', '.join(team)})")
    named = [m for m in spec.moves if m.object != RANDOM]
    if named:
        objects = _objects(task)
        found += [f"--moves {m}: {task.floor_plan} has no {m.object}" for m in named
                  if not _present(m.object, objects)]
    return found


def split_applicable(spec: Disturbances, tasks: Sequence[BenchTask]) -> tuple[list[BenchTask], list[str]]:
    """The tasks ``spec`` applies to, and one ``"TASK: why"`` line per task it does not.
    Raises :class:`DisturbanceSpecError` when a named disturbance matches no task."""
    applicable: list[BenchTask] = []
    skipped: list[str] = []
    for task in tasks:
        why = reasons(spec, task)
        if why:
            skipped.append(f"{task.key}: {'; '.join(why)}")
        else:
            applicable.append(task)
    if tasks and not applicable:
        raise DisturbanceSpecError(_unmatched(spec, tasks))
    return applicable, skipped


def _unmatched(spec: Disturbances, tasks: Sequence[BenchTask]) -> str:
    """What to fix: the first named disturbance that applies to no task of the suite."""
    for b in spec.breakdowns:
        if b.robot != RANDOM and all(reasons(Disturbances(breakdowns=(b,)), t) for t in tasks):
            members: dict[str, int] = {}
            for t in tasks:
                for p in parse_team(list(t.robots)):
                    members[p.name] = members.get(p.name, 0) + 1
            common = sorted(members, key=lambda n: (-members[n], n))[:3]
            return (f"--breakdown {b}: no task of the suite has {robot_profile(b.robot).name} in its team "
                    f"(robots in the most teams: {', '.join(common)}; random@WHEN picks one of each team)")
    for m in spec.moves:
        if m.object != RANDOM and all(reasons(Disturbances(moves=(m,)), t) for t in tasks):
            return (f"--moves {m}: no floor plan of the suite has an object {m.object!r} (ids as "
                    "'emboteam scene FLOORPLAN' lists them, e.g. Apple_1; random@WHEN picks one the plan uses)")
    return "--breakdown and --moves together apply to no task of the suite: each task lacks one of them"
