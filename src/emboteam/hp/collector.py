"""Python's cycle collector, paused while a plan is made.

Planning allocates hundreds of thousands of short-lived containers (state copies, step
groundings, literals). Reference counting frees them as they go: the planner makes almost
no reference cycles (``tests/test_hp_collector.py`` keeps it so). The cycle collector
runs on allocation counts all the same: a young pass every 700 net allocations, and in a
large plan one or two full passes over every long-lived object of the process (scenes,
catalogue, word tables, imported modules: about 100,000 objects, some 60 ms each on a
2-core machine), which find nothing to free. In the 32-robot, 96-goal cell of
``benchmarks/plan_latency.py`` the collector took 10-15% of the planning CPU.

So :func:`collector_paused` turns it off for the length of a planning call and back on
after, as build tools that allocate heavily do (mypy raises the collector's thresholds for
its build). What a call leaves in cycles (a few hundred objects) is collected by the next
pass after it. The switch is process-wide, so it is counted: of overlapping calls (threads),
the first pauses the collector and the last resumes it, and a collector that was off
before the first stays off.
"""

from __future__ import annotations

import gc
import threading
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["collector_paused"]

_lock = threading.Lock()
_depth = 0
_resume = False


@contextmanager
def collector_paused() -> Iterator[None]:
    """The cycle collector off inside the block (reference counting still frees memory)."""
    global _depth, _resume
    with _lock:
        if _depth == 0:
            _resume = gc.isenabled()
            gc.disable()
        _depth += 1
    try:
        yield
    finally:
        with _lock:
            _depth -= 1
            if _depth == 0 and _resume:
                gc.enable()
