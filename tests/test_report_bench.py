"""The benchmark index and ``emboteam report DIR`` (write_report), without a browser."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest

from emboteam.exec.episode import Episode
from emboteam.report import ReportError, write_bench_index, write_report
from emboteam.report.bench_index import markdown_to_html
from test_report_fixtures import scripted_fridge_episode

EMBEDDED = re.compile(r'<script type="application/json" id="bench-data">(.*?)</script>', re.S)
# a 1x1 PNG
PIXEL = bytes.fromhex("89504e470d0a1a0a0000000d4948445200000001000000010806000000"
                      "1f15c4890000000d49444154789c6360000002000154a24f5d0000000049454e44ae426082")


def data_of(path: Path) -> Any:
    m = EMBEDDED.search(path.read_text(encoding="utf-8"))
    assert m is not None
    return json.loads(m.group(1))


@pytest.fixture(scope="module")
def episodes() -> list[tuple[str, Episode]]:
    ok = scripted_fridge_episode()
    failed = scripted_fridge_episode(seed=0)
    assert ok.success and not failed.success
    return [("mace-thor_fridge__full__oracle__seed=7", ok),
            ("mace-thor_fridge__no-btc__oracle__seed=0", failed.model_copy(update={"mode": "no-btc"})),
            ("with space|and#hash", failed.model_copy(update={"error": "PlannerTimeout: <b>slow</b>"}))]


def make_bench_dir(root: Path, episodes: list[tuple[str, Episode]]) -> Path:
    for key, ep in episodes:
        ep.save(root / "episodes" / key)
    return root


def test_index_has_a_row_per_episode_linking_to_its_report(tmp_path: Path,
                                                           episodes: list[tuple[str, Episode]]) -> None:
    make_bench_dir(tmp_path, episodes)
    plot = tmp_path / "sr_by_mode.png"
    plot.write_bytes(PIXEL)
    summary = {"suite": "mace-thor", "n": 3, "sr": 1 / 3, "by_category": {"parallel": {"n": 3, "sr": 1 / 3}}}
    out = write_bench_index(tmp_path, episodes, summary, "| mode | SR |\n|---|---|\n| full | 1.0 |\n", [plot])
    assert out == tmp_path / "index.html"
    data = data_of(out)
    rows = data["rows"]
    assert [r["key"] for r in rows] == [k for k, _ in episodes]
    assert [r["success"] for r in rows] == [True, False, False]
    assert rows[1]["mode"] == "no-btc" and rows[2]["error"].startswith("PlannerTimeout")
    for (key, _), row in zip(episodes, rows, strict=True):
        # missing episode reports were built; links are relative and URL-quoted
        assert (tmp_path / "episodes" / key / "report.html").is_file()
        assert row["link"].startswith("episodes/") and row["link"].endswith("/report.html")
        assert " " not in row["link"] and "#" not in row["link"] and "|" not in row["link"]
    assert data["plots"][0]["src"].startswith("data:image/png;base64,")
    assert data["summary"]["by_category"]["parallel"]["n"] == 3
    html = out.read_text()
    assert "<table>" in html and "<td>full</td>" in html  # the Markdown tables, rendered
    assert "<b>slow</b>" not in html  # error text is data, never markup


def test_markdown_tables_escape_raw_html() -> None:
    html = markdown_to_html("| a |\n|---|\n| <script>x</script> |\n\n[x](javascript:alert(1))")
    assert "<script>" not in html and "&lt;script&gt;" in html
    assert "href=\"javascript:" not in html  # the link is refused, left as text


def test_bad_index_inputs_are_typed_errors(tmp_path: Path, episodes: list[tuple[str, Episode]]) -> None:
    one = episodes[:1]
    with pytest.raises(ReportError, match="unique"):
        write_bench_index(tmp_path, one + one, {}, "", [])
    with pytest.raises(ReportError, match="not a directory name"):
        write_bench_index(tmp_path, [("../escape", one[0][1])], {}, "", [])
    with pytest.raises(ReportError, match="cannot read plot"):
        write_bench_index(tmp_path, one, {}, "", [tmp_path / "missing.png"])
    (tmp_path / "table.csv").write_text("a,b")
    with pytest.raises(ReportError, match="unsupported image type"):
        write_bench_index(tmp_path, one, {}, "", [tmp_path / "table.csv"])


def test_write_report_rebuilds_a_run(tmp_path: Path, episodes: list[tuple[str, Episode]]) -> None:
    episodes[0][1].save(tmp_path)
    assert write_report(tmp_path) == [tmp_path / "report.html"]


def test_write_report_rebuilds_a_benchmark_with_its_files(tmp_path: Path,
                                                          episodes: list[tuple[str, Episode]]) -> None:
    make_bench_dir(tmp_path, episodes)
    (tmp_path / "summary.json").write_text(json.dumps({"suite": "mace-thor", "n": 3, "sr": 0.33}))
    (tmp_path / "tables.md").write_text("## Table 1\n\n| mode | SR |\n|---|---|\n| full | 0.33 |\n")
    (tmp_path / "by_category.png").write_bytes(PIXEL)
    written = write_report(tmp_path)
    assert written[-1] == tmp_path / "index.html"
    assert len(written) == len(episodes) + 1
    data = data_of(written[-1])
    assert data["summary"]["sr"] == 0.33 and [p["file"] for p in data["plots"]] == ["by_category.png"]
    assert "<h2>Table 1</h2>" in written[-1].read_text()


def test_write_report_recomputes_a_missing_summary(tmp_path: Path, episodes: list[tuple[str, Episode]]) -> None:
    make_bench_dir(tmp_path, episodes)
    summary = data_of(write_report(tmp_path)[-1])["summary"]
    assert summary["n"] == 3 and summary["sr"] == pytest.approx(1 / 3, abs=1e-4)
    assert summary["errors"] == 1


def test_write_report_rejects_other_directories(tmp_path: Path) -> None:
    with pytest.raises(ReportError, match=r"neither episode\.json"):
        write_report(tmp_path)
    (tmp_path / "episodes").mkdir()
    (tmp_path / "summary.json").write_text("{broken")
    with pytest.raises(ReportError, match=r"summary\.json"):
        write_report(tmp_path)


def test_write_report_reads_what_the_bench_runner_writes(tmp_path: Path,
                                                         episodes: list[tuple[str, Episode]]) -> None:
    tables = pytest.importorskip("emboteam.bench.tables", reason="the benchmark tables have not landed")
    plots = pytest.importorskip("emboteam.bench.plots", reason="the benchmark plots have not landed")
    make_bench_dir(tmp_path, episodes)
    eps = [ep for _, ep in episodes]
    tables.write_summary(eps, tmp_path / "summary.json", suite="mace-thor")
    tables.write_tables(eps, tmp_path / "tables.md")
    pngs = plots.write_plots(eps, tmp_path)
    index = write_report(tmp_path)[-1]
    data = data_of(index)
    assert data["summary"]["n"] == len(episodes) and "sr_ci" in data["summary"]
    assert sorted(p["file"] for p in data["plots"]) == sorted(p.name for p in pngs)
    assert index.read_text().count("<table>") >= 1
