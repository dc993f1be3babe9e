"""What --llm selects, measured with the perfect-model stand-in (emboteam.bench.standin), and
the routing benchmark's own bookkeeping on a small round."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from emboteam.bench.mace_thor import load_mace_thor
from emboteam.bench.standin import DISCLAIMER, StandInServer, known_tasks
from emboteam.cli import HYBRID_DEFAULT_WHEN, LLM_DEFAULT_FRONTEND, app

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

TASK = "fp1-toast"


@pytest.fixture(scope="module")
def standin() -> StandInServer:
    with StandInServer(known_tasks(t for t in load_mace_thor() if t.id == TASK)) as server:
        yield server


def run_json(out: Path, *args: str) -> dict[str, object]:
    """The episode record of ``emboteam run`` (it names the front end that ran)."""
    result = CliRunner().invoke(app, ["run", f"mace-thor/{TASK}", *args, "--out", str(out), "--json"])
    assert result.exit_code == 0, result.stdout
    return json.loads((out / "episode.json").read_text())


def test_llm_alone_selects_the_measured_default_and_llm_when_picks_hybrid(standin: StandInServer,
                                                                         tmp_path: Path) -> None:
    alone = run_json(tmp_path / "a", "--llm", standin.spec)
    assert alone["frontend"] == LLM_DEFAULT_FRONTEND and alone["success"] is True
    cheap = run_json(tmp_path / "b", "--llm", standin.spec, "--llm-when", "doubt")
    assert cheap["frontend"] == "hybrid" and cheap["success"] is True
    assert cheap["llm_calls"] <= alone["llm_calls"]  # type: ignore[operator]


def test_hybrid_without_llm_when_uses_the_documented_default(standin: StandInServer, tmp_path: Path) -> None:
    other = "always" if HYBRID_DEFAULT_WHEN == "doubt" else "doubt"
    named = run_json(tmp_path / "a", "--llm", standin.spec, "--frontend", "hybrid", "--llm-when", HYBRID_DEFAULT_WHEN)
    unnamed = run_json(tmp_path / "b", "--llm", standin.spec, "--frontend", "hybrid")
    changed = run_json(tmp_path / "c", "--llm", standin.spec, "--frontend", "hybrid", "--llm-when", other)
    assert named["llm_calls"] == unnamed["llm_calls"] != changed["llm_calls"]


def test_benchmark_counts_silent_failures_and_says_what_the_model_is(tmp_path: Path) -> None:
    from frontend_routing import Row, render, summarize

    features = {"error": None, "doubtful": False, "notes": {}, "unsure": 0, "unexplained": [], "conditions": 1,
                "content_words": 3, "turns": 0}
    ok = {"success": True, "calls": 1, "error": None}
    rows = [Row("r", "wrong-unasked", True, False, None, features,
                {"llm": ok, "hybrid-doubt": {"success": False, "calls": 0, "error": None}, "hybrid-always": ok}),
            Row("r", "right", True, True, None, features, {"llm": ok, "hybrid-doubt": {**ok, "calls": 0},
                                                            "hybrid-always": ok})]
    summary = summarize(rows)
    assert summary["r"]["modes"]["hybrid-doubt"]["silent_failures"] == 1
    assert summary["r"]["modes"]["hybrid-always"]["silent_failures"] == 0
    assert summary["r"]["modes"]["hybrid-doubt"]["sr"] == 0.5
    assert summary["r"]["notes"] == {"wrong": 1, "wrong_flagged": 0, "right": 1, "right_flagged": 0}
    assert DISCLAIMER in render(summary, markdown=True)
