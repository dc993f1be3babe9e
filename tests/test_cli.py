"""The command-line contract of docs/cli.md, through the installed ``emboteam`` script:
``--json`` prints exactly one JSON object on stdout, bad input exits non-zero with one
line on stderr and no traceback."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

EMBOTEAM = shutil.which("emboteam") or str(Path(sys.executable).parent / "emboteam")


def cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([EMBOTEAM, *args], capture_output=True, text=True, timeout=600, cwd=cwd)


def one_json(proc: subprocess.CompletedProcess[str], code: int = 0) -> dict[str, object]:
    assert proc.returncode == code, proc.stderr
    lines = [line for line in proc.stdout.splitlines() if line.strip()]
    assert len(lines) == 1, proc.stdout  # exactly one object, nothing else on stdout
    data = json.loads(lines[0])
    assert isinstance(data, dict)
    return data


def test_scenes_lists_all_120_floor_plans() -> None:
    data = one_json(cli("scenes", "--json"))
    scenes = data["scenes"]
    assert isinstance(scenes, list) and len(scenes) == 120
    ids = {s["id"] for s in scenes}
    assert {"FloorPlan1", "FloorPlan6", "FloorPlan15", "FloorPlan21", "FloorPlan201", "FloorPlan209",
            "FloorPlan303", "FloorPlan414"} <= ids
    assert {s["room"] for s in scenes} == {"kitchen", "living_room", "bedroom", "bathroom"}


def test_python_dash_m_runs_the_same_command_line() -> None:
    proc = subprocess.run([sys.executable, "-m", "emboteam", "scenes", "--json"], capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert len(json.loads(proc.stdout)["scenes"]) == 120
    bad = subprocess.run([sys.executable, "-m", "emboteam", "run", "--frobnicate"], capture_output=True, text=True,
                         timeout=600)
    assert bad.returncode == 2 and len(bad.stderr.strip().splitlines()) == 1


def test_tasks_lists_the_suite() -> None:
    data = one_json(cli("tasks", "--suite", "mace-thor", "--json"))
    tasks = data["tasks"]
    assert isinstance(tasks, list) and len(tasks) == 42
    assert set(tasks[0]) >= {"id", "scene", "category", "instruction"}


def test_run_json_has_the_documented_fields_and_writes_a_report(tmp_path: Path) -> None:
    out = tmp_path / "run"
    data = one_json(cli("run", "mace-thor/fp1-fridge-apple-tomato", "--frontend", "oracle",
                        "--faults", "0.2", "--seed", "1", "--out", str(out), "--json"))
    assert set(data) == {"task", "success", "gcr", "exec", "makespan", "actions", "llm_calls", "tokens",
                         "plan_seconds", "error", "notes", "unexplained", "candidates", "not_attempted", "clarification"}
    assert data["success"] is True and data["llm_calls"] == 0 and data["notes"] == [] and data["clarification"] is None
    assert (out / "episode.json").exists() and (out / "trace.jsonl").exists()
    assert (out / "report.html").read_text().startswith("<!DOCTYPE html>")


def test_run_an_instruction_offline_in_plain_text() -> None:
    proc = cli("run", "switch off the light and open the fridge", "--scene", "FloorPlan1", "--robots", "1,2")
    assert proc.returncode == 0, proc.stderr
    assert "SUCCESS" in proc.stdout and "switched_off(LightSwitch)" in proc.stdout


def test_plan_json_has_subtasks_robots_sync_and_timing() -> None:
    data = one_json(cli("plan", "mace-thor/fp1-fridge-apple-tomato", "--frontend", "oracle", "--json"))
    assert {"subtasks", "robots", "sync", "makespan", "plan_seconds"} <= set(data)
    assert data["sync"], "a temporal task has cross-robot sync points"


def test_what_the_parser_could_not_read_reaches_the_user_as_notes() -> None:
    instruction = "Put the apple in the frobnicator and the tomato in the fridge."
    data = one_json(cli("plan", instruction, "--scene", "FloorPlan1", "--robots", "1,2", "--json"))
    # the team closes the fridge it opens (pfg/close_after_use.py), and says so
    assert [str(c) for s in data["subtasks"] for c in s["goal"]] == ["inside(Tomato, Fridge)", "closed(Fridge)"]
    assert len(data["notes"]) == 2 and "frobnicator" in data["notes"][0] and "closed(Fridge)" in data["notes"][1]
    run = one_json(cli("run", instruction, "--scene", "FloorPlan1", "--robots", "1,2", "--json"))
    assert run["success"] is True and run["notes"] == data["notes"]
    panel = cli("run", instruction, "--scene", "FloorPlan1", "--robots", "1,2")
    assert panel.returncode == 0 and "note: unread 'frobnicator'" in panel.stdout


def test_export_bt_btcpp_is_behaviortree_cpp_v4_xml() -> None:
    proc = cli("export-bt", "mace-thor/fp1-fridge-apple-tomato", "--frontend", "oracle", "--format", "btcpp")
    assert proc.returncode == 0, proc.stderr
    root = ET.fromstring(proc.stdout)
    assert root.tag == "root" and root.get("BTCPP_format") == "4"
    assert root.find("TreeNodesModel") is not None
    assert root.find(".//Parallel") is not None


@pytest.mark.parametrize("args, needle", [
    (("scene", "FloorPlan999"), "unknown floor plan"),
    (("run", "mace-thor/no-such-task"), "no task"),
    (("run", "put the apple in the fridge", "--scene", "FloorPlan1"), "--robots"),
    (("run", "put the apple in the fridge", "--scene", "1", "--robots", "99"), "robot profile 99"),
    (("tasks", "--suite", "nonsense"), "unknown suite"),
    (("run", "mace-thor/fp1-toast", "--frontend", "llm"), "--llm"),
    (("run", "mace-thor/fp1-toast", "--frontend", "llm", "--llm", "nosuchprovider:x"), "provider"),
])
def test_bad_input_is_one_line_and_a_non_zero_exit(args: tuple[str, ...], needle: str) -> None:
    proc = cli(*args)
    assert proc.returncode != 0
    assert "Traceback" not in proc.stderr
    lines = [line for line in proc.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, proc.stderr
    assert needle.lower() in proc.stderr.lower()
    assert proc.stdout == ""


def test_a_task_that_cannot_be_understood_is_bad_input_with_success_false() -> None:
    # exit 2 (bad input), as plan and export-bt exit on the same instruction; docs/cli.md
    proc = cli("run", "put the piano in the fridge", "--scene", "1", "--robots", "1", "--json")
    data = one_json(proc, 2)
    assert data["success"] is False and "piano" in str(data["error"])
    (line,) = proc.stderr.splitlines()
    # the message as plan prints it, without the class name (docs/cli.md, issue 24)
    assert line == f"error: {data['error']}" and not line.startswith("error: GroundingError") and "piano" in line
    assert data["exit_code"] == 2
