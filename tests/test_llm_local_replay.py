"""The committed cassettes of the local-model benchmark (benchmarks/llm_local.py, Qwen2.5-
Coder-0.5B through llama.cpp) replay through ``emboteam run ... --llm replay:DIR`` and give
exactly the metrics recorded in benchmarks/llm_local/results.json: no model needed, and a
change to a prompt, the schema or the offline parser's draft shows up here as a replay
miss or a different number."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from emboteam.cli import app

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "llm_local"
RESULTS = OUT / "results.json"


def recorded() -> list[tuple[str, dict[str, Any]]]:
    """(front end, row) of every recorded episode that called the LLM or ran the pure LLM
    front end (a hybrid task that made no call is the offline reading: nothing to replay)."""
    if not RESULTS.exists():
        return []
    data = json.loads(RESULTS.read_text())
    return [(frontend, row) for frontend, rows in data["runs"].items() if frontend != "offline"
            for row in rows.values() if frontend == "llm" or row["llm_calls"]]


def error_type(error: str | None) -> str | None:
    return error.split(":", 1)[0] if error else None


@pytest.mark.parametrize(("frontend", "row"), recorded(), ids=lambda v: v if isinstance(v, str) else v["task"])
def test_recorded_episode_replays_with_the_same_metrics(frontend: str, row: dict[str, Any]) -> None:
    cassette = OUT / "cassettes" / frontend
    result = CliRunner().invoke(app, ["run", f"mace-thor/{row['task']}", "--frontend", frontend,
                                      "--llm", f"replay:{cassette}", "--json"])
    got = json.loads(result.stdout.strip().splitlines()[-1])
    assert got.get("error_type") != "LLMReplayMiss", got["error"]
    for metric in ("success", "gcr", "exec", "llm_calls", "tokens"):
        assert got[metric] == row[metric], (metric, got[metric], row[metric])
    assert got.get("error_type") == error_type(row["error"])   # run --json: the message has no class name


def test_the_benchmark_recorded_hybrid_calls_and_the_offline_reference() -> None:
    runs = json.loads(RESULTS.read_text())["runs"]
    assert runs.get("hybrid") and runs.get("offline")
    assert any(row["llm_calls"] for row in runs["hybrid"].values())
    assert (OUT / "cassettes" / "hybrid" / "cassette.json").is_file()
