"""Run a test in a child interpreter, so that a crash in native code fails that one test.

A pytest plugin (conftest.py loads it): ``@pytest.mark.isolated`` tests (llama.cpp's) are run
by :func:`run_isolated` from the ``pytest_pyfunc_call`` hook below: the parent starts ``python -m pytest NODEID`` with
:data:`CHILD_ENV` set, and the child runs the body as usual. A segmentation fault then shows as
this test's failure with the signal's name instead of ending the whole run.

Written by hand because pytest-forked (1.7.5, the maintained plugin for this) exits every
forked test with status 3 under pytest 9, and forking after llama.cpp's threads start is unsafe
anyway; a fresh interpreter is the robust form.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
from pathlib import Path

import pytest

#: set in the child: the hook then lets pytest call the test body itself
CHILD_ENV = "EMBOTEAM_ISOLATED_CHILD"


def in_child() -> bool:
    return os.environ.get(CHILD_ENV) == "1"


def _outcome_line(output: str) -> str:
    lines = [ln for ln in output.strip().splitlines() if ln.strip()]
    return lines[-1] if lines else "(no output)"


def run_isolated(item: pytest.Item, timeout: float) -> None:
    """Run ``item`` in a child pytest; fail, skip or pass as the child did."""
    root = Path(str(item.config.rootpath))
    cmd = [sys.executable, "-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider", item.nodeid]
    env = {**os.environ, CHILD_ENV: "1"}
    try:
        done = subprocess.run(cmd, cwd=root, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        pytest.fail(f"the isolated test did not finish within {timeout:.0f} s", pytrace=False)
    output = done.stdout + done.stderr
    if done.returncode < 0:
        name = signal.Signals(-done.returncode).name
        pytest.fail(f"the test's interpreter crashed with {name} (native code); last output: "
                    f"{_outcome_line(output)}", pytrace=False)
    if done.returncode == 0 and re.search(r"\b1 skipped\b", output):
        reason = re.search(r"SKIPPED \[\d+\] [^:]+:\d+: (.*)", output)
        pytest.skip(reason.group(1) if reason else "skipped in the isolated run")
    if done.returncode != 0:
        pytest.fail(f"isolated run failed (exit {done.returncode}):\n{output[-4000:]}", pytrace=False)


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "isolated(timeout=S): run the test in a child interpreter "
                                       "(native code that may crash)")


@pytest.hookimpl(tryfirst=True)
def pytest_pyfunc_call(pyfuncitem: pytest.Function) -> bool | None:
    """``isolated`` tests run in a child interpreter; in the child, pytest calls the body."""
    marker = pyfuncitem.get_closest_marker("isolated")
    if marker is None or in_child():
        return None
    run_isolated(pyfuncitem, timeout=float(marker.kwargs.get("timeout", 300)))
    return True
