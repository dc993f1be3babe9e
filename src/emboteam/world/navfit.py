"""How well a floor plan's navigation grid fits its objects, and the check that a task
only needs objects a robot can reach.

The grid is AI2-THOR 2.1's (ALFRED), the objects AI2-THOR 5.x's: in some floor plans
objects moved between versions and lie beyond the 1.5 m interaction distance of every
reachable cell. Where open floor leads to them, cells were added to the grid
(``data/nav/added_cells.json``, :func:`emboteam.world.navgrid.load_grid`); the fit names
those cells and why, and the objects still out of reach (``emboteam scene N``). A task whose
goal needs one of those is rejected before planning with :class:`UnreachableObjectError`
instead of failing somewhere in execution.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

from emboteam.errors import EmboTeamError
from emboteam.world.goals import Goal, ObjectRef
from emboteam.world.navgrid import NavGrid
from emboteam.world.navigation import alfred_key, navigator
from emboteam.world.scene import Scene, load_scene


class UnreachableObjectError(EmboTeamError):
    """The goal needs an object no robot can reach on this floor plan's navigation grid
    (a capability the scene lacks: exit 2)."""


@dataclass(frozen=True)
class NavFit:
    """The fit of one floor plan's grid to its objects."""

    floor_plan: str
    cells: int
    dropped_cells: int
    objects: int
    unposed: tuple[str, ...]
    alfred_poses: int
    alfred_used: int
    starts: tuple[tuple[float, float], ...]
    #: cells added for AI2-THOR 5.x objects: ((x, z) in metres, why), in cell order
    added: tuple[tuple[tuple[float, float], str], ...] = ()

    @property
    def posed(self) -> int:
        return self.objects - len(self.unposed)

    def as_dict(self) -> dict[str, object]:
        return {"floor_plan": self.floor_plan, "cells": self.cells, "dropped_cells": self.dropped_cells,
                "objects": self.objects, "posed": self.posed, "unposed": list(self.unposed),
                "alfred_openable_poses": self.alfred_poses, "alfred_poses_used": self.alfred_used,
                "robot_starts": [list(p) for p in self.starts],
                "added_cells": [{"point": list(p), "reason": why} for p, why in self.added]}

    def summary(self) -> str:
        text = (f"navigation grid: {self.cells} cells"
                + (f" ({self.dropped_cells} cut-off cells left out)" if self.dropped_cells else "")
                + f"; {self.posed}/{self.objects} objects have an interaction pose"
                + f"; ALFRED openable poses used for {self.alfred_used}/{self.alfred_poses}")
        if self.added:
            added = sorted({o.split(" ")[-1] for _, why in self.added for o in why.split("; ")
                            if o.startswith("within reach of")})
            text += f"; {len(self.added)} cells added for AI2-THOR 5.x objects (to reach {', '.join(added)})"
        if self.unposed:
            text += f"; out of reach of every cell: {', '.join(self.unposed)}"
        return text


def _needs_pose(scene: Scene) -> list[str]:
    """Objects a robot may have to act on (the Floor is everywhere)."""
    return [o.id for o in scene.objects if o.type != "Floor"]


@cache
def nav_fit(floor_plan: str) -> NavFit:
    scene = load_scene(floor_plan)
    nav = navigator(scene.floor_plan)
    unposed = []
    used = 0
    for oid in _needs_pose(scene):
        o = scene.get(oid)
        pose = nav.pose_for((o.position[0], o.position[2]))
        if pose is None:
            unposed.append(oid)
            continue
        key = alfred_key(o, nav.grid)
        alfred = nav.grid.openable.get(key) if key else None
        if alfred is not None and nav.grid.cell_at((alfred[0], alfred[1])) == pose.cell:
            used += 1
    starts = tuple(scene.robot_start(i) for i in range(4))
    added = tuple((NavGrid.point(c), why) for c, why in sorted(nav.grid.added.items()))
    return NavFit(scene.floor_plan, len(nav.grid.cells), nav.grid.dropped, len(_needs_pose(scene)),
                  tuple(unposed), len(nav.grid.openable), used, starts, added)


def unposed_objects(floor_plan: str) -> frozenset[str]:
    return frozenset(nav_fit(floor_plan).unposed)


def _out_of_reach(ref: ObjectRef, scene: Scene, unposed: frozenset[str]) -> list[str]:
    """The objects ``ref`` could mean, when every one of them is out of reach (else [])."""
    if ref.id is not None:
        base = ref.id.split("_Slice_")[0]
        return [base] if base in unposed else []
    cands = [o.id for o in scene.objects if o.type in ref.types
             or any(o.type == t.removesuffix("Sliced") for t in ref.types)]
    return cands if cands and all(c in unposed for c in cands) else []


def check_reachable(goal: Goal, scene: Scene) -> None:
    """Raise :class:`UnreachableObjectError` when a goal condition names an object (or
    only objects of a type) that no reachable cell is within 1.5 m of."""
    unposed = unposed_objects(scene.floor_plan)
    if not unposed:
        return
    problems = []
    for cond in goal.conditions:
        for ref in (cond.subject, cond.receptacle):
            missing = _out_of_reach(ref, scene, unposed) if ref is not None else []
            if missing:
                problems.append(f"{cond}: no reachable cell of {scene.floor_plan}'s navigation grid is "
                                f"within 1.5 m of {', '.join(missing)}")
    if problems:
        raise UnreachableObjectError("; ".join(problems))
