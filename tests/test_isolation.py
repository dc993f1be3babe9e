"""The ``isolated`` marker: a test whose native code crashes fails alone, with the signal
named, and the rest of the run goes on (the llama.cpp tests depend on it)."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

TESTS = Path(__file__).resolve().parent


def _run(tmp_path: Path, body: str) -> subprocess.CompletedProcess[str]:
    (tmp_path / "conftest.py").write_text(
        f"import sys\nsys.path.insert(0, {str(TESTS)!r})\npytest_plugins = ['isolation']\n")
    (tmp_path / "test_child.py").write_text(textwrap.dedent(body))
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider", str(tmp_path)],
                          cwd=tmp_path, capture_output=True, text=True, timeout=120)


def test_a_crash_fails_one_test_with_its_signal_and_the_run_goes_on(tmp_path: Path) -> None:
    done = _run(tmp_path, """
        import os, signal
        import pytest

        @pytest.mark.isolated
        def test_crashes():
            os.kill(os.getpid(), signal.SIGSEGV)

        def test_after():
            assert True
    """)
    assert done.returncode == 1, done.stdout
    assert "crashed with SIGSEGV" in done.stdout
    assert "1 failed, 1 passed" in done.stdout


def test_isolated_pass_and_skip_are_reported_as_in_the_child(tmp_path: Path) -> None:
    done = _run(tmp_path, """
        import pytest

        pytestmark = pytest.mark.isolated

        def test_passes():
            assert True

        def test_skips():
            pytest.skip("no model here")
    """)
    assert done.returncode == 0, done.stdout
    assert "1 passed, 1 skipped" in done.stdout and "no model here" in done.stdout
