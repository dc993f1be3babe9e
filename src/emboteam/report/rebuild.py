"""``emboteam report DIR``: rebuild the HTML of a run or of a benchmark from its files.

A run directory holds ``episode.json``; a benchmark directory holds
``episodes/<key>/episode.json`` for each episode, plus (when the bench runner wrote
them) ``summary.json`` (the ``bench --json`` object), ``tables.md`` and plot images
(``*.png`` / ``*.svg`` in DIR or ``DIR/plots``). A summary that is missing is recomputed
from the episodes (n, SR, GCR, Exec means), so an interrupted benchmark still gets an index.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from emboteam.exec.episode import Episode
from emboteam.report.bench_index import EPISODES_DIR, write_bench_index
from emboteam.report.episode_report import save_episode_report, write_episode_report
from emboteam.report.loading import ReportError, load_episode_dir

SUMMARY_NAME = "summary.json"
TABLES_NAME = "tables.md"
PLOT_SUFFIXES = (".png", ".svg")


def _summary(directory: Path, episodes: list[Episode]) -> dict[str, Any]:
    path = directory / SUMMARY_NAME
    if not path.exists():
        from emboteam.bench.tables import bench_summary

        return {**bench_summary(episodes).to_json(), "note": "recomputed from the episodes (no summary.json)"}
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ReportError(f"cannot read {path}: {exc}") from None
    if not isinstance(data, dict):
        raise ReportError(f"{path}: expected a JSON object")
    return data


def _plots(directory: Path) -> list[Path]:
    found: list[Path] = []
    for folder in (directory, directory / "plots"):
        if folder.is_dir():
            found += sorted(p for p in folder.iterdir() if p.suffix.lower() in PLOT_SUFFIXES and p.is_file())
    return found


def write_report(directory: Path, *, refresh: bool = True) -> list[Path]:
    """Rebuild every report page under ``directory``; return the pages written (a
    benchmark: each episode's viewer, then the index last). ``refresh=False`` keeps the
    episode pages that exist (a resumed benchmark renders only its new episodes)."""
    directory = Path(directory)
    if (directory / "episode.json").is_file():
        return [write_episode_report(directory)]
    episodes_root = directory / EPISODES_DIR
    if not episodes_root.is_dir():
        raise ReportError(f"{directory} holds neither episode.json (a run) nor {EPISODES_DIR}/ (a benchmark)")
    written: list[Path] = []
    pairs: list[tuple[str, Episode]] = []
    for sub in sorted(p for p in episodes_root.iterdir() if (p / "episode.json").is_file()):
        episode = load_episode_dir(sub)
        pairs.append((sub.name, episode))
        if refresh or not (sub / "report.html").is_file():
            written.append(save_episode_report(episode, sub))
    tables = directory / TABLES_NAME
    tables_md = tables.read_text(encoding="utf-8") if tables.is_file() else ""
    summary = _summary(directory, [ep for _, ep in pairs])
    written.append(write_bench_index(directory, pairs, summary, tables_md, _plots(directory)))
    return written
