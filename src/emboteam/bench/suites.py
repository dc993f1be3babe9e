"""Benchmark suites by name: ``mace-thor`` (package data) and ``smart-llm:PATH`` (tasks in
the SMART-LLM / MAT-THOR format, imported from every ``FloorPlanN*.json`` beneath PATH).

``get_task("SUITE/ID")`` is how the CLI resolves a TASK argument; unknown suites and tasks
are typed errors that list the closest names.
"""

from __future__ import annotations

import difflib
from pathlib import Path

from emboteam.bench.congestion import SUITE_NAME as CONGESTION
from emboteam.bench.congestion import load_congestion
from emboteam.bench.mace_thor import SUITE_NAME as MACE_THOR
from emboteam.bench.mace_thor import load_mace_thor
from emboteam.bench.suite import Suite, UnknownSuiteError, UnknownTaskError
from emboteam.task import BenchTask

SMART_LLM_PREFIX = "smart-llm:"

#: how suites are written on the command line
SUITE_SPECS: tuple[str, ...] = (MACE_THOR, CONGESTION, SMART_LLM_PREFIX + "PATH")


def load_suite(spec: str) -> Suite:
    """``mace-thor``, ``congestion`` or ``smart-llm:PATH`` (a directory searched recursively,
    or one file)."""
    text = spec.strip()
    if text == MACE_THOR:
        return Suite(name=MACE_THOR, tasks=load_mace_thor())
    if text == CONGESTION:
        return Suite(name=CONGESTION, tasks=load_congestion())
    if text.startswith(SMART_LLM_PREFIX):
        from emboteam.bench.importers.smart_llm import import_smart_llm

        path = text[len(SMART_LLM_PREFIX):]
        if not path:
            raise UnknownSuiteError("smart-llm needs a path: smart-llm:PATH (a folder of FloorPlanN*.json files)")
        return import_smart_llm(Path(path).expanduser(), suite=text)
    close = difflib.get_close_matches(text, [MACE_THOR, CONGESTION, "smart-llm"], n=1, cutoff=0.5)
    hint = f"; did you mean {close[0]}{':PATH' if close[0] == 'smart-llm' else ''}?" if close else ""
    raise UnknownSuiteError(f"unknown suite {spec!r}{hint} (suites: {', '.join(SUITE_SPECS)})")


def split_task_key(key: str) -> tuple[str, str]:
    """``SUITE/ID`` -> (suite, id). The id is after the last ``/`` (a smart-llm PATH may
    contain slashes)."""
    suite, sep, task_id = key.strip().rpartition("/")
    if not sep or not suite or not task_id:
        hint = ""
        if sep == "" and key.strip():
            ids = [t.id for t in load_mace_thor()]
            if key.strip() in ids:
                hint = f"; did you mean {MACE_THOR}/{key.strip()}?"
        raise UnknownTaskError(f"a task is written SUITE/ID, e.g. {MACE_THOR}/fp1-toast, not {key!r}{hint}")
    return suite, task_id


def get_task(key: str) -> BenchTask:
    """The task ``SUITE/ID`` (e.g. ``mace-thor/fp1-toast``)."""
    suite, task_id = split_task_key(key)
    return load_suite(suite).task(task_id)


__all__ = ["SUITE_SPECS", "Suite", "UnknownSuiteError", "UnknownTaskError", "get_task", "load_suite",
           "split_task_key"]
