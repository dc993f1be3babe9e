"""PNG plots of a benchmark run (matplotlib's object API with the Agg canvas: no display,
no pyplot global state).

- ``by_category.png``: SR, GCR and Exec per task category and overall, one bar per mode
  (grouped bars), at the run's lowest fault rate (the nominal condition);
- ``sr_vs_faults.png`` (only when the run has two or more fault rates): SR against the
  fault rate, one line per mode, error bars = the 95% bootstrap confidence interval of SR
  (:func:`emboteam.bench.metrics.summarize` resamples tasks).

A mode run with several front ends gets one series per front end ("EmboTeam (llm)").
Numbers come from the same per-group summaries as the tables.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from matplotlib.figure import Figure

from emboteam.bench.tables import MODE_LABELS, Group, GroupSummaries
from emboteam.config import MODES
from emboteam.exec.episode import Episode

#: one fixed colour per mode (tab10), so a mode looks the same in every plot
_COLOURS: dict[str, str] = {mode: f"C{i}" for i, mode in enumerate(MODES)}
_MARKERS = "osD^vP*X"
#: a front end's bar hatch and line style, so one mode under two front ends stays apart
_FRONTEND_STYLE = {"offline": ("", "-"), "oracle": ("..", ":"), "llm": ("//", "--")}


@dataclass(frozen=True)
class Series:
    label: str
    colour: str
    hatch: str
    linestyle: str
    frontend: str
    mode: str


def _series(summaries: GroupSummaries, groups: Sequence[Group]) -> list[Series]:
    """One series per mode, or per (mode, front end) if the front ends vary."""
    several = len(summaries.frontends()) > 1
    out: list[Series] = []
    for frontend, mode in dict.fromkeys((g.frontend, g.mode) for g in groups):
        hatch, linestyle = _FRONTEND_STYLE.get(frontend, ("xx", "-."))
        label = MODE_LABELS.get(mode, mode) + (f" ({frontend})" if several else "")
        out.append(Series(label, _COLOURS.get(mode, "C9"), hatch, linestyle, frontend, mode))
    return out


def plot_by_category(summaries: GroupSummaries, path: Path) -> Path:
    level = summaries.fault_levels()[0]
    groups = summaries.groups(fault_level=level)
    columns = [*summaries.categories(groups), "overall"]
    series = _series(summaries, groups)
    fig = Figure(figsize=(4.2 * 3, 4.0), layout="constrained")
    axes = fig.subplots(1, 3, sharey=True)
    width = 0.8 / max(len(series), 1)
    for ax, metric in zip(axes, ("sr", "gcr", "exec"), strict=True):
        for i, ser in enumerate(series):
            s = summaries.get(Group(ser.frontend, level, ser.mode))
            assert s is not None  # a series exists only for groups with episodes
            values = []
            for col in columns:
                cell = s if col == "overall" else s.by_category.get(col)
                values.append(100 * getattr(cell, metric) if cell is not None and cell.n else 0.0)
            xs = [c + (i - (len(series) - 1) / 2) * width for c in range(len(columns))]
            ax.bar(xs, values, width, label=ser.label, color=ser.colour, hatch=ser.hatch or None,
                   edgecolor="black" if ser.hatch else "white", linewidth=0.5)
        ax.set_title({"sr": "SR", "gcr": "GCR", "exec": "Exec"}[metric])
        ax.set_xticks(range(len(columns)), [c.capitalize() for c in columns])
        ax.set_ylim(0, 105)
        ax.grid(axis="y", alpha=0.3)
    axes[0].set_ylabel("%")
    axes[-1].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small")
    n = sum(s.n for s in map(summaries.get, groups) if s is not None)
    fig.suptitle(f"SR / GCR / Exec by category and mode (fault rate {level:g}, {n} episodes)")
    fig.savefig(path, dpi=120)
    return path


def plot_sr_vs_faults(summaries: GroupSummaries, path: Path) -> Path:
    fig = Figure(figsize=(6.4, 4.4), layout="constrained")
    ax = fig.subplots()
    levels = summaries.fault_levels()
    series = _series(summaries, summaries.groups())
    # a small sideways shift per series keeps overlapping confidence intervals readable
    shift = 0.012 * (levels[-1] - levels[0])
    for i, ser in enumerate(series):
        offset = (i - (len(series) - 1) / 2) * shift
        xs: list[float] = []
        ys: list[float] = []
        below: list[float] = []
        above: list[float] = []
        for p in levels:
            s = summaries.get(Group(ser.frontend, p, ser.mode))
            if s is None:
                continue
            xs.append(p + offset)
            ys.append(100 * s.sr)
            below.append(100 * max(s.sr - s.sr_ci[0], 0.0))
            above.append(100 * max(s.sr_ci[1] - s.sr, 0.0))
        ax.errorbar(xs, ys, yerr=[below, above], label=ser.label, color=ser.colour, linestyle=ser.linestyle,
                    marker=_MARKERS[i % len(_MARKERS)], capsize=3)
    ax.set_xlabel("fault rate (action failure probability)")
    ax.set_ylabel("SR (%)")
    ax.set_ylim(-2, 102)
    ax.set_xticks(levels)
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small")
    ax.set_title("Success rate against fault rate (95% CI)")
    fig.savefig(path, dpi=120)
    return path


def write_plots(episodes: Sequence[Episode] | GroupSummaries, out_dir: Path) -> list[Path]:
    """Write the plots that the episodes support; return their paths."""
    summaries = episodes if isinstance(episodes, GroupSummaries) else GroupSummaries(episodes)
    out_dir = Path(out_dir)
    if not summaries.episodes:
        return []
    out_dir.mkdir(parents=True, exist_ok=True)
    written = [plot_by_category(summaries, out_dir / "by_category.png")]
    if len(summaries.fault_levels()) > 1:
        written.append(plot_sr_vs_faults(summaries, out_dir / "sr_vs_faults.png"))
    return written
