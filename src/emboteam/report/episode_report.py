"""The episode viewer: ``DIR/report.html`` from ``DIR/episode.json`` + ``DIR/trace.jsonl``.

One self-contained page (inline CSS, JS and SVG, no network) with the floor-plan map and
the robots' paths animated over simulated time, the Gantt chart with sync arrows, the
behavior tree with statuses at the scrubber's time, the blackboard timeline, and the
metrics, goal results, TaskSpec and plan. Python computes the view (this module and
:mod:`timeline`, :mod:`behavior_tree`, :mod:`floor_map`); the page's plain JS only draws
it (``assets/episode.js``). docs/report.md describes the page.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from emboteam import __version__
from emboteam.errors import EmboTeamError
from emboteam.exec.episode import Episode
from emboteam.hp.plan import MergedPlan
from emboteam.report.behavior_tree import behavior_tree
from emboteam.report.floor_map import floor_map
from emboteam.report.loading import ReportError, load_episode_dir
from emboteam.report.page import render_page
from emboteam.report.timeline import Timeline, build_timeline
from emboteam.world.scene import Scene, load_scene

REPORT_NAME = "report.html"

#: robot colours (Tableau 10 without its red and green, which mean failure and success)
ROBOT_COLORS = ("#4e79a7", "#f28e2b", "#b07aa1", "#76b7b2", "#9c755f", "#edc948", "#ff9da7",
                "#bab0ac", "#17becf", "#8c564b", "#1f77b4", "#e377c2")


def _scene(floor_plan: str) -> tuple[Scene | None, str]:
    try:
        return load_scene(floor_plan), ""
    except EmboTeamError as exc:
        return None, f"no map: {exc}"


def _touched(episode: Episode) -> set[str]:
    """Objects the plan or the executed actions name: they get permanent map labels."""
    ids: set[str] = set()
    if episode.plan is not None:
        for s in episode.plan.steps:
            ids.add(s.action.target)
            if s.action.receptacle:
                ids.add(s.action.receptacle)
    return ids


def _plan_view(plan: MergedPlan | None) -> dict[str, Any] | None:
    if plan is None:
        return None
    robots = list(plan.robots) + sorted({s.robot for s in plan.steps} - set(plan.robots))
    waits: dict[str, list[dict[str, str]]] = {}
    for sp in plan.sync:
        waits.setdefault(sp.consumer, []).append({"step": sp.producer, "reason": sp.reason})
    for s in plan.steps:
        known = {w["step"] for w in waits.get(s.id, [])}
        for dep in s.after:
            if dep not in known:
                waits.setdefault(s.id, []).append({"step": dep, "reason": ""})
    return {
        "robots": {r: [{"id": s.id, "action": str(s.action), "subtask": s.subtask,
                        "resources": list(s.resources), "waits": waits.get(s.id, []),
                        "est_start": s.est_start, "est_end": s.est_end,
                        "pre": [str(p) for p in s.pre], "post": [str(p) for p in s.post]}
                       for s in plan.for_robot(r)] for r in robots},
        "sync": [{"producer": w["step"], "consumer": consumer, "reason": w["reason"]}
                 for consumer, ws in waits.items() for w in ws],
        "makespan": plan.makespan, "lower_bound": plan.lower_bound, "joint": plan.joint,
        "planner_calls": plan.planner_calls, "plan_seconds": plan.plan_seconds,
    }


def _timeline(episode: Episode, scene: Scene | None) -> Timeline:
    starts = {r: scene.robot_start(i) for i, r in enumerate(episode.robots)} if scene else None
    return build_timeline(episode.trace, episode.robots, episode.makespan, starts)


def episode_view(episode: Episode) -> dict[str, Any]:
    """Everything the page draws, as JSON-able data."""
    scene, map_note = _scene(episode.floor_plan)
    timeline = _timeline(episode, scene)
    tree = behavior_tree(timeline.nodes, episode.plan, timeline.actions, timeline.robots,
                         episode.success if episode.actions or timeline.actions else None, timeline.end)
    fmap = None
    if scene is not None:
        points = [(x, z) for track in timeline.poses.values() for x, z in zip(track.x, track.z, strict=True)]
        fmap = floor_map(scene, _touched(episode), points).model_dump()
    robots = timeline.robots
    return {
        "generator": f"emboteam {__version__}",
        "meta": {
            "task": episode.task, "instruction": episode.instruction, "floor_plan": episode.floor_plan,
            "room": scene.room if scene else "", "robots": list(episode.robots), "category": episode.category,
            "mode": episode.mode, "frontend": episode.frontend, "seed": episode.seed,
            "fault_level": episode.fault_level, "faults": episode.faults.model_dump(mode="json"),
            "disturbance": episode.disturbance.model_dump(mode="json") if episode.disturbance else None,
            "error": episode.error, "notes": list(episode.notes),
            "unexplained": list(episode.unexplained), "candidates": list(episode.candidates),
            "not_attempted": [n.model_dump() for n in episode.not_attempted],
        },
        "metrics": {
            "success": episode.success, "gcr": episode.gcr, "exec": episode.exec,
            "makespan": episode.makespan, "actions": episode.actions,
            "failed_actions": episode.failed_actions, "recoveries": episode.recoveries,
            "replans": episode.replans, "llm_calls": episode.llm_calls, "tokens": episode.tokens,
            "plan_seconds": episode.plan_seconds, "wall_seconds": episode.wall_seconds,
        },
        "conditions": [c.model_dump() for c in episode.conditions],
        "taskspec": episode.taskspec.model_dump(mode="json") if episode.taskspec else None,
        "taskspec_text": ({s.id: [str(c) for c in s.goal] for s in episode.taskspec.subtasks}
                          if episode.taskspec else {}),
        "plan": _plan_view(episode.plan),
        "map": fmap,
        "map_note": map_note,
        "timeline": timeline.model_dump(mode="json"),
        "tree": tree.model_dump(mode="json"),
        "colors": {r: ROBOT_COLORS[i % len(ROBOT_COLORS)] for i, r in enumerate(robots)},
    }


def render_episode_report(episode: Episode) -> str:
    """The report page of ``episode`` as HTML text."""
    verdict = "success" if episode.success else "failed"
    return render_page("episode.html", title=f"{episode.task} · {verdict} · EmboTeam",
                       styles=["common.css", "episode.css"], scripts=["common.js", "episode.js"],
                       data=episode_view(episode))


def save_episode_report(episode: Episode, directory: Path) -> Path:
    """Write the report of an episode already in memory to ``directory/report.html``."""
    out = Path(directory) / REPORT_NAME
    try:
        out.write_text(render_episode_report(episode), encoding="utf-8")
    except OSError as exc:
        raise ReportError(f"cannot write {out}: {exc}") from None
    return out


def write_episode_report(directory: Path) -> Path:
    """Write ``directory/report.html`` from the episode saved there; return its path.

    Raises :class:`ReportError` when the directory holds no readable episode."""
    directory = Path(directory)
    return save_episode_report(load_episode_dir(directory), directory)
