"""The episode report without a browser: the view it computes from a trace, the page it
writes, and the typed errors for directories it cannot read."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from emboteam.errors import EmboTeamError
from emboteam.exec.episode import Episode
from emboteam.exec.trace import TraceEvent
from emboteam.report import ReportError, episode_view, render_episode_report, write_episode_report
from emboteam.report.behavior_tree import tree_from_plan, tree_from_trace
from emboteam.report.floor_map import CONTENT_MARGIN, floor_map
from emboteam.report.page import json_for_script
from emboteam.report.timeline import build_timeline, classify_key, normalize_status, parse_action
from emboteam.world.scene import load_scene
from test_report_fixtures import fridge_plan, scripted_fridge_episode

EMBEDDED = re.compile(r'<script type="application/json" id="episode-data">(.*?)</script>', re.S)


@pytest.fixture(scope="module")
def episode() -> Episode:
    return scripted_fridge_episode()


def embedded_data(html: str) -> Any:
    m = EMBEDDED.search(html)
    assert m is not None, "the page embeds its data as application/json"
    return json.loads(m.group(1))


# ---- embedding ---------------------------------------------------------------------------

@pytest.mark.parametrize("text", ["</script><script>alert(1)</script>", "</SCRIPT >", "<!--", "a & b > c",
                                  "line\u2028separator\u2029", "ünïcødé “quotes”"])
def test_json_for_script_cannot_end_the_element_and_round_trips(text: str) -> None:
    encoded = json_for_script({"instruction": text})
    assert "<" not in encoded and ">" not in encoded and "\u2028" not in encoded
    assert json.loads(encoded) == {"instruction": text}


@given(st.recursive(st.text() | st.integers() | st.booleans() | st.none(),
                    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(), inner, max_size=4),
                    max_leaves=12))
def test_any_json_value_survives_embedding(value: Any) -> None:
    encoded = json_for_script(value)
    assert "</" not in encoded and "<!--" not in encoded
    assert json.loads(encoded) == value


def test_hostile_text_in_an_episode_stays_data(episode: Episode, tmp_path: Path) -> None:
    evil = 'Put </script><script>alert("x")</script> the apple <img src=x onerror=alert(1)>'
    ep = episode.model_copy(update={"instruction": evil, "error": "</script>"})
    html = render_episode_report(ep)
    # exactly the page's own two script elements close
    assert html.lower().count("</script>") == 2
    assert "<img" not in html
    data = embedded_data(html)
    assert data["meta"]["instruction"] == evil and data["meta"]["error"] == "</script>"


# ---- the page on disk ----------------------------------------------------------------------

def test_write_episode_report_is_one_self_contained_file(episode: Episode, tmp_path: Path) -> None:
    episode.save(tmp_path)
    out = write_episode_report(tmp_path)
    assert out == tmp_path / "report.html"
    html = out.read_text(encoding="utf-8")
    # nothing to fetch: no external scripts, styles, images or fonts
    assert not re.search(r"<script[^>]+src=", html, re.I)
    assert not re.search(r"<link[^>]+stylesheet", html, re.I)
    assert not re.search(r"(src|href)\s*=\s*[\"'](https?:)?//", html, re.I)
    assert "@import" not in html and "url(http" not in html
    assert "default-src 'none'" in html  # the CSP forbids fetches even if a bug tried one
    data = embedded_data(html)
    assert data["meta"]["task"] == episode.task
    assert data["metrics"]["success"] == episode.success


def test_view_has_one_bar_per_executed_action_and_a_track_per_robot(episode: Episode) -> None:
    view = episode_view(episode)
    tl = view["timeline"]
    assert tl["robots"] == list(episode.robots)
    assert len(tl["actions"]) == episode.actions
    failed = [a for a in tl["actions"] if a["outcome"] == "failed"]
    assert len(failed) == episode.failed_actions and all(a["reason"] for a in failed)
    assert any(a["recovery"] for a in tl["actions"])
    for robot in episode.robots:
        track = tl["poses"][robot]
        assert len(track["t"]) > 5 and track["t"] == sorted(track["t"])
    assert tl["end"] == pytest.approx(episode.makespan, abs=1e-6)
    # every plan sync point is in the view, and the colours are distinct per robot
    assert len(view["plan"]["sync"]) == len(fridge_plan().sync)
    assert len(set(view["colors"].values())) == len(episode.robots)


def test_objects_picked_and_put_move_on_the_map(episode: Episode) -> None:
    moves = episode_view(episode)["timeline"]["moves"]
    apple = [m for m in moves if m["object"] == "Apple_1"]
    assert [bool(m["robot"]) for m in apple] == [True, False]
    assert apple[0]["robot"] == "robot1" and apple[1]["at"] == "Fridge_1"
    assert apple[0]["t"] < apple[1]["t"]


def test_an_episode_that_failed_before_acting_still_renders(tmp_path: Path) -> None:
    ep = Episode(task="mace-thor/x", instruction="slice the bread", floor_plan="FloorPlan1",
                 robots=("robot1", "robot2"), error="PlannerTimeout: Fast Downward ran out of time")
    ep.save(tmp_path)
    view = embedded_data(write_episode_report(tmp_path).read_text())
    assert view["meta"]["error"].startswith("PlannerTimeout")
    assert view["tree"]["source"] == "none" and view["timeline"]["actions"] == []
    scene = load_scene(1)
    # the team is drawn at its start poses
    assert view["timeline"]["poses"]["robot2"]["x"] == [scene.robot_start(1)[0]]


def test_an_unknown_floor_plan_gives_a_report_without_a_map(episode: Episode) -> None:
    view = episode_view(episode.model_copy(update={"floor_plan": "FloorPlan999"}))
    assert view["map"] is None and "FloorPlan999" in view["map_note"]
    assert len(view["timeline"]["actions"]) == episode.actions


# ---- trace interpretation ------------------------------------------------------------------

def test_parse_action_accepts_text_and_structured_actions() -> None:
    assert parse_action("PutObject(Apple_1, Fridge_1)") == ("PutObject(Apple_1, Fridge_1)", "PutObject",
                                                            ("Apple_1", "Fridge_1"))
    assert parse_action({"skill": "OpenObject", "target": "Fridge_1"}) == ("OpenObject(Fridge_1)", "OpenObject",
                                                                           ("Fridge_1",))
    assert parse_action(None)[1] == "?"


def test_blackboard_keys_are_classified_for_the_filter() -> None:
    # the compiler's keys (btc/keys.py) and the fixture's
    assert classify_key("done_robot1_3") == "sync" and classify_key("done/robot1.3") == "sync"
    assert classify_key("lock_Fridge_1") == "lock" and classify_key("lock/Fridge_1") == "lock"
    assert classify_key("failed_robot2") == "blackboard"
    assert normalize_status("Status.SUCCESS") == normalize_status("SUCCESS") == "success"


def test_actions_pair_per_robot_and_unfinished_ones_are_kept() -> None:
    ev = [
        TraceEvent(t=0.0, kind="action_start", robot="r1", data={"action": "GoToObject(Apple_1)", "step": "r1.1"}),
        TraceEvent(t=0.5, kind="action_start", robot="r2", data={"action": "OpenObject(Fridge_1)"}),
        TraceEvent(t=2.0, kind="action_end", robot="r2", data={"success": False, "reason": "spot_busy"}),
        TraceEvent(t=3.0, kind="action_end", robot="r1", data={"success": True}),
        TraceEvent(t=3.0, kind="action_start", robot="r1", data={"action": "PickupObject(Apple_1)"}),
    ]
    tl = build_timeline(ev, ["r1", "r2"], makespan=4.0)
    got = [(a.robot, a.skill, a.start, a.end, a.outcome, a.reason) for a in tl.actions]
    assert got == [("r1", "GoToObject", 0.0, 3.0, "success", None),
                   ("r2", "OpenObject", 0.5, 2.0, "failed", "spot_busy"),
                   ("r1", "PickupObject", 3.0, 4.0, "unfinished", None)]
    assert tl.end == 4.0


def test_recovery_and_replan_events_are_logged() -> None:
    ev = [TraceEvent(t=1.0, kind="recovery", robot="r1",
                     data={"step": "r1.2", "strategy": "reapproach", "why": "Fridge_1 not visible"}),
          TraceEvent(t=2.0, kind="replan", data={"reason": "r2: gave up", "unmet": ["closed(Fridge)"]})]
    tl = build_timeline(ev, ["r1"])
    assert [(e.category, e.key) for e in tl.events] == [("recovery", "reapproach"), ("replan", "r2: gave up")]
    assert "r1.2" in tl.events[0].value and "closed(Fridge)" in tl.events[1].value


# ---- behavior tree -------------------------------------------------------------------------

def test_tree_from_node_events_puts_parents_first_and_keeps_status_changes(episode: Episode) -> None:
    tl = build_timeline(episode.trace, episode.robots)
    tree = tree_from_trace(tl.nodes, episode.robots, episode.plan)
    seen: set[int] = set()
    for n in tree.nodes:
        assert n.parent is None or n.parent in seen
        seen.add(n.id)
        times = [t for t, _ in n.changes]
        assert times == sorted(times)
        assert all(a[1] != b[1] for a, b in zip(n.changes, n.changes[1:], strict=False))
    steps = [n for n in tree.nodes if n.kind == "step"]
    assert len(steps) == len(fridge_plan().steps)
    waits = next(n for n in steps if n.name.startswith("robot2.4 "))
    assert "waits for robot1.2" in waits.note
    # all steps ended in success in this run
    assert all(n.changes[-1][1] == "success" for n in steps)


def test_tree_from_plan_derives_statuses_from_actions(episode: Episode) -> None:
    tl = build_timeline(episode.trace, episode.robots)
    plan = fridge_plan()
    tree = tree_from_plan(plan, tl.actions, episode.success, tl.end)
    assert tree.source == "plan"
    assert [n.name for n in tree.nodes if n.kind == "robot"] == list(plan.robots)
    steps = {n.name.split()[0]: n for n in tree.nodes if n.kind == "step"}
    assert set(steps) == {s.id for s in plan.steps}
    first = next(a for a in tl.actions if a.step == "robot2.4")
    assert steps["robot2.4"].changes[0] == (first.start, "running")
    assert steps["robot2.4"].changes[-1][1] == "success"
    recovered = {a.step for a in tl.actions if a.recovery}
    recover_nodes = [n for n in tree.nodes if n.kind == "recover" and n.changes]
    assert len(recover_nodes) == len(recovered)


# ---- map -----------------------------------------------------------------------------------

def test_floor_map_footprints_cover_their_contents_and_the_room_holds_everything() -> None:
    scene = load_scene(1)
    fmap = floor_map(scene, {"Fridge_1", "Apple_1"}, [scene.robot_start(2)])
    by_id = {o.id: o for o in fmap.objects}
    for o in scene.objects:
        if o.type == "Floor":
            assert o.id not in by_id
            continue
        x, z = o.position[0], o.position[2]
        assert fmap.min_x < x < fmap.max_x and fmap.min_z < z < fmap.max_z
        parent = by_id.get(o.parent or "")
        if parent is not None and parent.kind in ("furniture", "appliance"):
            assert abs(x - parent.x) <= parent.w / 2 + 1e-6 and abs(z - parent.z) <= parent.d / 2 + 1e-6, o.id
    assert by_id["Fridge_1"].kind == "appliance" and by_id["Apple_1"].kind == "item"
    assert by_id["CounterTop_2"].kind == "furniture" and by_id["LightSwitch_1"].kind == "fixture"
    assert {o.id for o in fmap.objects if o.highlight} == {"Fridge_1", "Apple_1"}
    assert CONTENT_MARGIN > 0


# ---- errors --------------------------------------------------------------------------------

def test_directory_problems_are_typed_errors_naming_the_file(episode: Episode, tmp_path: Path) -> None:
    with pytest.raises(ReportError, match="is not a directory"):
        write_episode_report(tmp_path / "missing")
    with pytest.raises(ReportError, match=r"no episode\.json"):
        write_episode_report(tmp_path)
    episode.save(tmp_path)
    trace = tmp_path / "trace.jsonl"
    lines = trace.read_text().splitlines()
    trace.write_text("\n".join([*lines[:3], "{not json", *lines[3:]]))
    with pytest.raises(ReportError, match=r"trace.jsonl:4: not JSON"):
        write_episode_report(tmp_path)
    trace.write_text('{"t": 1, "kind": "teleport"}\n')
    with pytest.raises(ReportError, match=r"trace.jsonl:1: not a trace event: kind"):
        write_episode_report(tmp_path)
    trace.unlink()
    (tmp_path / "episode.json").write_text('{"task": "x"}')
    with pytest.raises(ReportError, match="not an episode"):
        write_episode_report(tmp_path)
    (tmp_path / "episode.json").write_text("[1, 2]")
    with pytest.raises(ReportError, match="expected a JSON object"):
        write_episode_report(tmp_path)
    assert issubclass(ReportError, EmboTeamError)


def test_the_front_ends_notes_are_in_the_page(episode: Episode) -> None:
    """What the parser could not read reaches the report's reader (the page shows
    ``meta.notes`` above the metrics)."""
    noted = episode.model_copy(update={"notes": ("unread 'frobnicator': names nothing",)})
    assert episode_view(noted)["meta"]["notes"] == ["unread 'frobnicator': names nothing"]
    assert embedded_data(render_episode_report(noted))["meta"]["notes"] == [
        "unread 'frobnicator': names nothing"]
    assert episode_view(episode)["meta"]["notes"] == []
