"""The benchmark index: ``DIR/index.html`` with the summary, the tables, the plots and one
sortable, filterable row per episode linking to its viewer (``episodes/<key>/report.html``).

Self-contained like the episode viewer: plots are embedded as ``data:`` URIs, the tables'
Markdown is rendered here (markdown-it-py, with raw HTML disabled so a task name cannot
inject markup), and the rows travel as JSON drawn by ``assets/bench.js``.
"""

from __future__ import annotations

import base64
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any
from urllib.parse import quote

from markdown_it import MarkdownIt

from emboteam import __version__
from emboteam.exec.episode import Episode
from emboteam.report.episode_report import REPORT_NAME, write_episode_report
from emboteam.report.loading import ReportError
from emboteam.report.page import render_page

INDEX_NAME = "index.html"
EPISODES_DIR = "episodes"

_IMAGE_TYPES = {".png": "image/png", ".svg": "image/svg+xml", ".jpg": "image/jpeg", ".jpeg": "image/jpeg",
                ".gif": "image/gif", ".webp": "image/webp"}

EpisodeRows = Mapping[str, Episode] | Iterable[tuple[str, Episode]]


def markdown_to_html(text: str) -> str:
    """CommonMark + pipe tables; raw HTML in the source is escaped, not passed through."""
    md = MarkdownIt("commonmark", {"html": False}).enable("table")
    html: str = md.render(text)
    return html


def _plot(path: Path) -> dict[str, str]:
    kind = _IMAGE_TYPES.get(path.suffix.lower())
    if kind is None:
        raise ReportError(f"plot {path}: unsupported image type {path.suffix or '(none)'} "
                          f"(use {', '.join(sorted(_IMAGE_TYPES))})")
    try:
        payload = base64.b64encode(path.read_bytes()).decode("ascii")
    except OSError as exc:
        raise ReportError(f"cannot read plot {path}: {exc}") from None
    title = path.stem.replace("_", " ").replace("-", " ")
    return {"title": title, "file": path.name, "src": f"data:{kind};base64,{payload}"}


def _row(directory: Path, key: str, ep: Episode) -> dict[str, Any]:
    episode_dir = directory / EPISODES_DIR / key
    report = episode_dir / REPORT_NAME
    if not report.exists() and (episode_dir / "episode.json").exists():
        write_episode_report(episode_dir)  # a run killed between saving and reporting
    return {
        "key": key, "task": ep.task, "category": ep.category, "mode": ep.mode, "frontend": ep.frontend,
        "seed": ep.seed, "faults": ep.fault_level, "success": ep.success, "gcr": ep.gcr, "exec": ep.exec,
        "makespan": ep.makespan, "actions": ep.actions, "llm_calls": ep.llm_calls, "tokens": ep.tokens,
        "robots": len(ep.robots), "error": ep.error or "",
        "link": f"{EPISODES_DIR}/{quote(key)}/{REPORT_NAME}" if report.exists() else None,
    }


def bench_view(directory: Path, episodes: EpisodeRows, summary: Mapping[str, Any],
               plots: Sequence[Path]) -> dict[str, Any]:
    pairs = list(episodes.items()) if isinstance(episodes, Mapping) else list(episodes)
    keys = [k for k, _ in pairs]
    if len(keys) != len(set(keys)):
        dup = sorted({k for k in keys if keys.count(k) > 1})
        raise ReportError(f"episode keys must be unique; repeated: {', '.join(dup[:5])}")
    for key in keys:
        if not key or "/" in key or "\\" in key or key in (".", ".."):
            raise ReportError(f"episode key {key!r} is not a directory name under {EPISODES_DIR}/")
    return {
        "generator": f"emboteam {__version__}",
        "summary": dict(summary),
        "rows": [_row(directory, k, ep) for k, ep in pairs],
        "plots": [_plot(Path(p)) for p in plots],
    }


def render_bench_index(directory: Path, episodes: EpisodeRows, summary: Mapping[str, Any], tables_md: str,
                       plots: Sequence[Path]) -> str:
    suite = str(summary.get("suite", "benchmark"))
    tables = markdown_to_html(tables_md) if tables_md.strip() else ""
    return render_page("bench.html", title=f"{suite} · EmboTeam benchmark", styles=["common.css", "bench.css"],
                       scripts=["common.js", "bench.js"],
                       data=bench_view(directory, episodes, summary, plots), body=tables)


def write_bench_index(directory: Path, episodes: EpisodeRows, summary: Mapping[str, Any], tables_md: str,
                      plots: Sequence[Path]) -> Path:
    """Write ``directory/index.html``; return its path.

    ``episodes``: (key, Episode) pairs or a key -> Episode mapping, where key is the
    episode's directory name under ``directory/episodes`` (the bench runner's job
    directory); an episode whose ``report.html`` is missing gets one built first.
    ``summary``: the ``emboteam bench --json`` object. ``tables_md``: Markdown (tables,
    headings, text). ``plots``: image files (PNG, SVG, ...) embedded in the page.
    """
    directory = Path(directory)
    html = render_bench_index(directory, episodes, summary, tables_md, plots)
    out = directory / INDEX_NAME
    try:
        directory.mkdir(parents=True, exist_ok=True)
        out.write_text(html, encoding="utf-8")
    except OSError as exc:
        raise ReportError(f"cannot write {out}: {exc}") from None
    return out
