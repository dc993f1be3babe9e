"""``DIR/tables.md``: the paper's tables from the episodes of a benchmark run.

- Table 1, methods x category: SR, GCR and Exec per task category and overall, for
  SMART-LLM, LaMMA-P and EmboTeam (modes ``smart-llm``, ``lamma-p``, ``full``);
- Table 2, ablations x category: the same columns for ``full``, ``no-pfg-hp``, ``no-hp``
  and ``no-btc``;
- the SR of every mode at every fault rate (when the run swept fault rates);
- every (mode, front end, fault rate) with the run's other metrics and the 95% bootstrap
  confidence interval of SR.

One Table 1 and one Table 2 per (front end, fault rate) setting, since numbers under
different settings are not comparable. Every number comes from
:func:`emboteam.bench.metrics.summarize` over the episodes of one (mode, front end, fault
rate) group (all tasks and seeds pooled), so the tables, the plots, ``summary.json`` and
``--json`` agree by construction.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from emboteam.bench.metrics import CATEGORY_ORDER, BenchSummary, GroupSummary, summarize
from emboteam.config import ABLATIONS, MODES
from emboteam.exec.episode import Episode

METHOD_LABELS = {"smart-llm": "SMART-LLM", "lamma-p": "LaMMA-P", "full": "EmboTeam"}
ABLATION_LABELS = {"full": "EmboTeam (full)", "no-pfg-hp": "w/o PFG & HP", "no-hp": "w/o HP",
                   "no-btc": "w/o BTC", "no-avoidance": "w/o avoidance"}
MODE_LABELS: dict[str, str] = {**{m: m for m in MODES}, **METHOD_LABELS}
TABLE1_MODES = ("smart-llm", "lamma-p", "full")


def canonical_order(episodes: Iterable[Episode]) -> list[Episode]:
    """Episodes sorted by what they are, not by when they finished: parallel workers finish
    in a different order each run, and the bootstrap CI of :func:`summarize` depends on
    the order it sees tasks in, so reports sort first to be reproducible."""
    return sorted(episodes, key=lambda e: (e.frontend, e.fault_level, e.mode, e.category, e.task, e.seed))


@dataclass(frozen=True, order=True)
class Group:
    """The unit every table cell and plot point is computed over."""

    frontend: str
    fault_level: float
    mode: str


class GroupSummaries:
    """The episodes of a run split into (front end, fault rate, mode) groups, each
    summarised once: the bootstrap CI in :func:`summarize` makes a summary cost tens of
    milliseconds, and tables and plots ask for the same groups many times."""

    def __init__(self, episodes: Iterable[Episode]) -> None:
        self.episodes = canonical_order(episodes)
        self._members: dict[Group, list[Episode]] = {}
        for e in self.episodes:
            self._members.setdefault(Group(e.frontend, e.fault_level, e.mode), []).append(e)
        self._cache: dict[Group, BenchSummary] = {}

    def groups(self, *, frontend: str | None = None, fault_level: float | None = None) -> list[Group]:
        """The groups present, by front end, fault rate, then mode in the tables' order."""
        found = [g for g in self._members
                 if (frontend is None or g.frontend == frontend)
                 and (fault_level is None or g.fault_level == fault_level)]
        return sorted(found, key=lambda g: (g.frontend, g.fault_level, _mode_rank(g.mode)))

    def frontends(self) -> list[str]:
        return sorted({g.frontend for g in self._members})

    def fault_levels(self) -> list[float]:
        return sorted({g.fault_level for g in self._members})

    def settings(self) -> list[tuple[str, float]]:
        return sorted({(g.frontend, g.fault_level) for g in self._members})

    def modes(self) -> list[str]:
        return mode_order(g.mode for g in self._members)

    def get(self, group: Group) -> BenchSummary | None:
        if group not in self._members:
            return None
        if group not in self._cache:
            self._cache[group] = summarize(self._members[group])
        return self._cache[group]

    def categories(self, groups: Iterable[Group]) -> list[str]:
        """The categories of those groups' episodes, in the paper's order."""
        present: set[str] = set()
        for g in groups:
            s = self.get(g)
            present |= set(s.by_category) if s else set()
        return [c for c in CATEGORY_ORDER if c in present] + sorted(present - set(CATEGORY_ORDER))


def _mode_rank(mode: str) -> tuple[int, str]:
    return (MODES.index(mode), "") if mode in MODES else (len(MODES), mode)


def mode_order(modes: Iterable[str]) -> list[str]:
    return sorted(set(modes), key=_mode_rank)


def _pct(x: float) -> str:
    return f"{100 * x:.1f}"


def _row(cells: Sequence[str]) -> str:
    return "| " + " | ".join(cells) + " |"


def _setting_title(frontend: str, fault_level: float) -> str:
    return f"front end `{frontend}`, fault rate {fault_level:g}"


def _sr_gcr_exec(s: GroupSummary | BenchSummary | None) -> list[str]:
    return [_pct(s.sr), _pct(s.gcr), _pct(s.exec)] if s is not None and s.n else ["–", "–", "–"]


def category_table(summaries: GroupSummaries, frontend: str, fault_level: float, modes: Sequence[str],
                   labels: dict[str, str], first: str) -> list[str]:
    """Rows of ``modes`` (those with episodes) x (categories + overall) x (SR, GCR, Exec)."""
    groups = [Group(frontend, fault_level, m) for m in modes]
    groups = [g for g in groups if summaries.get(g) is not None]
    cats = summaries.categories(groups)
    cols = [first]
    for cat in [*cats, "overall"]:
        cols += [f"{cat.capitalize()} SR", f"{cat.capitalize()} GCR", f"{cat.capitalize()} Exec"]
    cols.append("n")
    lines = [_row(cols), _row(["---"] + ["---:"] * (len(cols) - 1))]
    for g in groups:
        s = summaries.get(g)
        assert s is not None  # filtered above
        cells = [labels.get(g.mode, g.mode)]
        for cat in cats:
            cells += _sr_gcr_exec(s.by_category.get(cat))
        cells += [*_sr_gcr_exec(s), str(s.n)]
        lines.append(_row(cells))
    return lines


def fault_sweep_table(summaries: GroupSummaries) -> list[str]:
    """SR (%) of each (mode, front end) at each fault rate."""
    levels = summaries.fault_levels()
    lines = [_row(["Method", "Front end", *(f"SR @ {p:g}" for p in levels)]),
             _row(["---", "---"] + ["---:"] * len(levels))]
    for frontend in summaries.frontends():
        for mode in summaries.modes():
            points = [summaries.get(Group(frontend, p, mode)) for p in levels]
            if any(points):
                lines.append(_row([MODE_LABELS.get(mode, mode), f"`{frontend}`",
                                   *(_pct(s.sr) if s else "–" for s in points)]))
    return lines


def runs_table(summaries: GroupSummaries) -> list[str]:
    """Every (mode, front end, fault rate) with all summary metrics."""
    cols = ["Mode", "Front end", "Faults", "n", "SR", "SR 95% CI", "GCR", "Exec", "errors", "plan s (p50)",
            "makespan s (mean, successes)", "LLM calls (mean)", "tokens (mean)"]
    lines = [_row(cols), _row(["---", "---"] + ["---:"] * (len(cols) - 2))]
    for g in summaries.groups():
        s = summaries.get(g)
        assert s is not None
        lines.append(_row([g.mode, f"`{g.frontend}`", f"{g.fault_level:g}", str(s.n), _pct(s.sr),
                           f"{_pct(s.sr_ci[0])}–{_pct(s.sr_ci[1])}", _pct(s.gcr), _pct(s.exec), str(s.errors),
                           f"{s.plan_seconds_p50:.3f}", f"{s.makespan_mean:.1f}", f"{s.llm_calls_mean:.1f}",
                           f"{s.tokens_mean:.0f}"]))
    return lines


def render_tables(episodes: Sequence[Episode] | GroupSummaries, *, title: str = "Benchmark results",
                  not_applicable: Sequence[str] = ()) -> str:
    """The Markdown of ``tables.md``; ``not_applicable``: ``"TASK: why"`` of the tasks the
    disturbance could not happen in (not run, not in any SR)."""
    summaries = episodes if isinstance(episodes, GroupSummaries) else GroupSummaries(episodes)
    eps = summaries.episodes
    out = [f"# {title}", ""]
    if not eps:
        return "\n".join([*out, "No episodes yet.", ""])
    seeds = sorted({e.seed for e in eps})
    out += [f"{len(eps)} episodes, {len({e.task for e in eps})} tasks, seeds "
            f"{', '.join(map(str, seeds))}. SR, GCR and Exec in percent, averaged over the tasks and "
            "seeds of each cell; n = episodes in the row; – = no episodes of that category.", ""]
    for frontend, level in summaries.settings():
        modes = {g.mode for g in summaries.groups(frontend=frontend, fault_level=level)}
        if modes & set(TABLE1_MODES):
            out += [f"## Table 1: EmboTeam and the baselines ({_setting_title(frontend, level)})", "",
                    *category_table(summaries, frontend, level, TABLE1_MODES, METHOD_LABELS, "Method"), ""]
        if modes & (set(ABLATIONS) - {"full"}):
            out += [f"## Table 2: ablations ({_setting_title(frontend, level)})", "",
                    *category_table(summaries, frontend, level, ABLATIONS, ABLATION_LABELS, "Variant"), ""]
    if len(summaries.fault_levels()) > 1:
        out += ["## Success rate against fault rate", "", *fault_sweep_table(summaries), ""]
    # the disturbance section (bench --breakdown/--join/--moves/--msg-*)
    from emboteam.bench.disturbance_table import disturbance_section

    out += disturbance_section(eps)
    out += not_applicable_section(not_applicable)
    out += ["## All runs", "", *runs_table(summaries), ""]
    return "\n".join(out)


def not_applicable_section(lines: Sequence[str]) -> list[str]:
    """The tasks a disturbance could not happen in, one line each with the reason."""
    if not lines:
        return []
    return [f"## Not applicable ({len(lines)} tasks)", "",
            "The disturbance cannot happen in these tasks: they were not run and count in no SR.", "",
            *(f"- {line}" for line in lines), ""]


def write_tables(episodes: Sequence[Episode] | GroupSummaries, path: Path, *,
                 title: str = "Benchmark results", not_applicable: Sequence[str] = ()) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(render_tables(episodes, title=title, not_applicable=not_applicable))
    return path


def bench_summary(episodes: Iterable[Episode], *, suite: str = "", not_applicable: Sequence[str] = ()) -> BenchSummary:
    """The summary ``emboteam bench --json`` prints (``.to_json()``), in canonical order so
    it is the same whatever order the episodes finished in."""
    summary = summarize(canonical_order(episodes), suite=suite)
    return summary.model_copy(update={"not_applicable": tuple(not_applicable)}) if not_applicable else summary


def write_summary(episodes: Sequence[Episode], path: Path, *, suite: str = "",
                  not_applicable: Sequence[str] = ()) -> Path:
    """``summary.json``: :func:`bench_summary` of the episodes."""
    path = Path(path)
    summary = bench_summary(episodes, suite=suite, not_applicable=not_applicable)
    path.write_text(json.dumps(summary.to_json(), indent=1) + "\n")
    return path


# --------------------------------------------------------------------------- the terminal

def _cells(line: str) -> list[str]:
    return [c.strip().strip("`") for c in line.strip().strip("|").split("|")]


def _split_columns(widths: Sequence[int], keys: int, width: int) -> list[list[int]]:
    """Column groups that each fit ``width`` with the ``keys`` label columns repeated: a
    table too wide for the terminal is shown as several tables, never with a cell cut."""
    def table_width(cols: Sequence[int]) -> int:
        return sum(widths[c] + 3 for c in cols) + 1  # a cell's padding and border: 3

    label = list(range(keys))
    groups: list[list[int]] = []
    current: list[int] = []
    for col in range(keys, len(widths)):
        if current and table_width(label + current + [col]) > width:
            groups.append(current)
            current = []
        current.append(col)
    if current or not groups:
        groups.append(current)
    return [label + g for g in groups]


def _rich_table(rows: list[list[str]], align: list[str], width: int) -> list[Any]:
    from rich.table import Table
    from rich.text import Text

    header, body = rows[0], rows[1:]
    n = len(header)
    numeric = [a.endswith(":") for a in align] + [False] * (n - len(align))
    keys = next((i for i, num in enumerate(numeric) if num), n) or 1  # the leading label columns
    # a header may wrap at its spaces; a value never does
    widths = [max([max((len(w) for w in header[c].split()), default=1)]
                  + [len(r[c]) for r in body if c < len(r)]) for c in range(n)]
    out: list[Any] = []
    for cols in _split_columns(widths, keys, width):
        table = Table(show_lines=False, pad_edge=True)
        for c in cols:
            table.add_column(Text(header[c]), justify="right" if numeric[c] else "left",
                             min_width=widths[c], overflow="fold")
        for r in body:
            table.add_row(*(Text(r[c] if c < len(r) else "") for c in cols))
        out.append(table)
    return out


def terminal_tables(markdown: str, *, width: int) -> list[Any]:
    """``tables.md`` as Rich renderables for a terminal ``width`` columns wide.

    Rich's Markdown squeezes a wide table into the terminal by cutting cells
    (``Paral…``, ``100…``); here every table keeps whole numbers and labels, and one too
    wide is split into several that repeat its label columns."""
    from rich.text import Text

    out: list[Any] = []
    lines = markdown.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.lstrip().startswith("|"):
            block: list[str] = []
            while i < len(lines) and lines[i].lstrip().startswith("|"):
                block.append(lines[i])
                i += 1
            rows = [_cells(b) for b in block]
            align = rows[1] if len(rows) > 1 and all(set(c) <= set(":-") for c in rows[1]) else []
            body = [rows[0], *rows[2:]] if align else rows
            out += _rich_table(body, align, width)
            continue
        if line.startswith("#"):
            out.append(Text(line.lstrip("#").strip().replace("`", ""), style="bold"))
        elif line.strip():
            out.append(Text(line.replace("`", "")))
        else:
            out.append(Text(""))
        i += 1
    return out
