"""The committed cassette of benchmarks/pmi_scorer.py (Qwen2.5-Coder-0.5B through llama.cpp
on tests/data/pmi_cases.json) replays without the model and reproduces every score, pick
and accuracy in benchmarks/pmi_scorer/results.json; a change to the scoring prompts, the
objects summary or the cases shows up here as a replay miss or a different number."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from types import ModuleType

from emboteam.llm import make_client

ROOT = Path(__file__).resolve().parents[1]


def benchmark() -> ModuleType:
    """benchmarks/pmi_scorer.py as a module (benchmarks/ is no package; as tests/test_frontend_routing.py)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import pmi_scorer

    return pmi_scorer


def test_the_recorded_run_replays_with_the_same_scores_and_accuracy() -> None:
    bench = benchmark()
    recorded = json.loads(bench.RESULTS.read_text())
    client = make_client(f"replay:{bench.CASSETTE}")
    replayed = bench.evaluate(client, bench.load_cases())
    assert bench.differences(recorded, replayed) == []
    assert replayed["summary"]["pmi_ambiguous"] == recorded["summary"]["pmi_ambiguous"]
    assert client.usage.calls == len(bench.load_cases())
    # the recorded run is what docs/llm.md reports: PMI beats the raw sum on the ambiguous cases
    right, total = recorded["summary"]["pmi_ambiguous"]
    assert total >= 30 and right > recorded["summary"]["raw_ambiguous"][0]
