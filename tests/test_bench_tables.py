"""Tables (Markdown, shaped like the paper's Tables 1 and 2), plots and the run's reports."""

from __future__ import annotations

import json
import struct
from pathlib import Path

import pytest

from emboteam.bench.jobs import expand_jobs
from emboteam.bench.metrics import summarize
from emboteam.bench.plots import write_plots
from emboteam.bench.runner import run_bench, write_reports
from emboteam.bench.store import ResultStoreError
from emboteam.bench.tables import bench_summary, canonical_order, render_tables, write_tables
from emboteam.exec.episode import Episode
from test_bench_runner import config, make_task, scripted_episode


def ep(mode: str, category: str, task: str, success: bool, *, gcr: float | None = None, failed: int = 0,
       seed: int = 0, faults: float = 0.0, frontend: str = "offline") -> Episode:
    """Every episode has 4 actions, so Exec is the same whether averaged per episode or pooled."""
    return Episode(task=f"unit/{task}", instruction="x", floor_plan="FloorPlan1", robots=("robot1",),
                   category=category, mode=mode, frontend=frontend, seed=seed, fault_level=faults,
                   success=success, gcr=(1.0 if success else 0.0) if gcr is None else gcr,
                   exec=(4 - failed) / 4, actions=4, failed_actions=failed, makespan=20.0)


def table(markdown: str, heading: str) -> list[list[str]]:
    """The header and body rows (cells) of the table under the first heading that starts
    with ``heading``, checking the Markdown shape on the way."""
    lines = markdown.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("## " + heading))
    assert lines[start + 1] == "", "a blank line follows the heading"
    rows = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        rows.append([c.strip() for c in line.strip("|").split("|")])
    header, separator, *body = rows
    assert len(separator) == len(header) and all(set(c) <= set("-:") for c in separator)
    assert all(len(r) == len(header) for r in body)
    return [header, *body]


def paper_episodes() -> list[Episode]:
    eps = []
    for mode, wins in (("smart-llm", (True, False, False, False)), ("lamma-p", (True, True, False, False)),
                       ("full", (True, True, True, False))):
        eps += [ep(mode, "parallel", "p1", wins[0]), ep(mode, "parallel", "p2", wins[1], gcr=0.5, failed=1),
                ep(mode, "temporal", "t1", wins[2]), ep(mode, "temporal", "t2", wins[3], gcr=0.5, failed=2)]
    return eps


def test_table1_is_methods_by_category_with_sr_gcr_exec() -> None:
    md = render_tables(paper_episodes())
    rows = table(md, "Table 1")
    assert rows[0] == ["Method", "Parallel SR", "Parallel GCR", "Parallel Exec", "Temporal SR", "Temporal GCR",
                       "Temporal Exec", "Overall SR", "Overall GCR", "Overall Exec", "n"]
    body = {r[0]: r[1:] for r in rows[1:]}
    assert list(body) == ["SMART-LLM", "LaMMA-P", "EmboTeam"]
    # SMART-LLM: parallel p1 ok (gcr 1), p2 failed (gcr .5, exec .75); temporal both failed
    assert body["SMART-LLM"] == ["50.0", "75.0", "87.5", "0.0", "25.0", "75.0", "25.0", "50.0", "81.2", "4"]
    # LaMMA-P: p2 succeeds (its gcr argument is ignored by success -> 0.5 given explicitly)
    assert body["LaMMA-P"][:3] == ["100.0", "75.0", "87.5"]
    assert body["EmboTeam"][:6] == ["100.0", "75.0", "87.5", "50.0", "75.0", "75.0"]
    assert "Table 2" not in md  # no ablation was run


def test_table2_lists_the_ablations_and_marks_missing_categories() -> None:
    eps = [ep("full", "parallel", "p1", True), ep("full", "temporal", "t1", True),
           ep("no-hp", "parallel", "p1", False), ep("no-btc", "parallel", "p1", True),
           ep("no-btc", "temporal", "t1", False)]
    rows = table(render_tables(eps), "Table 2")
    body = {r[0]: r[1:] for r in rows[1:]}
    assert list(body) == ["EmboTeam (full)", "w/o HP", "w/o BTC"]
    assert body["w/o HP"][3:6] == ["–", "–", "–"]  # no temporal episode of no-hp
    assert body["w/o BTC"][0] == "100.0" and body["w/o BTC"][3] == "0.0" and body["w/o BTC"][-1] == "2"


def test_each_setting_gets_its_own_tables_and_a_fault_sweep() -> None:
    eps = [ep("full", "parallel", "p1", True, faults=0.0), ep("full", "parallel", "p2", True, faults=0.0),
           ep("full", "parallel", "p1", True, faults=0.2), ep("full", "parallel", "p2", False, faults=0.2),
           ep("smart-llm", "parallel", "p1", False, faults=0.2), ep("full", "parallel", "p1", True, frontend="llm")]
    md = render_tables(eps)
    headings = [line for line in md.splitlines() if line.startswith("## Table 1")]
    assert headings == ["## Table 1: EmboTeam and the baselines (front end `llm`, fault rate 0)",
                        "## Table 1: EmboTeam and the baselines (front end `offline`, fault rate 0)",
                        "## Table 1: EmboTeam and the baselines (front end `offline`, fault rate 0.2)"]
    sweep = table(md, "Success rate against fault rate")
    assert sweep[0] == ["Method", "Front end", "SR @ 0", "SR @ 0.2"]
    assert ["EmboTeam", "`offline`", "100.0", "50.0"] in sweep
    assert ["SMART-LLM", "`offline`", "–", "0.0"] in sweep
    runs = table(md, "All runs")
    assert len(runs) == 1 + 4  # header + (full llm 0, full offline 0, full 0.2, smart-llm 0.2)


def test_no_episodes_gives_an_empty_report() -> None:
    assert "No episodes yet." in render_tables([])


def _png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    width, height = struct.unpack(">II", data[16:24])
    return width, height


def test_plots_by_category_always_and_against_faults_when_swept(tmp_path: Path) -> None:
    nominal = paper_episodes()
    assert [p.name for p in write_plots(nominal, tmp_path / "a")] == ["by_category.png"]
    swept = nominal + [ep("full", "parallel", "p1", False, faults=0.3, seed=s) for s in range(3)]
    written = write_plots(swept, tmp_path / "b")
    assert [p.name for p in written] == ["by_category.png", "sr_vs_faults.png"]
    for path in written:
        width, height = _png_size(path)
        assert width > 500 and height > 300
    assert write_plots([], tmp_path / "c") == []


def test_a_run_writes_tables_summary_and_plots_from_its_store(tmp_path: Path) -> None:
    out = tmp_path / "out"
    cfg = config(out, executor="inline", modes=["full", "no-btc"], fault_levels=[0.0, 0.4])
    tasks = [make_task("t1"), make_task("t2", "temporal"), make_task("t4", "temporal")]
    episodes = run_bench(cfg, expand_jobs(cfg, tasks), scripted_episode, progress=False)

    for name in ("tables.md", "summary.json", "by_category.png", "sr_vs_faults.png"):
        assert (out / name).exists(), name
    summary = json.loads((out / "summary.json").read_text())
    assert summary == json.loads(json.dumps(bench_summary(episodes, suite="unit").to_json()))
    assert bench_summary(episodes) == summarize(canonical_order(episodes))
    assert summary["n"] == 12 and summary["sr"] == pytest.approx(4 / 12)
    md = (out / "tables.md").read_text()
    assert table(md, "Table 2")[1][0] == "EmboTeam (full)"
    # rebuilding from the store alone gives the same tables
    (out / "tables.md").unlink()
    write_reports(out)
    assert (out / "tables.md").read_text() == md
    with pytest.raises(ResultStoreError, match="no benchmark results"):
        write_reports(tmp_path / "empty")


def test_write_tables_creates_the_file(tmp_path: Path) -> None:
    path = write_tables(paper_episodes(), tmp_path / "sub" / "tables.md")
    assert path.read_text().startswith("# Benchmark results")


def test_reports_do_not_depend_on_the_order_episodes_finished_in(tmp_path: Path) -> None:
    """Parallel workers finish in a different order each run; the reports must not change.

    With these outcomes (7 tasks x 3 seeds) a bootstrap that resampled tasks in arrival
    order gave different CIs for the two orders; summarize() resamples them in key order."""
    from emboteam.bench.jobs import Job
    from emboteam.bench.runner import store_path
    from emboteam.bench.store import ResultStore

    wins = [[1, 1, 1], [0, 1, 0], [0, 1, 0], [0, 1, 1], [0, 1, 0], [1, 1, 1], [0, 0, 0]]
    pairs = [(job, scripted_episode(job).model_copy(update={"success": bool(wins[i][seed])}))
             for i in range(7) for seed in range(3) for job in [Job(task=make_task(f"t{i}"), seed=seed)]]
    episodes = [e for _, e in pairs]
    assert summarize(episodes).sr_ci == summarize(episodes[::-1]).sr_ci
    for name, order in (("a", pairs), ("b", pairs[::-1])):
        with ResultStore(store_path(tmp_path / name)) as store:
            for job, episode in order:
                store.add(job, episode)
        write_reports(tmp_path / name)
    for report in ("tables.md", "summary.json"):
        assert (tmp_path / "a" / report).read_text() == (tmp_path / "b" / report).read_text(), report
