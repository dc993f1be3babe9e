"""Starting AI2-THOR: on a machine where no build can start (these: no display, no Vulkan,
no route to the build server), ``--env ai2thor`` fails fast with one line and exit 3."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from emboteam.bench.jobs import Job
from emboteam.bench.mace_thor import load_mace_thor
from emboteam.errors import EXIT_BAD_INPUT, EXIT_SERVICE
from emboteam.thor.errors import ThorUnavailableError
from emboteam.thor.launch import PREFIX, probe

EMBOTEAM = Path(sys.executable).with_name("emboteam")
TASK = "mace-thor/fp1-coffee-and-light"


def _startable() -> str | None:
    try:
        probe()
    except ThorUnavailableError as exc:
        return str(exc)
    return None


UNAVAILABLE = _startable()
needs_no_thor = pytest.mark.skipif(UNAVAILABLE is None, reason="an AI2-THOR build can start on this machine")


def cli(*args: str, timeout: float = 120) -> tuple[subprocess.CompletedProcess[str], float]:
    t0 = time.monotonic()
    proc = subprocess.run([str(EMBOTEAM), *args], capture_output=True, text=True, timeout=timeout,
                          env={**os.environ, "COLUMNS": "200"})
    return proc, time.monotonic() - t0


@needs_no_thor
def test_probe_says_in_one_line_everything_that_is_missing() -> None:
    assert UNAVAILABLE is not None and UNAVAILABLE.startswith(PREFIX)
    assert "\n" not in UNAVAILABLE
    assert "display" in UNAVAILABLE and "Vulkan" in UNAVAILABLE and "build thor-" in UNAVAILABLE


@needs_no_thor
@pytest.mark.parametrize("command", [["run", TASK], ["bench", "--suite", "mace-thor"]])
def test_env_ai2thor_fails_fast_with_one_line_and_exit_3(command: list[str], tmp_path: Path) -> None:
    extra = ["--out", str(tmp_path / "b")] if command[0] == "bench" else []
    proc, seconds = cli(*command, "--env", "ai2thor", *extra)
    assert proc.returncode == EXIT_SERVICE
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and PREFIX in lines[0], proc.stderr
    assert "Traceback" not in proc.stderr and proc.stdout == ""
    assert seconds < 60  # no download hang: the probe is bounded (a few seconds on a loaded machine)
    assert not (tmp_path / "b").exists()  # nothing ran


def test_bad_env_and_simulator_only_options_are_bad_input() -> None:
    proc, _ = cli("run", TASK, "--env", "unity")
    assert proc.returncode == EXIT_BAD_INPUT and "sim or ai2thor" in proc.stderr
    proc, _ = cli("run", TASK, "--env", "ai2thor", "--faults", "0.1")
    assert proc.returncode == EXIT_BAD_INPUT and "AI2-THOR's own" in proc.stderr


def test_a_missing_ai2thor_package_is_named_with_the_extra_to_install() -> None:
    code = ("import sys; sys.modules['ai2thor'] = None\n"
            "from emboteam.thor.launch import probe\n"
            "try:\n    probe()\nexcept Exception as e:\n    print(type(e).__name__, e)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120).stdout
    assert out.startswith("ThorUnavailableError") and "pip install 'emboteam[ai2thor]'" in out


def test_the_default_install_never_imports_ai2thor() -> None:
    code = ("import sys, emboteam.cli, emboteam.modes, emboteam.environments, emboteam.thor.environment, "
            "emboteam.thor.session\nprint(any(m == 'ai2thor' or m.startswith('ai2thor.') for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.strip() == "False", out.stderr


def test_env_is_in_a_jobs_key_only_when_not_the_simulator() -> None:
    task = load_mace_thor()[0]
    sim, thor = Job(task=task), Job(task=task, env="ai2thor")
    assert "env=" not in sim.key and sim.key == Job(task=task, env="sim").key
    assert thor.key == f"{sim.key}|env=ai2thor" and thor.dirname != sim.dirname


@needs_no_thor
def test_probe_picks_the_hosts_platform_and_checks_the_overrides(monkeypatch: pytest.MonkeyPatch) -> None:
    from emboteam.thor import launch

    monkeypatch.setattr(launch.host, "system", lambda: "Darwin")
    with pytest.raises(ThorUnavailableError, match=r"build thor-OSXIntel64-"):
        probe()  # macOS needs no display check, but the build still has to be had
    monkeypatch.undo()
    monkeypatch.setenv("EMBOTEAM_THOR_PLATFORM", "WebGL")
    with pytest.raises(ThorUnavailableError, match="unknown AI2-THOR platform 'WebGL'"):
        probe()
    monkeypatch.setenv("EMBOTEAM_THOR_PLATFORM", "CloudRendering")
    monkeypatch.setenv("EMBOTEAM_THOR_EXECUTABLE", "/nonexistent/thor-build")
    with pytest.raises(ThorUnavailableError, match="EMBOTEAM_THOR_EXECUTABLE=/nonexistent/thor-build is not"):
        probe()
