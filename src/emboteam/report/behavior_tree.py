"""The behavior tree the viewer shows, with each node's status changes over time.

Two sources, best first:

- the trace's ``node`` events: the tree is the prefix tree of their ``path`` (the names
  from the root down, ``/``-separated or a list), children in the order they were first
  ticked, so it shows the tree that actually ran whatever the compiler named its nodes;
- otherwise the plan (episodes of modes without a behavior tree, or traces without node
  events): Parallel -> one Sequence per robot -> per step Sequence(Fallback(Pre,
  Recover), Core, Post), as docs/architecture.md specifies, with statuses derived from the
  step's action events. The page says which source it shows.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import Literal

from pydantic import BaseModel, Field

from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.report.timeline import ActionBar, NodeChange

Source = Literal["trace", "plan", "none"]
#: a core action node is named after its action, e.g. ``PutObject(Apple_1, Fridge_1)``
_SKILL_CALL = re.compile(r"^(GoTo|Pickup|Put|Open|Close|Slice|Break|Clean|Throw|DropHand|Push|Pull)Object\(|"
                         r"^SwitchO(n|ff)\(")
ROOT_NAME = "EmboTeam"


class TreeNode(BaseModel):
    id: int
    parent: int | None
    name: str
    kind: str
    depth: int
    robot: str | None = None
    note: str = ""
    changes: list[tuple[float, str]] = Field(default_factory=list, description="(t, status), by t")


class BehaviorTree(BaseModel):
    source: Source
    nodes: list[TreeNode] = Field(description="depth-first order: a node comes before its children")


def infer_kind(name: str, depth: int, robots: Sequence[str], type_hint: str | None = None) -> str:
    """What a node is, from the compiler's node type if the trace has it, else its name."""
    if name in robots:
        return "robot"
    if re.match(r"^\S+\.\d+\b", name):
        return "step"
    if _SKILL_CALL.match(name):
        return "action"
    if "|" in name:  # "Pre|Recover": alternatives
        return "fallback"
    text = (type_hint or name).lower()
    for word, kind in (("parallel", "parallel"), ("fallback", "fallback"), ("selector", "fallback"),
                       ("recover", "recover"), ("sequence", "sequence"), ("wait", "sync"),
                       ("sync", "sync"), ("lock", "sync"), ("signal", "sync"), ("acquire", "sync"),
                       ("release", "sync")):
        if word in text:
            return kind
    first = name.split()[0].lower() if name.split() else ""
    if first in ("pre", "post", "precondition", "postcondition") or "condition" in text:
        return "condition"
    if first in ("core", "act"):
        return "action"
    if depth == 0:
        return "parallel"
    return "node"


def _step_notes(plan: MergedPlan | None) -> dict[str, str]:
    if plan is None:
        return {}
    notes = {}
    for s in plan.steps:
        parts = [f"subtask {s.subtask}"]
        if s.after:
            parts.append("waits for " + ", ".join(s.after))
        if s.resources:
            parts.append("holds " + ", ".join(s.resources))
        notes[s.id] = "; ".join(parts)
    return notes


def _step_of(name: str, step_ids: set[str]) -> str | None:
    m = re.match(r"^(\S+?\.\d+)(?=$|[\s:(])", name)
    return m.group(1) if m and m.group(1) in step_ids else None


def tree_from_trace(changes: Sequence[NodeChange], robots: Sequence[str],
                    plan: MergedPlan | None = None) -> BehaviorTree:
    nodes: list[TreeNode] = []
    index: dict[tuple[str, ...], int] = {}
    children: dict[int | None, list[int]] = {}
    notes = _step_notes(plan)
    step_ids = set(notes)
    for ch in changes:
        for depth in range(len(ch.path)):
            key = ch.path[: depth + 1]
            if key in index:
                continue
            parent = index[key[:-1]] if depth else None
            name = key[-1]
            robot = ch.robot or next((p for p in key if p in robots), None)
            hint = ch.type if depth == len(ch.path) - 1 else None
            step = _step_of(name, step_ids)
            node = TreeNode(id=len(nodes), parent=parent, name=name,
                            kind=infer_kind(name, depth, robots, hint), depth=depth, robot=robot,
                            note=notes.get(step, "") if step else "")
            index[key] = node.id
            nodes.append(node)
            children.setdefault(parent, []).append(node.id)
        target = nodes[index[ch.path]]
        if not target.changes or target.changes[-1][1] != ch.status:
            target.changes.append((ch.t, ch.status))
    return BehaviorTree(source="trace", nodes=_depth_first(nodes, children))


def _depth_first(nodes: list[TreeNode], children: dict[int | None, list[int]]) -> list[TreeNode]:
    """Renumber so that every node follows its parent (a list the page can build in one pass)."""
    order: list[int] = []
    stack = list(reversed(children.get(None, [])))
    while stack:
        i = stack.pop()
        order.append(i)
        stack.extend(reversed(children.get(i, [])))
    new_id = {old: new for new, old in enumerate(order)}
    out = []
    for old in order:
        n = nodes[old]
        out.append(n.model_copy(update={"id": new_id[old],
                                        "parent": None if n.parent is None else new_id[n.parent]}))
    return out


class _PlanTree:
    def __init__(self) -> None:
        self.nodes: list[TreeNode] = []

    def add(self, parent: int | None, name: str, kind: str, robot: str | None = None,
            note: str = "", changes: list[tuple[float, str]] | None = None) -> int:
        depth = 0 if parent is None else self.nodes[parent].depth + 1
        self.nodes.append(TreeNode(id=len(self.nodes), parent=parent, name=name, kind=kind, depth=depth,
                                   robot=robot, note=note, changes=changes or []))
        return len(self.nodes) - 1


def _span(bars: list[ActionBar], final: str | None) -> list[tuple[float, str]]:
    """running from the first bar's start; at the last bar's end ``final`` (if known)."""
    if not bars:
        return []
    out = [(bars[0].start, "running")]
    if final is not None:
        out.append((bars[-1].end, final))
    return out


def _step_changes(step: PlanStep, bars: list[ActionBar]) -> dict[str, list[tuple[float, str]]]:
    core = [b for b in bars if b.action == str(step.action)]
    recover = [b for b in bars if b.recovery]
    last = bars[-1] if bars else None
    finished = last is not None and last.outcome != "unfinished"
    ok = finished and last is not None and last.outcome == "success" and last.action == str(step.action)
    verdict = ("success" if ok else "failure") if finished else None
    out: dict[str, list[tuple[float, str]]] = {
        "step": _span(bars, verdict),
        "pre": [(bars[0].start, "success")] if bars else [],
        "core": _span(core, ("success" if ok else "failure") if core and finished else None),
        "recover": _span(recover, ("success" if ok else "failure") if recover and finished else None),
        "post": [(last.end, "success")] if ok and last is not None else [],
    }
    out["fallback"] = out["pre"]
    return out


def tree_from_plan(plan: MergedPlan, actions: Sequence[ActionBar], success: bool | None,
                   end: float) -> BehaviorTree:
    """The tree shape of docs/architecture.md for ``plan``, with statuses derived from executed actions."""
    by_step: dict[str, list[ActionBar]] = {}
    for a in actions:
        if a.step is not None:
            by_step.setdefault(a.step, []).append(a)
    notes = _step_notes(plan)
    t = _PlanTree()
    all_bars = sorted(actions, key=lambda a: a.start)
    root_changes = [(0.0, "running")] if all_bars else []
    if all_bars and success is not None:
        root_changes.append((end, "success" if success else "failure"))
    root = t.add(None, f"{ROOT_NAME} (Parallel)", "parallel", changes=root_changes)
    for robot in plan.robots:
        steps = plan.for_robot(robot)
        mine = [a for a in all_bars if a.robot == robot]
        done = all(by_step.get(s.id) and by_step[s.id][-1].outcome == "success" for s in steps)
        robot_changes = _span(mine, "success" if done else ("failure" if mine else None))
        r = t.add(root, robot, "robot", robot, changes=robot_changes)
        for step in steps:
            ch = _step_changes(step, by_step.get(step.id, []))
            s = t.add(r, f"{step.id} {step.action}", "step", robot, notes.get(step.id, ""), ch["step"])
            f = t.add(s, "Fallback", "fallback", robot, changes=ch["fallback"])
            t.add(f, "Pre", "condition", robot, " ∧ ".join(map(str, step.pre)), ch["pre"])
            t.add(f, "Recover", "recover", robot, changes=ch["recover"])
            t.add(s, f"Core {step.action}", "action", robot, changes=ch["core"])
            t.add(s, "Post", "condition", robot, " ∧ ".join(map(str, step.post)), ch["post"])
    return BehaviorTree(source="plan", nodes=t.nodes)


def behavior_tree(changes: Sequence[NodeChange], plan: MergedPlan | None, actions: Sequence[ActionBar],
                  robots: Sequence[str], success: bool | None, end: float) -> BehaviorTree:
    if changes:
        return tree_from_trace(changes, robots, plan)
    if plan is not None and plan.steps:
        return tree_from_plan(plan, actions, success, end)
    return BehaviorTree(source="none", nodes=[])
