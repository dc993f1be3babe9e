"""The command-line contract of docs/cli.md: one exit-code table for every command, one
line on stderr for every error (ours or click's), one JSON object on stdout with
``--json`` even when the command fails, messages that keep their brackets, a bad ``--out``
as bad input, tables that keep numbers and ids whole at 80 columns, and a benchmark that
says what it saved when interrupted.

Probes that depend on the real entry point (click's own errors, signals, the process
exit) start ``emboteam`` in a subprocess; the rest use typer's in-process runner, since
each CLI start costs about a second."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from rich.console import Console
from typer.testing import CliRunner

import emboteam.cli as cli_module
from emboteam.bench.runner import default_out_dir
from emboteam.bench.tables import render_tables, terminal_tables
from emboteam.cli import app, episode_exit_code
from emboteam.errors import EXIT_CODES
from test_bench_tables import paper_episodes

EMBOTEAM = str(Path(sys.executable).parent / "emboteam")
runner = CliRunner()


def cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([EMBOTEAM, *args], capture_output=True, text=True, timeout=300, cwd=cwd)


def one_line(stderr: str) -> str:
    lines = [line for line in stderr.splitlines() if line.strip()]
    assert len(lines) == 1, stderr
    assert "Traceback" not in stderr and "╭" not in stderr  # no traceback, no click box
    return lines[0]


def one_object(stdout: str) -> dict[str, object]:
    lines = [line for line in stdout.splitlines() if line.strip()]
    assert len(lines) == 1, stdout
    data = json.loads(lines[0])
    assert isinstance(data, dict)
    return data


# ---- through the real entry point ------------------------------------------------------------

@pytest.mark.parametrize(("args", "needle"), [
    (("run", "mace-thor/fp1-toast", "--faults", "2", "--json"), "not a probability"),
    (("run", "mace-thor/fp1-toast", "--faults", "nan"), "nan is not a probability"),
    (("plan", "mace-thor/fp1-toast", "--no-such-option", "--json"), "no such option"),
    (("export-bt",), "missing argument"),
    (("bench", "--suite", "nonsense", "--json"), "unknown suite"),
])
def test_option_and_input_errors_are_one_line_exit_2_and_one_json_object(args: tuple[str, ...],
                                                                         needle: str) -> None:
    proc = cli(*args)
    assert proc.returncode == 2, proc.stderr
    line = one_line(proc.stderr)
    assert line.startswith("error: ") and needle in line.lower()
    if "--json" in args:
        data = one_object(proc.stdout)
        assert data["success"] is False and needle in str(data["error"]).lower() and data["exit_code"] == 2
    else:
        assert proc.stdout == ""


def test_a_run_that_ran_and_failed_exits_1(tmp_path: Path) -> None:
    # every action fails: the episode runs to its end without reaching the goal
    proc = cli("run", "mace-thor/fp1-toast", "--frontend", "oracle", "--faults", "1", "--json")
    assert proc.returncode == 1, proc.stderr
    data = one_object(proc.stdout)
    assert data["success"] is False and int(str(data["actions"])) > 0


def test_a_bad_out_is_bad_input_before_anything_runs(tmp_path: Path) -> None:
    a_file = tmp_path / "taken"
    a_file.write_text("")
    for args, needle in [
        (("run", "mace-thor/fp1-toast", "--frontend", "oracle", "--out", str(a_file)), "existing file"),
        (("export-bt", "mace-thor/fp1-toast", "--out", str(tmp_path / "missing" / "tree.xml")), "does not exist"),
    ]:
        proc = cli(*args)
        assert proc.returncode == 2, proc.stderr
        assert needle in one_line(proc.stderr)
    assert a_file.read_text() == ""


def test_version() -> None:
    proc = cli("--version")
    assert proc.returncode == 0 and re.fullmatch(r"emboteam \S+\n", proc.stdout)


TINY_SUITE = "\n".join(json.dumps({"task": task, "robot list": [1, 2], "object_states": states}) for task, states in [
    ("Put the apple in the fridge", [{"name": "Fridge", "contains": ["Apple"], "state": None}]),
    ("Turn off the light", [{"name": "LightSwitch", "contains": [], "state": "OFF"}]),
    ("Put the tomato in the fridge", [{"name": "Fridge", "contains": ["Tomato"], "state": None}]),
    ("Open the fridge", [{"name": "Fridge", "contains": [], "state": "OPEN"}]),
] * 18) + "\n"
#: episodes in it: enough that a run is still going when the first one is reported (four
#: finished before the interrupt arrived on an idle machine; all 24 of a 24-episode suite
#: once did, in the full suite at load 7, where the test's reader thread waits its turn)
TINY_EPISODES = 72


def _bench(tmp_path: Path, out: Path) -> tuple[subprocess.Popen[str], list[str], threading.Thread]:
    (tmp_path / "suite").mkdir(exist_ok=True)
    (tmp_path / "suite" / "FloorPlan1.json").write_text(TINY_SUITE)
    # a foreground terminal's Ctrl-C: SIGINT handled by default even when pytest itself was
    # started in the background (where the shell ignores SIGINT, and children inherit that)
    proc = subprocess.Popen([EMBOTEAM, "bench", "--suite", f"smart-llm:{tmp_path / 'suite'}", "--frontend", "oracle",
                             "--workers", "1", "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    lines: list[str] = []

    def read() -> None:
        assert proc.stderr is not None
        for line in proc.stderr:
            lines.append(line)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    return proc, lines, reader


def _wait_for_episode(lines: list[str], timeout: float = 120) -> None:
    deadline = time.monotonic() + timeout
    while not any(line.startswith("[1/") for line in lines):
        assert time.monotonic() < deadline, "".join(lines)
        time.sleep(0.05)


def test_ctrl_c_says_what_is_saved_and_how_to_resume(tmp_path: Path) -> None:
    out = tmp_path / "run"
    proc, lines, reader = _bench(tmp_path, out)
    _wait_for_episode(lines)
    os.killpg(proc.pid, signal.SIGINT)  # what Ctrl-C does: the whole foreground group
    proc.wait(timeout=60)
    reader.join(timeout=30)  # stderr ends when every process holding it has ended
    text = "".join(lines)
    # once (CI, 2026-12-07, load 2-5) this run exited 70, an internal error, not reproduced
    # since: the message shows which error it was
    assert proc.returncode == 130, text[-2000:]
    assert "Traceback" not in text and "leaked semaphore" not in text
    last = [line for line in lines if line.strip()][-1]
    m = re.fullmatch(rf"error: interrupted: (\d+) of {TINY_EPISODES} episodes are saved in (\S+); continue with: (.+)\n", last)
    assert m, text
    assert int(m.group(1)) >= 1 and m.group(2) == str(out)
    resume = m.group(3)
    assert resume.startswith("emboteam bench ") and resume.endswith(f"--resume --out {out}")
    # the command it gives continues the run
    done = subprocess.run([EMBOTEAM, *resume.split()[1:], "--json"], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert one_object(done.stdout)["n"] == TINY_EPISODES


_INTERRUPT_WHILE_LOADING = """
import sys

class CtrlC:  # Ctrl-C landing while the CLI's libraries load, as it does in the first second
    def find_spec(self, name, path=None, target=None):
        if name == "emboteam.cli":
            raise KeyboardInterrupt

sys.meta_path.insert(0, CtrlC())
sys.argv = ["emboteam", "tasks", "--suite", "mace-thor", "--json"]
from emboteam.entry import main
main()
"""


def test_ctrl_c_while_the_cli_loads_is_one_line_not_a_traceback() -> None:
    proc = subprocess.run([sys.executable, "-c", _INTERRUPT_WHILE_LOADING], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 130
    assert proc.stderr == "error: interrupted\n"
    assert one_object(proc.stdout) == {"success": False, "error": "interrupted", "error_type": "KeyboardInterrupt",
                                       "exit_code": 130}


def test_sigkill_leaves_no_leaked_semaphore_warning(tmp_path: Path) -> None:
    proc, lines, reader = _bench(tmp_path, tmp_path / "run")
    _wait_for_episode(lines)
    os.kill(proc.pid, signal.SIGKILL)  # the runner only: its workers and resource tracker outlive it
    proc.wait(timeout=60)
    reader.join(timeout=30)  # the tracker warns (if at all) after the workers notice and exit
    assert not reader.is_alive()
    assert "leaked semaphore" not in "".join(lines)


# ---- in process -------------------------------------------------------------------------------

@pytest.mark.parametrize(("args", "needle"), [
    (("run", "mace-thor/fp1-toast", "--llm-merge"), "--llm-merge needs --llm"),
    (("run", "mace-thor/fp1-toast", "--llm-record", "cassette"), "--llm-record needs --llm"),
    (("run", "mace-thor/fp1-toast", "--join", "3@inf"), "--join '3@inf'"),
    (("plan", "mace-thor/fp1-toast", "--schedule", "best"), "--schedule takes fast or optimal"),
    (("run", "open the fridge", "--scene", "1", "--robots", "1,,2"), "empty item"),
    (("export-bt", "mace-thor/fp1-toast", "--format", "btcpp", "--out", "tree.png"), "is an image"),
    (("export-bt", "open the fridge"), "needs --scene FLOORPLAN and --robots LIST"),
    (("plan", "mace-thor/fp1-toast", "--frontend", "llm", "--llm", "openai:x@notaurl"), "must start with http"),
    (("tasks", "--suite", "smart-llm:/no/such/[pfg]/emboteam[ray]"), "/no/such/[pfg]/emboteam[ray]"),
    (("bench", "--suite", "mace-thor", "--out", "taken"), "--out taken is an existing file"),
    (("bench", "--suite", "mace-thor", "--out", "missing/run"), "its parent folder missing does not exist"),
])
def test_bad_input_says_what_is_wrong(args: tuple[str, ...], needle: str, tmp_path: Path,
                                      monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "taken").write_text("")
    result = runner.invoke(app, list(args))
    assert result.exit_code == 2, result.output
    assert needle in one_line(result.stderr)  # brackets survive: messages are not Rich markup
    assert not (tmp_path / "tree.png").exists()


def test_the_exit_code_follows_the_error_that_ended_the_episode() -> None:
    import emboteam.llm.errors  # noqa: F401  (the classes the names refer to)

    assert episode_exit_code(True, None) == 0
    assert episode_exit_code(False, None) == 1  # ran, did not reach the goal
    assert episode_exit_code(False, "robot2 dropped the apple") == 1
    assert episode_exit_code(False, "GroundingError: 'piano' names nothing") == 2
    assert episode_exit_code(False, "LLMUnreachable: [pfg] cannot reach openai:m") == 3
    assert episode_exit_code(False, "LLMTimeout: [pfg] every attempt timed out") == 3
    assert [code for code, _ in EXIT_CODES] == [0, 1, 2, 3, 70, 130]


def test_instruction_brackets_are_printed(monkeypatch: pytest.MonkeyPatch) -> None:
    result = runner.invoke(app, ["plan", "put the apple in the fridge [now]", "--scene", "1", "--robots", "1"])
    assert result.exit_code == 0, result.output
    assert "put the apple in the fridge [now]" in result.stdout


def _at_80_columns(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(cli_module, "out", Console(width=80, highlight=False))


def test_tasks_at_80_columns_keep_every_id_and_instruction_whole(monkeypatch: pytest.MonkeyPatch,
                                                                  tmp_path: Path) -> None:
    _at_80_columns(monkeypatch)
    (tmp_path / "FloorPlan1.json").write_text(TINY_SUITE)
    for suite in ("mace-thor", f"smart-llm:{tmp_path}"):
        result = runner.invoke(app, ["tasks", "--suite", suite])
        assert result.exit_code == 0, result.output
        text = result.stdout
        assert "…" not in text and max(len(line) for line in text.splitlines()) <= 80
        data = json.loads(runner.invoke(app, ["tasks", "--suite", suite, "--json"]).stdout)
        flat = " ".join(re.sub(r"[│┃]", " ", text).split())  # a table's wrapped cells, read down
        for task in data["tasks"]:
            task_id = task["id"].rpartition("/")[2]
            assert re.search(rf"(^|\s){re.escape(task_id)}\s", text), task_id  # on one line, whole
            assert " ".join(task["instruction"].split()) in flat  # every word, in order


def test_bench_tables_at_80_columns_cut_no_number_or_label() -> None:
    markdown = render_tables(paper_episodes())
    console = Console(width=80, record=True, file=open(os.devnull, "w"))  # noqa: SIM115
    for renderable in terminal_tables(markdown, width=80):
        console.print(renderable)
    text = console.export_text()
    assert "…" not in text and max(len(line) for line in text.splitlines()) <= 80
    cells = {c.strip().strip("`") for line in markdown.splitlines() if line.startswith("|")
             for c in line.strip("|").split("|")}
    values = {c for c in cells if c and not set(c) <= set("-:") and " " not in c}
    for value in values:  # every number and one-word label appears whole
        assert re.search(rf"(^|[\s│┃]){re.escape(value)}($|[\s│┃])", text, re.M), value


def test_the_default_bench_folder_is_new_each_run(tmp_path: Path) -> None:
    from emboteam.bench.jobs import BenchConfig

    cfg = BenchConfig(suite="mace-thor", modes=("full", "no-hp"), frontends=("oracle",), fault_levels=(0.0, 0.2),
                      seeds=3)
    first = default_out_dir(cfg, root=tmp_path, now=0)
    assert first.parent == tmp_path
    assert re.fullmatch(r"mace-thor_full\+no-hp_oracle_f0\+0\.2_s3_\d{8}-\d{6}", first.name)
    first.mkdir()
    second = default_out_dir(cfg, root=tmp_path, now=0)
    assert second != first and second.name == first.name + "-2"
    other = default_out_dir(cfg.model_copy(update={"suite": "smart-llm:/data/peers/final_test/"}), root=tmp_path)
    assert other.name.startswith("smart-llm-final-test_full+no-hp_oracle_")  # "_" only between parts


def test_bench_without_out_twice_makes_two_folders(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "suite").mkdir()
    (tmp_path / "suite" / "FloorPlan1.json").write_text(TINY_SUITE.splitlines()[1] + "\n")
    monkeypatch.chdir(tmp_path)
    args = ["bench", "--suite", f"smart-llm:{tmp_path / 'suite'}", "--frontend", "oracle", "--executor", "inline",
            "--json"]
    for _ in range(2):
        result = runner.invoke(app, args)
        assert result.exit_code == 0, result.output
    runs = sorted(p for p in (tmp_path / "bench-out").iterdir() if (p / "results.sqlite").is_file())
    assert len(runs) == 2
    # --out stays strict, and --resume must name the run it continues
    assert runner.invoke(app, [*args, "--out", str(runs[0])]).exit_code == 2
    result = runner.invoke(app, [*args, "--resume"])
    assert result.exit_code == 2 and "--resume needs --out DIR" in result.stderr


def test_a_refused_executor_leaves_no_results_store(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import emboteam.bench.runner as runner_module
    from emboteam.bench.jobs import BenchConfigError, expand_jobs
    from emboteam.bench.runner import run_bench, store_path
    from test_bench_runner import config, make_task

    def refuse(*_: object) -> None:
        raise BenchConfigError("cannot start a local Ray instance: no")

    monkeypatch.setattr(runner_module, "make_executor", refuse)
    cfg = config(tmp_path / "run")
    with pytest.raises(BenchConfigError, match="cannot start"):
        run_bench(cfg, expand_jobs(cfg, [make_task("t1")]), "test_bench_runner:scripted_episode", progress=False)
    assert not store_path(tmp_path / "run").exists()


def test_an_unplanned_plan_does_not_claim_a_makespan() -> None:
    # no-pfg-hp executes the action lists as written: nothing was planned or scheduled
    result = runner.invoke(app, ["run", "mace-thor/fp1-toast", "--mode", "no-pfg-hp"])
    assert result.exit_code in (0, 1), result.output
    assert "actions as written, not planned: no Fast Downward call" in " ".join(result.stdout.split())
    assert "makespan 0.0 s" not in result.stdout


def test_a_bug_is_exit_70_in_one_line_and_one_json_object(monkeypatch: pytest.MonkeyPatch) -> None:
    def broken() -> list[str]:
        raise RuntimeError("index [3] out of range")

    monkeypatch.delenv("EMBOTEAM_DEBUG", raising=False)
    monkeypatch.setattr(cli_module, "scene_ids", broken)
    result = runner.invoke(app, ["scenes", "--json"])
    assert result.exit_code == 70
    line = one_line(result.stderr)
    assert line.startswith("internal error: RuntimeError: index [3] out of range") and "EMBOTEAM_DEBUG=1" in line
    data = one_object(result.stdout)
    assert data["success"] is False and data["exit_code"] == 70


def test_abort_is_caught_with_the_click_that_typer_uses() -> None:
    # typer releases that ship their own click have no Abort in its exceptions module: the
    # handler must still name a class (it raised AttributeError on a broken pipe)
    from emboteam.cli import _abort_class, _click_exceptions

    abort = _abort_class(_click_exceptions())
    assert issubclass(abort, BaseException)
    import typer.exceptions
    assert abort in (typer.exceptions.Abort, getattr(_click_exceptions(), "Abort", None))
