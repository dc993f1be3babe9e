"""Bad input through the real ``emboteam`` entry point: options, tasks, instructions, suites,
files, LLM specs pointing at closed loopback ports, resume folders, control characters,
unicode, empty strings and huge numbers (issue 24, docs/cli.md).

Every probe must keep the command-line contract: the documented exit code, exactly one
line on stderr, no traceback, no raw control character on stdout or stderr, and with
``--json`` exactly one JSON object on stdout carrying ``error`` and ``exit_code``.

Each probe is a process (0.3-1.2 s of CPU, mostly imports), so the probes run in a small
thread pool once per module and each test only reads its result. The file takes about
90 s of CPU in all (81 s user + 7 s system measured on 2026-12-06, 2 cores at load ~16,
5 min 51 s wall). The probes are chosen to fail before any episode or benchmark runs,
except the LLM probes, which wait out the client's retries (a few seconds each, idle).
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import pytest

EMBOTEAM = str(Path(sys.executable).parent / "emboteam")
CLOSED = "http://127.0.0.1:9/v1"   # the discard port: nothing listens on loopback
FP1 = ("--scene", "FloorPlan1", "--robots", "1,2")
#: C0 controls but newline and tab, DEL and C1 controls: what must never reach a terminal raw
RAW_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f]")


@dataclass(frozen=True)
class Probe:
    args: tuple[str, ...]
    code: int
    needle: str = ""          # a word the one-line message must hold (lower case)
    absent: str = ""          # a word it must not hold

    @property
    def id(self) -> str:
        text = " ".join(self.args)
        return RAW_CONTROL.sub("^", text)[:70]


def P(*args: str, code: int = 2, needle: str = "", absent: str = "") -> Probe:
    return Probe(tuple(args), code, needle, absent)


PROBES: list[Probe] = [
    # ---- options ---------------------------------------------------------------------------
    P("run", "--frobnicate", needle="no such option"),
    P("run", "--frobnicate", "--json", needle="no such option"),
    P("frobnicate", needle="no such command"),
    P("plan", needle="missing argument"),
    P("bench", "--json", needle="missing option"),
    P("run", "mace-thor/fp1-toast", "--faults", "2", "--json", needle="not a probability"),
    P("run", "mace-thor/fp1-toast", "--faults", "nan", needle="not a probability"),
    P("run", "mace-thor/fp1-toast", "--faults", "-0.1", needle="not a probability"),
    P("run", "mace-thor/fp1-toast", "--faults", "inf", "--json", needle="not a probability"),
    P("run", "mace-thor/fp1-toast", "--seed", "abc", needle="seed"),
    P("run", "mace-thor/fp1-toast", "--mode", "nonsense", needle="unknown mode"),
    P("run", "mace-thor/fp1-toast", "--frontend", "nonsense", "--json", needle="unknown front end"),
    P("run", "mace-thor/fp1-toast", "--env", "mars", needle="unknown environment"),
    P("run", "mace-thor/fp1-toast", "--planner-input", "xml", needle="--planner-input"),
    P("run", "mace-thor/fp1-toast", "--planner-input", "", needle="--planner-input"),
    P("run", "mace-thor/fp1-toast", "--llm-merge", needle="--llm-merge needs --llm"),
    P("run", "mace-thor/fp1-toast", "--llm-record", "/tmp/x", needle="--llm-record needs --llm"),
    P("run", "mace-thor/fp1-toast", "--join", "3@inf", needle="join"),
    P("run", "mace-thor/fp1-toast", "--join", "99@3", needle="99"),
    P("run", "mace-thor/fp1-toast", "--join", "garbage", "--json", needle="join"),
    P("export-bt", "mace-thor/fp1-toast", "--format", "yaml", needle="unknown format"),
    P("export-bt", "mace-thor/fp1-toast", "--out", "{tmp}/tree.png", needle="image"),
    P("export-bt", "mace-thor/fp1-toast", "--out", "/nonexistent/tree.xml", needle="does not exist"),
    P("export-bt", "open the fridge", needle="--scene"),
    P("bench", "--suite", "mace-thor", "--seeds", "0", "--json", needle="seeds"),
    P("bench", "--suite", "mace-thor", "--workers", "0", needle="workers"),
    P("bench", "--suite", "mace-thor", "--faults", "0,abc", needle="abc"),
    P("bench", "--suite", "mace-thor", "--ablation", "nonsense", needle="nonsense"),
    P("bench", "--suite", "mace-thor", "--baseline", "nonsense", needle="nonsense"),
    P("bench", "--suite", "mace-thor", "--executor", "nonsense", needle="executor"),
    P("bench", "--suite", "mace-thor", "--msg-loss", "2", needle="msg-loss"),
    P("bench", "--suite", "mace-thor", "--msg-delay", "-1", needle="msg-delay"),
    P("bench", "--suite", "mace-thor", "--llm-merge", needle="no such option"),
    # ---- tasks and suites -----------------------------------------------------------------
    P("run", "nonsense", needle="suite/id"),
    P("run", "mace-thor/nope", "--json", needle="no task"),
    P("run", "nosuite/fp1", needle="unknown suite"),
    P("run", "fp1-toast", needle="did you mean mace-thor/fp1-toast"),
    P("run", "", needle="suite/id"),
    P("run", "   ", needle="suite/id"),
    P("run", "mace-thor/ünïcödé-✓", needle="no task"),
    P("run", "mace-thor/fp1\x1b[31m", needle="no task"),
    P("tasks", "--suite", "nonsense", "--json", needle="unknown suite"),
    P("tasks", "--suite", "smart-llm:", needle="needs a path"),
    P("tasks", "--suite", "smart-llm:/nonexistent", needle="does not exist"),
    P("tasks", "--suite", "smart-llm:{bad_suite}", needle="no usable task"),
    P("bench", "--suite", "smart-llm:{bad_suite}", "--json", needle="no usable task"),
    P("scene", "FloorPlan999", needle="floorplan999"),
    P("scene", "", "--json"),
    P("scene", "\x1b]0;pwned\x07"),
    P("scene", "99999999999999999999999999"),
    # ---- instructions ---------------------------------------------------------------------
    P("run", "put the piano in the fridge", *FP1, "--json", needle="piano", absent="closest"),
    P("plan", "put the apple in the fridge and put the apple in the sink", *FP1, needle="fridge"),
    P("plan", "open and close the fridge", *FP1, "--json", needle="at once"),
    P("run", "put the 🍎 in the fridge", *FP1, needle="what should be put?"),
    P("run", "put the \x1b[31mapple in the fridge", *FP1, needle="control characters"),
    P("plan", "put the \u202eapple in the fridge", *FP1, "--json", needle="control characters"),
    P("plan", "put the apple in the fridge", "--scene", "FloorPlan1", needle="--robots"),
    P("plan", "put the apple in the fridge", "--scene", "FloorPlan999", "--robots", "1"),
    P("plan", "put the apple in the fridge", "--scene", "FloorPlan1", "--robots", "1,,2", needle="empty item"),
    P("plan", "put the apple in the fridge", "--scene", "FloorPlan1", "--robots", "99", needle="99"),
    P("plan", "put the apple in the fridge", "--scene", "FloorPlan1", "--robots", "", "--json"),
    P("plan", "x " * 3000, *FP1, needle="too long"),
    P("plan", "", *FP1, needle="empty"),
    P("plan", "dance", *FP1, "--json", needle="no action"),
    P("plan", "put the fridge in the mug", *FP1, needle="fridge", absent="closest"),
    P("plan", "fill the bathtub", *FP1, needle="no bathtub", absent="closest"),
    P("plan", "put the toilet paper away", *FP1, needle="no toilet paper"),
    P("plan", "put the apple in the fridge", *FP1, "--frontend", "llm", needle="--llm"),
    # ---- LLM specs ------------------------------------------------------------------------
    P("plan", "mace-thor/fp1-toast", "--frontend", "llm", "--llm", f"openai:m@{CLOSED}", code=3,
      needle="unreachable"),
    P("run", "mace-thor/fp1-toast", "--frontend", "llm", "--llm", f"openai:m@{CLOSED}", "--json", code=3,
      needle="unreachable"),
    P("plan", "mace-thor/fp1-toast", "--llm", "openai:m@notaurl", needle="http"),
    P("plan", "mace-thor/fp1-toast", "--llm", "nonsense"),
    P("plan", "mace-thor/fp1-toast", "--llm", "llamacpp:/nonexistent.gguf", "--json"),
    P("plan", "mace-thor/fp1-toast", "--llm", "replay:/nonexistent"),
    # ---- files, reports, resume folders ---------------------------------------------------
    P("report", "/nonexistent", needle="does not exist"),
    P("report", "{file}", needle="not a folder"),
    P("report", "{empty}"),
    P("bench", "--suite", "mace-thor", "--resume", needle="--resume needs --out"),
    P("bench", "--suite", "mace-thor", "--resume", "--out", "{tmp}/never-ran", needle="nothing to resume"),
    P("bench", "--suite", "mace-thor", "--resume", "--out", "{empty}", "--json", needle="nothing to resume"),
    P("bench", "--suite", "mace-thor", "--out", "{file}", needle="existing file"),
    P("bench", "--suite", "mace-thor", "--out", "/nonexistent/a/b", needle="does not exist"),
    P("run", "mace-thor/fp1-toast", "--out", "/nonexistent/a/b", "--json", needle="does not exist"),
    # ---- benchmark disturbances and executors ---------------------------------------------
    P("bench", "--suite", "mace-thor", "--breakdown", "robot2@0.3", needle="no task"),
    P("bench", "--suite", "mace-thor", "--breakdown", "robot3@12s", "--json", needle="no task"),
    P("bench", "--suite", "mace-thor", "--moves", "Nothing_1@0.5", needle="no floor plan"),
    P("bench", "--suite", "mace-thor", "--breakdown", "robot99@0.3", needle="unknown robot"),
    P("bench", "--suite", "mace-thor", "--breakdown", "random@2", needle="past the end"),
    P("bench", "--suite", "mace-thor", "--breakdown", "random", needle="who@when"),
    P("bench", "--suite", "mace-thor", "--executor", "ray", "--ray-address", "127.0.0.1:9", "--out",
      "{tmp}/ray", "--json", code=3, needle="cannot reach the ray cluster"),
]


def _fill(arg: str, places: dict[str, str]) -> str:
    for key, value in places.items():
        arg = arg.replace("{" + key + "}", value)
    return arg


@pytest.fixture(scope="module")
def results(tmp_path_factory: pytest.TempPathFactory) -> dict[str, subprocess.CompletedProcess[str]]:
    tmp = tmp_path_factory.mktemp("probes")
    bad = tmp / "bad-suite"
    bad.mkdir()
    (bad / "FloorPlan1_bad.json").write_text("{not json\n")
    (bad / "FloorPlan2_list.json").write_text("[1, 2]\n")
    (tmp / "empty").mkdir()
    (tmp / "a-file").write_text("not a folder\n")
    places = {"tmp": str(tmp), "bad_suite": str(bad), "empty": str(tmp / "empty"), "file": str(tmp / "a-file")}
    env = {**os.environ, "COLUMNS": "80", "TERM": "xterm-256color"}

    def one(probe: Probe) -> tuple[str, subprocess.CompletedProcess[str]]:
        args = [_fill(a, places) for a in probe.args]
        return probe.id, subprocess.run([EMBOTEAM, *args], capture_output=True, text=True, timeout=120,
                                        env=env, cwd=tmp)

    with ThreadPoolExecutor(max_workers=4) as pool:
        return dict(pool.map(one, PROBES))


def test_there_are_at_least_60_distinct_probes() -> None:
    assert len(PROBES) >= 60
    assert len({p.id for p in PROBES}) == len(PROBES)


@pytest.mark.parametrize("probe", PROBES, ids=[p.id for p in PROBES])
def test_probe_keeps_the_contract(probe: Probe, results: dict[str, subprocess.CompletedProcess[str]]) -> None:
    proc = results[probe.id]
    assert proc.returncode == probe.code, (proc.returncode, proc.stderr, proc.stdout)
    lines = [line for line in proc.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, proc.stderr                  # exactly one line on stderr
    assert "Traceback" not in proc.stderr + proc.stdout and "╭" not in proc.stderr
    assert not RAW_CONTROL.search(proc.stderr), repr(proc.stderr)
    assert not RAW_CONTROL.search(proc.stdout), repr(proc.stdout)
    line = lines[0].lower()
    assert line.startswith("error: ")
    if probe.needle:
        assert probe.needle in line, line
    if probe.absent:
        assert probe.absent not in line, line
    if "--json" in probe.args:
        objects = [json.loads(x) for x in proc.stdout.splitlines() if x.strip()]
        assert len(objects) == 1, proc.stdout             # exactly one JSON object
        data = objects[0]
        assert data["success"] is False and data["exit_code"] == probe.code and "error_type" in data
        assert isinstance(data["error"], str) and data["error"]
        assert data["error"] == lines[0][len("error: "):]   # the same message as on stderr
    else:
        assert proc.stdout == "" or probe.args[0] in ("run",), proc.stdout
