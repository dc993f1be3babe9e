"""Exports of a compiled plan: BehaviorTree.CPP v4 XML (opens in Groot2), Graphviz DOT
(and SVG/PNG through the ``dot`` binary), and ASCII.

The XML is written by walking the very py_trees tree the executor ticks, so it shows
the same nodes in the same order:

- ``<root BTCPP_format="4" main_tree_to_execute="MainTree">``; the main tree is the team's
  ``Parallel`` with ``success_count`` = number of robots and ``failure_count`` = 1 (each
  branch sits under ``IsolateBranch``, which never fails, so only success ends it);
- each plan step is a ``<BehaviorTree ID="Step_robot1_3">`` referenced by a ``<SubTree>``
  whose ports carry the step's ``robot``/``target``/``receptacle`` as literals and remap
  every blackboard entry it uses (``done_robot1_3``, ``lock_Fridge_1``,
  ``failed_robot2``) to the main tree's entry of the same name, since BehaviorTree.CPP
  gives every subtree its own blackboard;
- py_trees composites map by memory: ``Sequence(memory=True)`` -> ``Sequence`` (resumes
  its running child, restarts after a failure), ``Sequence(memory=False)`` ->
  ``ReactiveSequence``, ``Selector(memory=True)`` -> ``Fallback``, ``Selector(memory=False)``
  -> ``ReactiveFallback``; the back-off wait is the built-in ``Sleep(msec)``;
- every custom node id used (conditions, actions, the three decorators, one action per
  THOR skill) is declared in ``<TreeNodesModel>`` with its ports, and so is every step
  SubTree, which is what Groot2 needs to open and edit the file.

Each step's GoToObject carries the grid path the simulator drives for it (the plan run
once with avoidance, :mod:`emboteam.btc.drives`): the input port ``path`` lists the cells
as ``x,z,yaw`` (metres, degrees; ``;``-separated) and ``moves`` the AI2-THOR agent actions
(``MoveAhead``, ``RotateLeft``, ``RotateRight``, ``Wait:SECONDS`` where it waits for another
robot), ending at the interaction pose facing the object. A GoToObject node implemented for
a real AI2-THOR controller can step ``moves`` (or ``Teleport`` along ``path``); recovery
re-approaches have no such port (they are planned when they happen). The ASCII export lists
the same drives below the tree.

The step-local scratch of the py_trees nodes (the pending fault, Pre's diagnosis and the
object it names) appears as subtree-local entries ``{fault}``, ``{diagnosis}``,
``{culprit}``.
"""

from __future__ import annotations

import shutil
import subprocess
import tempfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import py_trees

from emboteam.btc.compiler import CompiledTree, compile_plan
from emboteam.btc.config import BTConfig
from emboteam.btc.drives import PlannedDrive, planned_drives
from emboteam.btc.errors import ExportError
from emboteam.btc.keys import ident
from emboteam.btc.nodes import Act, Leaf, Port
from emboteam.hp.plan import MergedPlan
from emboteam.world.state import WorldState

if TYPE_CHECKING:  # py_trees renders with pydot (its dependency, not ours)
    import pydot

Behaviour = py_trees.behaviour.Behaviour

#: node ids BehaviorTree.CPP v4 registers itself (no TreeNodesModel entry needed)
BUILTIN = frozenset({"Sequence", "ReactiveSequence", "Fallback", "ReactiveFallback", "Parallel",
                     "Sleep", "SubTree"})


@dataclass
class _Model:
    kind: str
    description: str
    ports: dict[str, tuple[str, str]] = field(default_factory=dict)  # name -> (direction, description)

    def add(self, port: Port) -> None:
        old = self.ports.get(port.name)
        direction = port.direction
        if old is not None and old[0] != direction:
            direction = "inout"
        self.ports[port.name] = (direction, port.description or (old[1] if old else ""))


@dataclass
class _Scope:
    """Inside a step's SubTree: its literal ports and the blackboard keys it remaps."""

    step_id: str
    robot: str
    target: str
    receptacle: str | None
    keys: dict[str, str] = field(default_factory=dict)  # key -> direction


def _xml_name(step_id: str) -> str:
    return f"Step_{ident(step_id)}"


#: the ports a step's GoToObject gets for its drive
PATH_PORT = "path"
MOVES_PORT = "moves"
_PATH_DOC = "the grid cells of the drive as x,z,yaw (m, degrees), ';'-separated"
_MOVES_DOC = "the drive as AI2-THOR agent actions: MoveAhead RotateLeft RotateRight Wait:SECONDS"


def _core_goto(node: Behaviour) -> bool:
    """A step's own GoToObject (not a recovery's re-approach, planned when it happens)."""
    return isinstance(node, Act) and node.recovery is None and node.btcpp_id == "GoToObject"


def _drive_ports(node: Leaf, scope: _Scope | None, drives: dict[str, PlannedDrive]) -> list[Port]:
    """``path``/``moves`` for the core GoToObject of a step whose drive is known."""
    if scope is None or not _core_goto(node) or scope.step_id not in drives:
        return []
    drive = drives[scope.step_id]
    return [Port(PATH_PORT, drive.cells, description=_PATH_DOC),
            Port(MOVES_PORT, drive.moves, description=_MOVES_DOC)]


class _Writer:
    def __init__(self, compiled: CompiledTree, drives: dict[str, PlannedDrive] | None = None) -> None:
        self.c = compiled
        self.drives = drives or {}
        self.models: dict[str, _Model] = {}
        self.subtrees: list[tuple[str, ET.Element, _Scope]] = []
        self.step_of = {node.id: sid for sid, node in compiled.steps.items()}

    # ---- ports ---------------------------------------------------------------------
    def _value(self, port: Port, scope: _Scope | None) -> str:
        if port.ref in ("robot", "target", "receptacle") and scope is not None:
            return "{" + port.ref + "}"
        if port.ref == "key":
            if scope is not None:
                old = scope.keys.get(port.value)
                scope.keys[port.value] = port.direction if old in (None, port.direction) else "inout"
            return "{" + port.value + "}"
        if port.ref == "local":
            return "{" + port.value + "}"
        return port.value

    def _model(self, node_id: str, kind: str, description: str, ports: list[Port]) -> None:
        if node_id in BUILTIN:
            return
        model = self.models.setdefault(node_id, _Model(kind, description))
        for p in ports:
            model.add(p)

    # ---- nodes ---------------------------------------------------------------------
    def element(self, node: Behaviour, scope: _Scope | None) -> ET.Element:
        if scope is None and node.id in self.step_of:
            return self._subtree_call(node, self.step_of[node.id])
        if isinstance(node, py_trees.composites.Parallel):
            el = ET.Element("Parallel", {"name": node.name, "success_count": str(len(node.children)),
                                         "failure_count": "1"})
        elif isinstance(node, py_trees.composites.Sequence):
            el = ET.Element("Sequence" if node.memory else "ReactiveSequence", {"name": node.name})
        elif isinstance(node, py_trees.composites.Selector):
            el = ET.Element("Fallback" if node.memory else "ReactiveFallback", {"name": node.name})
        elif isinstance(node, py_trees.decorators.Decorator):
            node_id: str = getattr(node, "BTCPP_ID", type(node).__name__)
            ports: list[Port] = node.ports() if hasattr(node, "ports") else []
            el = ET.Element(node_id, {"name": node.name})
            for p in ports:
                el.set(p.name, self._value(p, scope))
            self._model(node_id, "Decorator", getattr(node, "DESCRIPTION", ""), ports)
        elif isinstance(node, Leaf):
            node_id = node.btcpp_id
            ports = node.ports() + _drive_ports(node, scope, self.drives)
            el = ET.Element(node_id, {"name": node.name})
            for p in ports:
                el.set(p.name, self._value(p, scope))
            kind = "Condition" if node.BTCPP_KIND == "Condition" else "Action"
            self._model(node_id, kind, node.DESCRIPTION or f"the THOR skill {node_id}", ports)
        else:  # pragma: no cover - the compiler only builds the node types above
            raise ExportError(f"no BehaviorTree.CPP equivalent for {type(node).__name__}")
        for child in node.children:
            el.append(self.element(child, scope))
        return el

    def _subtree_call(self, node: Behaviour, step_id: str) -> ET.Element:
        step = self.c.blueprint.steps[step_id].step
        scope = _Scope(step_id, step.robot, step.action.target, step.action.receptacle)
        body = ET.Element("BehaviorTree", {"ID": _xml_name(step_id)})
        body.append(self.element(node, scope))
        self.subtrees.append((step_id, body, scope))
        call = ET.Element("SubTree", {"ID": _xml_name(step_id), "name": node.name,
                                      "robot": step.robot, "target": step.action.target,
                                      "receptacle": step.action.receptacle or ""})
        for key in sorted(scope.keys):
            call.set(key, "{" + key + "}")
        return call

    # ---- document ------------------------------------------------------------------
    def document(self, main_tree: str) -> ET.Element:
        root = ET.Element("root", {"BTCPP_format": "4", "main_tree_to_execute": main_tree})
        main = ET.SubElement(root, "BehaviorTree", {"ID": main_tree})
        main.append(self.element(self.c.root, None))
        for _, body, _ in self.subtrees:
            root.append(body)
        models = ET.SubElement(root, "TreeNodesModel")
        for node_id in sorted(self.models):
            m = self.models[node_id]
            el = ET.SubElement(models, m.kind, {"ID": node_id})
            if m.description:
                el.set("description", m.description)
            for name in sorted(m.ports):
                direction, desc = m.ports[name]
                port = ET.SubElement(el, f"{direction}_port", {"name": name, "type": "std::string"})
                if desc:
                    port.text = desc
        for step_id, _, scope in self.subtrees:
            el = ET.SubElement(models, "SubTree", {"ID": _xml_name(step_id)})
            for name in ("robot", "target", "receptacle"):
                ET.SubElement(el, "input_port", {"name": name, "type": "std::string"})
            for key in sorted(scope.keys):
                ET.SubElement(el, f"{scope.keys[key]}_port", {"name": key})
        return root


def _compiled(plan: MergedPlan, state: WorldState | None, config: BTConfig | None) -> CompiledTree:
    return compile_plan(plan, None, state=state, config=config)


def to_btcpp_xml(plan: MergedPlan, *, state: WorldState | None = None, config: BTConfig | None = None,
                 main_tree: str = "MainTree") -> str:
    """The plan's behavior tree as BehaviorTree.CPP v4 XML (see the module docstring).
    ``state`` (the initial world) lets the compiler predict interaction spots for steps
    without ``resources``, and gives every GoToObject its grid path (``path``, ``moves``)."""
    compiled = _compiled(plan, state, config)
    drives = planned_drives(plan, state) if state is not None else {}
    try:
        doc = _Writer(compiled, drives).document(main_tree)
    finally:
        compiled.close()
    ET.indent(doc, space="  ")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(doc, encoding="unicode") + "\n"


def to_dot(plan: MergedPlan, *, state: WorldState | None = None, config: BTConfig | None = None) -> str:
    """Graphviz DOT of the py_trees tree (py_trees' own renderer). With ``state``, each
    step's GoToObject node carries its drive as the XML export's ports do: attributes
    ``path`` and ``moves`` (read by tools; Graphviz ignores them), and a ``tooltip`` with
    both that SVG viewers show on hover."""
    compiled = _compiled(plan, state, config)
    drives = planned_drives(plan, state) if state is not None else {}
    try:
        graph = py_trees.display.dot_tree(compiled.root)
        _mark_drives(graph, compiled, drives)
        return str(graph.to_string())
    finally:
        compiled.close()


def _mark_drives(graph: pydot.Dot, compiled: CompiledTree, drives: dict[str, PlannedDrive]) -> None:
    """Put each step's drive on its GoToObject node of ``graph`` (py_trees' rendering of
    ``compiled.root``). py_trees names the nodes itself (duplicate names get ``*``s), so
    the nodes are matched to behaviours by walking both trees together: a node's edges
    lead to its children in order."""
    if not drives:
        return
    kids: dict[str, list[str]] = {}
    for edge in graph.get_edges():
        kids.setdefault(str(edge.get_source()), []).append(str(edge.get_destination()))
    nodes = {n.get_name(): n for n in graph.get_nodes()}
    step_of = {node.id: sid for sid, node in compiled.steps.items()}
    roots = [n for n in kids if all(n not in v for v in kids.values())]
    stack: list[tuple[Behaviour, str, str | None]] = [(compiled.root, roots[0], None)] if len(roots) == 1 else []
    while stack:
        node, name, step = stack.pop()
        step = step_of.get(node.id, step)
        if step in drives and _core_goto(node) and name in nodes:
            drive = drives[step]
            for key, value in ((PATH_PORT, drive.cells), (MOVES_PORT, drive.moves),
                               ("tooltip", f"path: {drive.cells}\nmoves: {drive.moves}")):
                nodes[name].set(key, value)
        names = kids.get(name, [])
        if len(names) == len(node.children):  # py_trees left nothing out below this node
            stack.extend((c, n, step) for c, n in zip(node.children, names, strict=True))


def to_ascii(plan: MergedPlan, *, state: WorldState | None = None, config: BTConfig | None = None) -> str:
    """The tree as indented text (py_trees' ASCII renderer); with ``state``, followed by
    each GoToObject step's grid path and agent actions."""
    compiled = _compiled(plan, state, config)
    try:
        text = str(py_trees.display.ascii_tree(compiled.root))
    finally:
        compiled.close()
    drives = planned_drives(plan, state) if state is not None else {}
    if drives:
        text = text.rstrip("\n") + "\n\ndrives (grid path, then AI2-THOR actions):\n" + "".join(
            f"  {sid} {plan.step(sid).action}: {d.cells}\n    {d.moves}\n" for sid, d in drives.items())
    return text


def render(plan: MergedPlan, path: Path, *, fmt: str | None = None, state: WorldState | None = None,
           config: BTConfig | None = None, timeout: float = 120.0) -> Path:
    """Write the tree as SVG or PNG (format from ``fmt`` or the file suffix) with the
    Graphviz ``dot`` binary; :class:`ExportError` when it is not installed or fails."""
    fmt = (fmt or path.suffix.lstrip(".")).lower()
    if fmt not in ("svg", "png"):
        raise ExportError(f"cannot render {fmt!r}: use svg or png (or to_dot for DOT text)")
    dot = shutil.which("dot")
    if dot is None:
        raise ExportError("Graphviz 'dot' is not installed (apt install graphviz); export DOT text "
                          "instead and render it elsewhere")
    source = to_dot(plan, state=state, config=config)
    with tempfile.NamedTemporaryFile("w", suffix=".dot", delete=False) as fh:
        fh.write(source)
        src = fh.name
    try:
        proc = subprocess.run([dot, f"-T{fmt}", "-o", str(path), src], capture_output=True, text=True,
                              timeout=timeout, check=False)
    except subprocess.TimeoutExpired:
        raise ExportError(f"dot took longer than {timeout:g} s") from None
    finally:
        Path(src).unlink(missing_ok=True)
    if proc.returncode != 0:
        raise ExportError(f"dot failed ({proc.returncode}): {proc.stderr.strip()[:300]}")
    return path
