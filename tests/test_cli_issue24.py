"""Issue 24: each promise of docs/cli.md a new user found broken, through the real
``emboteam`` entry point (a subprocess), plus the small functions behind them.

The bad-input sweep is tests/test_cli_probes.py; here are the rows that need a run, a
folder, a signal or a browser to check."""

from __future__ import annotations

import json
import os
import re
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import pytest

from emboteam.bench.runner import _Progress
from emboteam.exec.episode import Episode
from emboteam.pfg.inflection import past_participle
from emboteam.terminal import error_object, one_line, printable, user_message

EMBOTEAM = str(Path(sys.executable).parent / "emboteam")
FP1 = ("--scene", "FloorPlan1", "--robots", "1,2")
RAW_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def cli(*args: str, cwd: Path | None = None, timeout: float = 600,
        env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([EMBOTEAM, *args], capture_output=True, text=True, timeout=timeout, cwd=cwd,
                          env={**os.environ, **(env or {})})


def one_line_err(proc: subprocess.CompletedProcess[str]) -> str:
    lines = [line for line in proc.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, proc.stderr
    assert "Traceback" not in proc.stderr
    return lines[0]


def one_object(proc: subprocess.CompletedProcess[str]) -> dict[str, object]:
    lines = [line for line in proc.stdout.splitlines() if line.strip()]
    assert len(lines) == 1, proc.stdout
    data = json.loads(lines[0])
    assert isinstance(data, dict)
    return data


# ---- Ray: an address that does not answer ------------------------------------------------------

def test_an_unreachable_ray_address_exits_3_with_one_line(tmp_path: Path) -> None:
    pytest.importorskip("ray")
    # a hang (Ray retrying for minutes) fails here through the timeout
    proc = cli("bench", "--suite", "mace-thor", "--executor", "ray", "--ray-address", "127.0.0.1:9",
               "--out", str(tmp_path / "out"), timeout=60)
    assert proc.returncode == 3
    assert "cannot reach the Ray cluster at 127.0.0.1:9" in one_line_err(proc)
    assert not (tmp_path / "out" / "results.sqlite").exists()


# ---- disturbances: refused when they match nothing, "not applicable" where they do not apply --

def test_a_breakdown_of_a_robot_no_team_has_is_refused_up_front(tmp_path: Path) -> None:
    proc = cli("bench", "--suite", "mace-thor", "--breakdown", "robot2@0.3", "--out", str(tmp_path / "o"), "--json")
    assert proc.returncode == 2
    data = one_object(proc)
    assert data["exit_code"] == 2 and "no task of the suite has robot2" in str(data["error"])
    assert not (tmp_path / "o").exists()     # refused before anything was created


def test_a_breakdown_runs_where_it_applies_and_lists_the_rest_as_not_applicable(tmp_path: Path) -> None:
    out = tmp_path / "o"
    proc = cli("bench", "--suite", "mace-thor", "--breakdown", "robot9@0.3", "--out", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    data = one_object(proc)
    skipped = data["not_applicable"]
    assert isinstance(skipped, list) and len(skipped) == 40 and data["n"] == 2     # robot9 is in 2 teams
    assert all("robot9 is not in its team" in line for line in skipped)
    with sqlite3.connect(out / "results.sqlite") as db:
        errors = [e for (e,) in db.execute("SELECT error FROM episodes") if e]
    assert not any("DisturbanceSpecError" in e for e in errors)   # never a failure of its own
    tables = (out / "tables.md").read_text()
    assert "## Not applicable (40 tasks)" in tables and "fp1-toast: --breakdown robot9@0.3" in tables
    assert json.loads((out / "summary.json").read_text())["not_applicable"] == skipped
    rebuilt = cli("report", str(out))           # the store keeps the list for a rebuild
    assert rebuilt.returncode == 0 and "## Not applicable (40 tasks)" in (out / "tables.md").read_text()


def test_the_help_example_of_breakdown_applies_to_the_default_suite() -> None:
    from emboteam.bench.disturbance_scope import split_applicable
    from emboteam.bench.suites import load_suite
    from emboteam.sim.disturbances import Disturbances

    proc = cli("bench", "--help", env={"COLUMNS": "200"})
    examples = re.findall(r"(robot\d+@\d+s)", proc.stdout)
    assert examples, proc.stdout
    for example in examples:
        applicable, _ = split_applicable(Disturbances.parse(breakdown=[example]), load_suite("mace-thor").tasks)
        assert len(applicable) >= 10


# ---- one object in two places -------------------------------------------------------------------

def test_two_places_for_one_object_at_once_is_an_error_naming_both() -> None:
    proc = cli("plan", "put the apple in the fridge and put the apple in the sink", *FP1)
    assert proc.returncode == 2
    line = one_line_err(proc)
    assert "inside(Apple, Fridge)" in line and "inside(Apple, SinkBasin)" in line


def test_a_later_place_said_with_then_wins_with_a_note() -> None:
    data = one_object(cli("plan", "put the apple in the sink, then put it in the fridge", *FP1, "--json"))
    goals = [g for s in data["subtasks"] for g in s["goal"]]            # type: ignore[attr-defined]
    assert goals == ["inside(Apple, Fridge)", "closed(Fridge)"]    # the team closes what it opens
    assert any("later place is kept" in n for n in data["notes"])        # type: ignore[attr-defined]


def test_objects_placed_in_two_places_one_each_still_plan() -> None:
    data = one_object(cli("plan", "put the apple in the fridge and the tomato in the sink", *FP1, "--json"))
    goals = {g for s in data["subtasks"] for g in s["goal"]}            # type: ignore[attr-defined]
    assert goals == {"inside(Apple, Fridge)", "inside(Tomato, SinkBasin)", "closed(Fridge)"}


# ---- one error object, one line --------------------------------------------------------------

def test_run_and_plan_report_a_failure_with_the_same_error_object() -> None:
    args = ("put the piano in the fridge", *FP1, "--json")
    ran, planned = cli("run", *args), cli("plan", *args)
    assert ran.returncode == planned.returncode == 2
    r, p = one_object(ran), one_object(planned)
    assert r["exit_code"] == p["exit_code"] == 2 and r["error_type"] == p["error_type"] == "GroundingError"
    assert r["error"] == p["error"] and not str(r["error"]).startswith("OfflineParseError")
    assert one_line_err(ran) == one_line_err(planned) == f"error: {r['error']}"


def test_llm_retries_reach_stderr_only_with_verbose() -> None:
    spec = "openai:m@http://127.0.0.1:9/v1"
    quiet = cli("plan", "mace-thor/fp1-toast", "--frontend", "llm", "--llm", spec)
    assert quiet.returncode == 3 and "unreachable" in one_line_err(quiet)
    loud = cli("-v", "plan", "mace-thor/fp1-toast", "--frontend", "llm", "--llm", spec)
    assert loud.returncode == 3 and "retrying" in loud.stderr and loud.stderr.count("error: ") == 1


def _smart_llm_suite(folder: Path, *, good: bool, bad: bool, instruction: str = "Put the apple in the fridge") -> Path:
    folder.mkdir()
    if good:
        record = {"task": instruction, "robot list": [1, 2],
                  "object_states": [{"name": "Fridge", "contains": ["Apple"], "state": None}]}
        (folder / "FloorPlan1_good.json").write_text(json.dumps(record) + "\n")
    if bad:
        (folder / "FloorPlan2_bad.json").write_text("{not json\n[1, 2]\n")
    return folder


def test_a_suite_with_malformed_files_sums_them_up_in_one_line(tmp_path: Path) -> None:
    partly = _smart_llm_suite(tmp_path / "partly", good=True, bad=True)
    proc = cli("tasks", "--suite", f"smart-llm:{partly}", "--json")
    assert proc.returncode == 0
    assert len(one_object(proc)["tasks"]) == 1                          # type: ignore[arg-type]
    assert "2 problem(s)" in one_line_err(proc) and "emboteam -v" in proc.stderr
    verbose = cli("-v", "tasks", "--suite", f"smart-llm:{partly}", "--json")
    assert verbose.stderr.count("FloorPlan2_bad.json") >= 2              # each problem, logged
    only_bad = _smart_llm_suite(tmp_path / "bad", good=False, bad=True)
    refused = cli("tasks", "--suite", f"smart-llm:{only_bad}")
    assert refused.returncode == 2 and "no usable task" in one_line_err(refused)


def test_control_characters_of_a_suite_file_are_escaped_in_text_mode(tmp_path: Path) -> None:
    suite = _smart_llm_suite(tmp_path / "s", good=True, bad=False,
                             instruction="Put the apple \x1b[31min the fridge\x1b]0;owned\x07")
    proc = cli("tasks", "--suite", f"smart-llm:{suite}", env={"COLUMNS": "200"})
    assert proc.returncode == 0, proc.stderr
    assert not RAW_CONTROL.search(proc.stdout + proc.stderr)
    assert "\\x1b[31min the fridge" in proc.stdout


# ---- Ctrl-C reaches the workers too: they ignore it, the runner handles it -------------------

def test_sigint_to_bench_workers_does_not_kill_them(tmp_path: Path) -> None:
    out = tmp_path / "o"
    proc = subprocess.Popen([EMBOTEAM, "bench", "--suite", "mace-thor", "--out", str(out), "--workers", "2"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    hit: set[int] = set()
    deadline = time.monotonic() + 180  # a loaded machine (CI beside other work) starts slowly
    while proc.poll() is None and time.monotonic() < deadline:
        for pid in _workers(proc.pid):                 # from their first instant: imports included
            if not hit:
                deadline = time.monotonic() + 20       # then 20 s of Ctrl-C at every worker
            hit.add(pid)
            os.kill(pid, signal.SIGINT)
        time.sleep(0.05)
    _, stderr = proc.communicate(timeout=600)
    assert hit, "no worker was seen"
    assert proc.returncode == 0, stderr
    with sqlite3.connect(out / "results.sqlite") as db:
        died = db.execute("SELECT count(*) FROM episodes WHERE error LIKE 'WorkerDied%'").fetchone()[0]
    assert died == 0 and "KeyboardInterrupt" not in stderr


def _workers(parent: int) -> list[int]:
    """The pool's worker processes of ``parent`` (not the resource tracker)."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
            cmdline = (entry / "cmdline").read_bytes()
        except OSError:
            continue
        ppid = int(stat.rsplit(")", 1)[1].split()[1])
        if ppid == parent and b"spawn_main" in cmdline:
            found.append(int(entry.name))
    return found


# ---- resume -----------------------------------------------------------------------------------

def test_resume_says_what_it_resumes(tmp_path: Path) -> None:
    out = tmp_path / "o"
    args = ("bench", "--suite", "mace-thor", "--breakdown", "robot9@0.3", "--out", str(out))
    assert cli(*args).returncode == 0
    with sqlite3.connect(out / "results.sqlite") as db:
        db.execute("DELETE FROM episodes WHERE key = (SELECT max(key) FROM episodes)")
    proc = cli(*args, "--resume")
    assert proc.returncode == 0, proc.stderr
    assert "resuming 1 of 2 episodes (1 already stored)" in proc.stderr


JOB = SimpleNamespace(key="s/t")


def _episode(wall: float) -> Episode:
    return Episode(task="s/t", instruction="x", floor_plan="FloorPlan1", robots=("robot1",), success=True,
                   wall_seconds=wall)


def test_the_eta_comes_from_the_episodes_this_run_finished() -> None:
    stored = [_episode(500.0)] * 30                     # slow stored episodes do not count
    progress = _Progress(total=40, previous=stored, enabled=False, workers=2)
    assert progress.resuming() == "resuming 10 of 40 episodes (30 already stored)"
    assert progress._eta() == "-"
    progress.finished(job=JOB, episode=_episode(4.0))  # type: ignore[arg-type]
    assert progress._eta() == "0:00:18"                 # 9 left x 4 s / 2 workers
    fresh = _Progress(total=4, previous=[], enabled=False, workers=8)
    assert fresh.resuming() is None
    fresh.finished(job=JOB, episode=_episode(3.0))     # type: ignore[arg-type]
    assert fresh._eta() == "0:00:03"                    # 3 left, never more workers than episodes


# ---- scene at 80 columns --------------------------------------------------------------------

@pytest.mark.parametrize("floor_plan", ["FloorPlan1", "FloorPlan201", "FloorPlan414"])
def test_scene_is_whole_at_80_columns(floor_plan: str) -> None:
    proc = cli("scene", floor_plan, env={"COLUMNS": "80"})
    assert proc.returncode == 0
    lines = proc.stdout.splitlines()
    assert max(len(line) for line in lines) <= 80 and "…" not in proc.stdout
    ids = one_object(cli("scene", floor_plan, "--json"))["objects"]
    for obj in ids:                                         # type: ignore[attr-defined]
        assert re.search(rf"\b{re.escape(obj['id'])}\b", proc.stdout), obj["id"]


# ---- the helpers -------------------------------------------------------------------------------

@pytest.mark.parametrize(("verb", "done"), [
    ("put", "put"), ("chop", "chopped"), ("empty", "emptied"), ("place", "placed"), ("turn on", "turned on"),
    ("open", "opened"), ("fix", "fixed"), ("stay", "stayed"), ("visit", "visited"), ("throw away", "thrown away"),
    ("cut", "cut"), ("mop", "mopped"), ("wash", "washed"), ("make", "made"), ("dry", "dried"),
])
def test_past_participle(verb: str, done: str) -> None:
    assert past_participle(verb) == done


def test_printable_escapes_controls_and_keeps_text() -> None:
    assert printable("a\x1b[31mb\x07\u202ec") == "a\\x1b[31mb\\x07\\u202ec"
    assert printable("put the 🍎 in the fridge [x]") == "put the 🍎 in the fridge [x]"
    assert one_line("a\n\tb\x9b") == "a b\\x9b"


def test_user_message_drops_the_class_name_of_typed_errors_only() -> None:
    # an episode's error was raised in the same process, so its class is loaded: as here
    from emboteam.llm.errors import LLMUnreachable
    from emboteam.pfg.offline.errors import OfflineParseError

    assert OfflineParseError.exit_code == 2 and LLMUnreachable.exit_code == 3
    assert user_message("OfflineParseError: 'piano' names nothing") == "'piano' names nothing"
    assert user_message("LLMUnreachable: [pfg] x is unreachable") == "[pfg] x is unreachable"
    assert user_message("ZeroDivisionError: division by zero") == "ZeroDivisionError: division by zero"
    assert user_message("note: a colon") == "note: a colon"
    assert error_object("a\nb", 3, "LLMTimeout") == {"success": False, "error": "a b", "error_type": "LLMTimeout",
                                                     "exit_code": 3}


# ---- the HTML report, rendered --------------------------------------------------------------

OVERLAPS_JS = """() => {
  const shown = t => t.getAttribute('display') !== 'none' && !t.closest('.axis');
  const texts = [...document.querySelectorAll('#gantt svg text')].filter(shown);
  const box = t => { const b = t.getBoundingClientRect(); return [b.left, b.top, b.right, b.bottom, t.textContent]; };
  const boxes = texts.map(box);
  const overlaps = [];
  for (let i = 0; i < boxes.length; i++) for (let j = i + 1; j < boxes.length; j++) {
    const [a, b] = [boxes[i], boxes[j]];
    if (a[0] < b[2] - 0.5 && b[0] < a[2] - 0.5 && a[1] < b[3] - 0.5 && b[1] < a[3] - 0.5) overlaps.push([a[4], b[4]]);
  }
  const outside = [];
  document.querySelectorAll('#gantt text.bar-label').forEach(t => {
    let r = t.previousElementSibling;
    while (r && !r.classList.contains('bar')) r = r.previousElementSibling;
    if (r && t.getBoundingClientRect().right > r.getBoundingClientRect().right + 0.5) outside.push(t.textContent);
  });
  // blackboard keys (sync flags, locks, other keys); a replan's reason may run longer
  // than two lines: the row's tooltip has it
  const board = ['sync', 'lock', 'other'];
  const keys = [...document.querySelectorAll('#event-list .ev-window .ev-row:not([hidden])')]
    .filter(r => board.includes(r.querySelector('.cat').textContent)).map(r => r.children[3]);
  const cut = keys.filter(k => k.scrollHeight > k.clientHeight + 1 || k.scrollWidth > k.clientWidth + 1)
                  .map(k => k.textContent);
  return {labels: texts.length, overlaps, outside, keys: keys.length, cut};
}"""


@pytest.fixture(scope="module")
def reports(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    """Two episode reports made by the CLI: a run with faults, and a benchmark episode whose
    robot breaks down (a replan and a breakdown marker among short bars: where labels
    used to run into each other)."""
    base = tmp_path_factory.mktemp("reports")
    run = base / "run"
    proc = cli("run", "mace-thor/fp303-clear-floor", "--faults", "0.2", "--seed", "3", "--out", str(run))
    assert proc.returncode in (0, 1), proc.stderr
    suite = base / "suite"
    suite.mkdir()
    record = {"task": "Put a plate, a bowl and a fork on the dining table", "robot list": [17, 25],
              "object_states": [{"name": "DiningTable", "contains": ["Plate", "Bowl", "Fork"], "state": None}]}
    (suite / "FloorPlan15_set.json").write_text(json.dumps(record) + "\n")
    bench = base / "bench"
    proc = cli("bench", "--suite", f"smart-llm:{suite}", "--breakdown", "robot25@0.3", "--out", str(bench))
    assert proc.returncode == 0, proc.stderr
    return [run / "report.html", *sorted(bench.glob("episodes/*/report.html"))]


@pytest.mark.parametrize("width", [1400, 900])
def test_report_labels_do_not_overlap_and_keys_are_whole(reports: list[Path], width: int) -> None:
    playwright = pytest.importorskip("playwright.sync_api")
    chromium = Path("/usr/bin/chromium")
    if not chromium.exists():
        pytest.skip("Debian's chromium package is not installed")
    assert len(reports) == 2
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=str(chromium), args=["--headless", "--no-sandbox", "--disable-gpu"])
        try:
            page = browser.new_page(viewport={"width": width, "height": 900})
            found = []
            for report in reports:
                page.goto(report.resolve().as_uri())
                page.wait_for_load_state("load")
                found.append(page.evaluate(OVERLAPS_JS))
        finally:
            browser.close()
    for one in found:
        assert one["labels"] >= 5 and one["keys"] >= 3, one
        assert one["overlaps"] == [] and one["outside"] == [] and one["cut"] == [], one
