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
from emboteam.report.episode_report import save_episode_report
from emboteam.report.loading import ReportError, load_episode_dir

SUMMARY_NAME = "summary.json"
TABLES_NAME = "tables.md"
PLOT_SUFFIXES = (".png", ".svg")


def _summary_of(episodes: list[Episode]) -> dict[str, Any]:
    from emboteam.bench.tables import bench_summary

    return {**bench_summary(episodes).to_json(), "note": "recomputed from the episodes (no summary.json)"}


def _summary(directory: Path, episodes: list[Episode]) -> dict[str, Any]:
    path = directory / SUMMARY_NAME
    if not path.exists():
        return _summary_of(episodes)
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


def write_report(directory: Path, *, refresh: bool = True, problems: list[str] | None = None) -> list[Path]:
    """Rebuild every report page under ``directory``; return the pages written (a
    benchmark: each episode's viewer, then the index last). ``refresh=False`` keeps the
    episode pages that exist (a resumed benchmark renders only its new episodes).

    With a ``problems`` list, what is broken is skipped and described there and the rest
    is built: an episode whose episode.json cannot be read is left out of the index, a
    bad trace.jsonl line is left out of its episode's viewer. Without it, the first
    problem raises :class:`ReportError`."""
    directory = Path(directory)
    if (directory / "episode.json").is_file():
        episode = load_episode_dir(directory, problems)
        return [save_episode_report(episode, directory)]
    episodes_root = directory / EPISODES_DIR
    if not episodes_root.is_dir():
        raise ReportError(f"{directory} holds neither episode.json (a run) nor {EPISODES_DIR}/ (a benchmark)")
    written: list[Path] = []
    pairs: list[tuple[str, Episode]] = []
    for sub in sorted(p for p in episodes_root.iterdir() if (p / "episode.json").is_file()):
        try:
            episode = load_episode_dir(sub, problems)
        except ReportError as exc:
            if problems is None:
                raise
            problems.append(f"{exc}; episode left out of the index")
            continue
        pairs.append((sub.name, episode))
        if refresh or not (sub / "report.html").is_file():
            written.append(save_episode_report(episode, sub))
    tables = directory / TABLES_NAME
    tables_md = tables.read_text(encoding="utf-8") if tables.is_file() else ""
    if problems:  # the index says what it is missing, not only the terminal
        tables_md += "\n\n## Left out of this report\n\n" + "".join(f"- `{p}`\n" for p in problems)
    try:
        summary = _summary(directory, [ep for _, ep in pairs])
    except ReportError as exc:
        if problems is None:
            raise
        problems.append(f"{exc}; summary recomputed from the episodes")
        summary = _summary_of([ep for _, ep in pairs])
    written.append(write_bench_index(directory, pairs, summary, tables_md, _plots(directory)))
    return written
