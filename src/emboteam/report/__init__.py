"""HTML reports: the episode viewer (``DIR/report.html``) and the benchmark index
(``DIR/index.html``), each one self-contained file that opens from ``file://``.

Public API (the CLI wires ``emboteam run --out``, ``emboteam bench --out`` and
``emboteam report DIR`` to it)::

    write_episode_report(directory) -> Path
    save_episode_report(episode, directory) -> Path
    write_bench_index(directory, episodes, summary, tables_md, plots) -> Path
    write_report(directory) -> list[Path]      # what `emboteam report DIR` does

docs/report.md describes the pages.
"""

from emboteam.report.bench_index import render_bench_index, write_bench_index
from emboteam.report.episode_report import (
    episode_view,
    render_episode_report,
    save_episode_report,
    write_episode_report,
)
from emboteam.report.loading import ReportError, load_episode_dir
from emboteam.report.rebuild import write_report

__all__ = ["ReportError", "episode_view", "load_episode_dir", "render_bench_index", "render_episode_report",
           "save_episode_report", "write_bench_index", "write_episode_report", "write_report"]
