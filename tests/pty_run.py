"""Run the command line on a pseudo-terminal, as a person at a terminal would, and answer
its question: what `--clarify` tests need (a pipe is no terminal, so the CLI would not ask)."""

from __future__ import annotations

import os
import pty
import select
import subprocess
import sys
import time
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"


def run_on_terminal(args: list[str], answer: bytes, prompt: bytes = b"Your choice",
                    timeout: float = 300) -> tuple[str, int]:
    """``python -m emboteam ARGS`` on a pseudo-terminal, ``answer`` typed once ``prompt``
    shows; the whole output (whitespace folded) and the exit code."""
    env = {**os.environ, "PYTHONPATH": str(SRC), "COLUMNS": "200"}
    master, slave = pty.openpty()
    proc = subprocess.Popen([sys.executable, "-m", "emboteam", *args], stdin=slave, stdout=slave, stderr=slave,
                            env=env)
    os.close(slave)
    out, answered, deadline = b"", False, time.monotonic() + timeout
    while time.monotonic() < deadline:
        ready, _, _ = select.select([master], [], [], 1.0)
        if ready:
            try:
                chunk = os.read(master, 4096)
            except OSError:
                break
            if not chunk:
                break
            out += chunk
            if not answered and prompt in out:
                os.write(master, answer)
                answered = True
        elif proc.poll() is not None:
            break
    proc.wait(timeout=60)
    os.close(master)
    return " ".join(out.decode(errors="replace").split()), proc.returncode
