"""``emboteam report DIR`` on what crashes and disk trouble leave behind: a corrupt
episode.json, a trace.jsonl cut mid-line. The broken parts are skipped and listed (on
stderr and in the index), the rest is built, and tables.md is never rewritten by a rebuild
that then fails before index.html."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from emboteam.cli import app
from emboteam.exec.episode import Episode
from emboteam.report import ReportError, write_report
from test_report_bench import data_of
from test_report_fixtures import scripted_fridge_episode


@pytest.fixture(scope="module")
def episode() -> Episode:
    return scripted_fridge_episode()


def bench_dir(root: Path, episode: Episode) -> Path:
    for key in ("a-good", "b-truncated-trace", "c-corrupt-episode"):
        episode.save(root / "episodes" / key)
    (root / "tables.md").write_text("# Benchmark results\n\n| Mode | SR |\n|---|---:|\n| full | 100.0 |\n")
    trace = root / "episodes" / "b-truncated-trace" / "trace.jsonl"
    text = trace.read_text()
    trace.write_text(text[: len(text) - 40])  # what a crash mid-write leaves: the last line cut
    (root / "episodes" / "c-corrupt-episode" / "episode.json").write_text('{"task": "x", ')
    return root


def test_broken_episodes_are_skipped_listed_and_the_rest_built(tmp_path: Path, episode: Episode) -> None:
    bench_dir(tmp_path, episode)
    with pytest.raises(ReportError):  # strict without a problems list, as before
        write_report(tmp_path)
    problems: list[str] = []
    pages = write_report(tmp_path, problems=problems)
    assert pages[-1] == tmp_path / "index.html"
    assert [r["key"] for r in data_of(pages[-1])["rows"]] == ["a-good", "b-truncated-trace"]
    assert len(problems) == 2
    assert "b-truncated-trace/trace.jsonl:" in problems[0] and "not JSON" in problems[0]
    assert "c-corrupt-episode/episode.json: not JSON" in problems[1] and "left out of the index" in problems[1]
    html = pages[-1].read_text()
    assert "Left out of this report" in html and "c-corrupt-episode" in html
    # the episode with the cut trace keeps every event before the cut
    viewer = (tmp_path / "episodes" / "b-truncated-trace" / "report.html").read_text()
    assert viewer.startswith("<!DOCTYPE html>")


def test_report_command_lists_what_it_skipped(tmp_path: Path, episode: Episode) -> None:
    bench_dir(tmp_path, episode)
    tables_before = (tmp_path / "tables.md").read_text()
    result = CliRunner().invoke(app, ["report", str(tmp_path)])
    assert result.exit_code == 0, result.output
    skipped = [line for line in result.stderr.splitlines() if line.startswith("skipped: ")]
    assert len(skipped) == 2 and "c-corrupt-episode" in skipped[1]
    assert "wrote " in result.stdout and (tmp_path / "index.html").is_file()
    assert (tmp_path / "tables.md").read_text() == tables_before


def test_a_run_with_a_truncated_trace_still_gets_its_report(tmp_path: Path, episode: Episode) -> None:
    episode.save(tmp_path)
    trace = tmp_path / "trace.jsonl"
    lines = trace.read_text().splitlines(keepends=True)
    trace.write_text("".join(lines[:-1]) + lines[-1][:10])
    result = CliRunner().invoke(app, ["report", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert f"trace.jsonl:{len(lines)}: not JSON" in result.stderr
    assert (tmp_path / "report.html").read_text().startswith("<!DOCTYPE html>")
