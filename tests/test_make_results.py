"""benchmarks/make_results.py rewrites only its generated blocks of docs/results.md.

Fast: ``--skip-run`` on small fixture bench outputs, the page and plots in a temporary
directory (the repository's docs/ are never touched).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from make_results import main, markers, splice  # noqa: E402

HAND = """## Reading, end to end (kept by hand)

| set | SR |
|---|---:|
| blind_r42 | 0.167 |
"""
OTHER_SCRIPT = "<!-- disturbances:start -->\n## Disturbances\n\nold numbers 4.4\n<!-- disturbances:end -->"


def fixture_run(out: Path) -> Path:
    """A finished run: the files make_results.py reads with --skip-run."""
    for fe, sr in (("oracle", "99.9"), ("offline", "77.7")):
        (out / fe).mkdir(parents=True)
        (out / fe / "tables.md").write_text(f"# Bench\n\n## Table 1 ({fe})\n\n| Method | SR |\n| --- | ---: |\n"
                                            f"| EmboTeam | {sr} |\n")
        (out / fe / "by_category.png").write_bytes(b"\x89PNG " + fe.encode())
        (out / f"{fe}.json").write_text("{}")
    (out / "smart-llm.json").write_text(json.dumps({"n": 34, "sr": 0.5, "gcr": 0.625, "errors": 3}))
    (out / "unseen.json").write_text(json.dumps({"n": 60, "sr": 0.111, "gcr": 0.222, "parse_errors": 7}))
    (out / "run.json").write_text(json.dumps({
        "started": "2026-12-06T09:00:00+00:00", "finished": "2026-12-06T09:41:00+00:00", "commit": "abc1234",
        "cpus": 2, "load_min": 1.2, "load_max": 3.4, "load_mean": 2.0}))
    return out


def block(name: str, text: str) -> str:
    start, end = markers(name)
    return f"{start}\n{text}\n{end}"


def page_with_blocks() -> str:
    return "\n\n".join([
        "# Results", block("provenance", "Measured on 2026-11-27."), HAND,
        block("oracle", "## Ground-truth goals\n\n| EmboTeam | 12.3 |"), block("offline", "stale offline"),
        block("unseen", "stale unseen 0.567"), block("smart-llm", "stale peers"), OTHER_SCRIPT]) + "\n"


def test_hand_sections_survive_and_generated_blocks_are_replaced(tmp_path: Path) -> None:
    out, doc = fixture_run(tmp_path / "out"), tmp_path / "docs" / "results.md"
    doc.parent.mkdir()
    doc.write_text(page_with_blocks())
    assert main(["--skip-run", "--out", str(out), "--doc", str(doc)]) == 0
    page = doc.read_text()
    assert HAND in page and OTHER_SCRIPT in page
    assert page.index(HAND) < page.index(markers("oracle")[0]), "blocks stay where the page put them"
    for stale in ("2026-11-27", "12.3", "stale offline", "0.567", "stale peers"):
        assert stale not in page
    assert "| EmboTeam | 99.9 |" in page and "| EmboTeam | 77.7 |" in page
    assert "| unseen | 60 | 0.111 | 0.222 | 7 |" in page
    assert "SR 0.500, GCR 0.625" in page
    assert "2026-12-06 between 09:00 and 09:41 UTC (41 min) at commit `abc1234`" in page
    assert "load average 1.2-3.4" in page
    for name in ("provenance", "oracle", "offline", "unseen", "smart-llm"):
        start, end = markers(name)
        assert page.count(start) == page.count(end) == 1
    assert (doc.parent / "img" / "results" / "offline_by_category.png").read_bytes() == b"\x89PNG offline"


def test_rerun_is_stable(tmp_path: Path) -> None:
    out, doc = fixture_run(tmp_path / "out"), tmp_path / "results.md"
    doc.write_text(page_with_blocks())
    main(["--skip-run", "--out", str(out), "--doc", str(doc)])
    once = doc.read_text()
    main(["--skip-run", "--out", str(out), "--doc", str(doc)])
    assert doc.read_text() == once


def test_a_block_without_markers_is_appended_not_lost(tmp_path: Path) -> None:
    out, doc = fixture_run(tmp_path / "out"), tmp_path / "results.md"
    doc.write_text(page_with_blocks().replace(block("unseen", "stale unseen 0.567"), ""))
    assert main(["--skip-run", "--out", str(out), "--doc", str(doc)]) == 0
    page = doc.read_text()
    assert HAND in page and OTHER_SCRIPT in page
    assert page.rstrip().endswith(markers("unseen")[1])


@pytest.mark.parametrize("damage", ["drop_end", "repeat_start", "swap"])
def test_unmatched_markers_stop_before_writing(tmp_path: Path, damage: str,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    out, doc = fixture_run(tmp_path / "out"), tmp_path / "results.md"
    start, end = markers("offline")
    page = page_with_blocks()
    page = {"drop_end": page.replace(end, ""),
            "repeat_start": page.replace(HAND, HAND + "\n" + start + "\n"),
            "swap": page.replace(start, "@@").replace(end, start).replace("@@", end)}[damage]
    doc.write_text(page)
    assert main(["--skip-run", "--out", str(out), "--doc", str(doc)]) == 2
    assert doc.read_text() == page
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "offline" in err[0]


def test_missing_run_output_is_one_line_exit_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out, doc = fixture_run(tmp_path / "out"), tmp_path / "results.md"
    (out / "run.json").unlink()
    doc.write_text(page_with_blocks())
    assert main(["--skip-run", "--out", str(out), "--doc", str(doc)]) == 2
    assert doc.read_text() == page_with_blocks()
    assert len(capsys.readouterr().err.strip().splitlines()) == 1


def test_new_page_holds_every_block(tmp_path: Path) -> None:
    out, doc = fixture_run(tmp_path / "out"), tmp_path / "results.md"
    assert main(["--skip-run", "--out", str(out), "--doc", str(doc)]) == 0
    page = doc.read_text()
    assert page.startswith("# Results\n")
    positions = [page.index(markers(n)[0]) for n in ("provenance", "oracle", "offline", "unseen", "smart-llm")]
    assert positions == sorted(positions)


def test_the_repository_page_has_every_block_once() -> None:
    """docs/results.md as committed: make_results.py can rewrite it without appending."""
    names = ("provenance", "oracle", "offline", "unseen", "smart-llm")
    page, appended = splice((ROOT / "docs" / "results.md").read_text(), {n: f"<{n}>" for n in names})
    assert appended == []
    assert [page.index(f"<{n}>") for n in names] == sorted(page.index(f"<{n}>") for n in names)
