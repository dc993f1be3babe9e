"""Exports: BehaviorTree.CPP v4 XML that Groot2 can open (parsed with ElementTree and
checked against the rules BehaviorTree.CPP's own schematron states), DOT and ASCII."""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from emboteam.btc.errors import ExportError
from emboteam.btc.export import BUILTIN, render, to_ascii, to_btcpp_xml, to_dot
from test_btc_plans import fresh_state, fridge_handoff, salad

CONTROL = {"Sequence", "ReactiveSequence", "Fallback", "ReactiveFallback", "Parallel"}


@pytest.fixture(scope="module")
def doc() -> ET.Element:
    plan, _ = fridge_handoff()
    return ET.fromstring(to_btcpp_xml(plan, state=fresh_state("FloorPlan1", "1,2")))


def _trees(doc: ET.Element) -> dict[str, ET.Element]:
    return {t.attrib["ID"]: t for t in doc.findall("BehaviorTree")}


def test_root_attributes_and_main_tree(doc: ET.Element) -> None:
    assert doc.tag == "root"
    assert doc.attrib["BTCPP_format"] == "4"
    main = doc.attrib["main_tree_to_execute"]
    trees = _trees(doc)
    assert main in trees
    assert all(len(list(t)) == 1 for t in trees.values())  # a BehaviorTree has exactly one child
    team = next(iter(trees[main]))
    assert team.tag == "Parallel"
    assert team.attrib["success_count"] == "2" and team.attrib["failure_count"] == "1"
    assert [c.attrib["robot"] for c in team] == ["robot1", "robot2"]
    assert all(c.tag == "IsolateBranch" for c in team)


def test_every_custom_node_is_declared_in_the_model(doc: ET.Element) -> None:
    model = doc.find("TreeNodesModel")
    assert model is not None
    declared = {m.attrib["ID"]: m for m in model if m.tag != "SubTree"}
    used: dict[str, set[str]] = {}
    for tree in doc.findall("BehaviorTree"):
        for el in tree.iter():
            if el.tag in ("BehaviorTree", "SubTree") or el.tag in BUILTIN:
                continue
            used.setdefault(el.tag, set()).update(k for k in el.attrib if k != "name")
    assert set(used) <= set(declared), set(used) - set(declared)
    for node_id, ports in used.items():
        m = declared[node_id]
        assert m.tag in ("Action", "Condition", "Decorator", "Control")
        names = {p.attrib["name"] for p in m if p.tag.endswith("_port")}
        assert ports <= names, (node_id, ports - names)
    assert declared["LiteralsHold"].tag == "Condition"
    assert declared["PickupObject"].tag == "Action"
    assert declared["Attempts"].tag == "Decorator"


def test_every_subtree_exists_with_its_ports(doc: ET.Element) -> None:
    trees = _trees(doc)
    model = {m.attrib["ID"]: m for m in doc.find("TreeNodesModel") if m.tag == "SubTree"}  # type: ignore[union-attr]
    calls = [el for t in trees.values() for el in t.iter("SubTree")]
    assert len(calls) == 7  # one per plan step
    for call in calls:
        sid = call.attrib["ID"]
        assert sid in trees, f"SubTree {sid} is not defined"
        assert {"robot", "target", "receptacle"} <= set(call.attrib)
        ports = {p.attrib["name"] for p in model[sid]}
        remapped = {k for k in call.attrib if k not in ("ID", "name")}
        assert remapped <= ports
        for key in remapped - {"robot", "target", "receptacle"}:
            assert call.attrib[key] == "{" + key + "}"  # blackboard entries remapped 1:1
    put = next(c for c in calls if c.attrib["ID"] == "Step_robot2_4")
    assert put.attrib["robot"] == "robot2" and put.attrib["target"] == "Apple_1"
    assert put.attrib["receptacle"] == "Fridge_1"


def test_sync_flags_are_blackboard_ports(doc: ET.Element) -> None:
    trees = _trees(doc)
    producer, consumer = trees["Step_robot1_2"], trees["Step_robot2_4"]
    signal = next(producer.iter("SignalDone"))
    assert signal.attrib["flag"] == "{done_robot1_2}"
    waits = [el.attrib["flag"] for el in consumer.iter() if el.tag in ("FlagSet", "WaitFlag")]
    assert waits == ["{done_robot1_2}", "{done_robot1_2}"]
    model = {m.attrib["ID"]: m for m in doc.find("TreeNodesModel")}  # type: ignore[union-attr]
    assert {p.tag for p in model["Step_robot1_2"] if p.attrib["name"] == "done_robot1_2"} == {"output_port"}
    assert {p.tag for p in model["Step_robot2_4"] if p.attrib["name"] == "done_robot1_2"} == {"input_port"}
    # the spot lock is shared read-write
    assert {p.tag for p in model["Step_robot2_4"] if p.attrib["name"] == "lock_Fridge_1"} == {"inout_port"}


def test_step_anatomy_in_xml(doc: ET.Element) -> None:
    step = next(iter(_trees(doc)["Step_robot2_2"]))
    assert step.tag == "Sequence"
    attempts = next(iter(step))
    assert attempts.tag == "Attempts" and attempts.attrib["max_attempts"] == "5"
    action = next(iter(attempts))
    fallback, core, post = list(action)
    assert fallback.tag == "ReactiveFallback"
    assert [c.tag for c in fallback] == ["ReactiveSequence", "RecoverLoop"]
    assert core.tag == "PickupObject" and core.attrib["target"] == "{target}"
    assert post.tag == "EffectsObserved" and "(holding robot2 Apple_1)" in post.attrib["literals"]
    for el in step.iter():
        if el.tag in CONTROL:
            assert len(list(el)) >= 1


def test_bigger_plan_exports_and_parses() -> None:
    plan, _ = salad()
    root = ET.fromstring(to_btcpp_xml(plan, state=fresh_state("FloorPlan1", "1,2,3")))
    assert len(root.findall("BehaviorTree")) == 1 + len(plan.steps)
    assert next(iter(_trees(root)["MainTree"])).attrib["success_count"] == "3"


def test_dot_and_ascii() -> None:
    plan, _ = fridge_handoff()
    dot = to_dot(plan)
    assert dot.lstrip().startswith("digraph") and "robot2.4 PutObject(Apple_1, Fridge_1)" in dot
    text = to_ascii(plan)
    assert "team" in text.splitlines()[0]
    assert "robot1.2 OpenObject(Fridge_1)" in text and "Pre|Recover" in text
    assert "drives" not in text  # without the initial state there are no drives to show
    drives = to_ascii(plan, state=fresh_state("FloorPlan1", "1,2")).split("drives (grid path")[1]
    gotos = [s for s in plan.steps if s.action.skill.value == "GoToObject"]
    assert all(f"{s.id} {s.action}:" in drives for s in gotos) and "MoveAhead" in drives


def test_dot_carries_each_steps_drive_as_the_xml_does(doc: ET.Element) -> None:
    """With the initial state, DOT's GoToObject nodes carry the same ``path`` and ``moves``
    as the XML export's ports (and a tooltip with both, for SVG viewers); without it, none."""
    import pydot

    plan, _ = fridge_handoff()
    (graph,) = pydot.graph_from_dot_data(to_dot(plan, state=fresh_state("FloorPlan1", "1,2")))

    def unquoted(v: object) -> str:
        return str(v).strip('"')

    marked = [n for n in graph.get_nodes() if "path" in n.get_attributes()]
    in_dot = sorted((unquoted(n.get("path")), unquoted(n.get("moves"))) for n in marked)
    in_xml = sorted((el.attrib["path"], el.attrib["moves"]) for el in doc.iter("GoToObject") if "path" in el.attrib)
    gotos = [s for s in plan.steps if s.action.skill.value == "GoToObject"]
    assert len(in_dot) == len(gotos) and in_dot == in_xml
    assert all(unquoted(n.get_name()).startswith("GoToObject(") for n in marked)
    for n, (path, moves) in zip(sorted(marked, key=lambda n: (unquoted(n.get("path")), unquoted(n.get("moves")))),
                                in_dot, strict=True):
        assert unquoted(n.get("tooltip")) == f"path: {path}\\nmoves: {moves}"
    assert "path=" not in to_dot(plan) and "moves=" not in to_dot(plan)


def test_render_needs_graphviz(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    plan, _ = fridge_handoff()
    with pytest.raises(ExportError, match="svg or png"):
        render(plan, tmp_path / "tree.pdf")
    monkeypatch.setattr(shutil, "which", lambda _name: None)
    with pytest.raises(ExportError, match="Graphviz"):
        render(plan, tmp_path / "tree.svg")


@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz dot not installed")
def test_render_svg(tmp_path: Path) -> None:  # pragma: no cover - needs graphviz
    plan, _ = fridge_handoff()
    out = render(plan, tmp_path / "tree.svg")
    assert out.read_text().lstrip().startswith(("<?xml", "<svg"))


def test_loads_and_ticks_in_behaviortree_cpp() -> None:
    """Load the export in BehaviorTree.CPP v4 itself (Python bindings ``behaviortreepy``,
    an optional test dependency). The bindings register custom nodes without ports, so
    the custom leaves' port attributes are dropped first (the ElementTree tests above check
    them against the model); everything else is BT.CPP's: control-node names and child
    counts, the Parallel's thresholds, the built-in Sleep, every SubTree with its remapped
    and literal ports and its model. With every leaf succeeding, the tree must succeed."""
    bt = pytest.importorskip("behaviortreepy")
    plan, _ = fridge_handoff()
    doc = ET.fromstring(to_btcpp_xml(plan, state=fresh_state("FloorPlan1", "1,2")))
    model = doc.find("TreeNodesModel")
    assert model is not None
    custom = {m.attrib["ID"]: m.tag for m in model if m.tag != "SubTree"}
    for m in [m for m in model if m.tag != "SubTree"]:
        model.remove(m)
    for tree in doc.findall("BehaviorTree"):
        for el in tree.iter():
            if el.tag in custom:
                for k in [k for k in el.attrib if k != "name"]:
                    del el.attrib[k]
    factory = bt.BehaviorTreeFactory()
    ticked: list[str] = []
    for node_id, kind in custom.items():
        def leaf(_node: object, node_id: str = node_id) -> object:
            ticked.append(node_id)
            return bt.NodeStatus.SUCCESS
        if kind == "Action":
            factory.register_simple_action(node_id, leaf)
        elif kind == "Condition":
            factory.register_simple_condition(node_id, leaf)
        else:
            factory.register_simple_decorator(node_id, lambda status, _node: status)
    factory.register_behavior_tree_from_text(ET.tostring(doc, encoding="unicode"))
    tree = factory.create_tree(doc.attrib["main_tree_to_execute"])
    assert tree.tick_while_running() == bt.NodeStatus.SUCCESS
    assert "PutObject" in ticked and "SignalDone" in ticked


def test_each_steps_drive_is_exported_with_its_grid_path(doc: ET.Element) -> None:
    """A step's GoToObject carries the cells and AI2-THOR actions the simulator drives for
    it; walked from its first cell, the moves visit exactly those cells and end facing
    the target from one of its interaction poses."""
    from emboteam.world.navgrid import STEPS, load_grid
    from emboteam.world.navigation import navigator
    from emboteam.world.scene import load_scene

    plan, _ = fridge_handoff()
    grid, nav, scene = load_grid("FloorPlan1"), navigator("FloorPlan1"), load_scene("FloorPlan1")
    trees = _trees(doc)
    drives = 0
    for step in plan.steps:
        if step.action.skill.value != "GoToObject":
            continue
        body = trees[f"Step_{step.id.replace('.', '_')}"]
        (go,) = [el for el in body.iter("GoToObject") if "path" in el.attrib]
        cells = [tuple(map(float, c.split(","))) for c in go.attrib["path"].split(";")]
        here = grid.cell_at(cells[0][:2])
        assert here is not None
        moves = go.attrib["moves"].split()
        # a cell's yaw is the one it is left with: undo the turns made on the first cell
        leading = moves[:moves.index("MoveAhead")] if "MoveAhead" in moves else moves
        turned = sum({"RotateRight": 1, "RotateLeft": -1}.get(m, 0) for m in leading)
        heading = (int(cells[0][2]) // 90 - turned) % 4
        visited = [here]
        for move in moves:
            if move == "MoveAhead":
                here = (here[0] + STEPS[heading][0], here[1] + STEPS[heading][1])
                visited.append(here)
            elif move in ("RotateRight", "RotateLeft"):
                heading = (heading + (1 if move == "RotateRight" else 3)) % 4
            else:
                assert move.startswith("Wait:") and float(move.split(":")[1]) > 0
        assert visited == [grid.cell_at(c[:2]) for c in cells]
        target = scene.get(step.action.target).position
        assert (here, heading) in {(p.cell, p.heading) for p in nav.poses_for((target[0], target[2]))}
        drives += 1
    assert drives >= 1
    model = doc.find("TreeNodesModel")
    assert model is not None
    go_model = next(m for m in model if m.attrib.get("ID") == "GoToObject")
    assert {"path", "moves"} <= {p.attrib["name"] for p in go_model}
