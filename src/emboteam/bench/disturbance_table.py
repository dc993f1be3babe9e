"""The "Disturbances" section of ``tables.md``: per (disturbance, front end, fault rate, mode)
the SR, the ceiling's savable share, SR of savable, how unsavable episodes ended and how
often a joining robot took work (docs/metrics.md)."""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.bench.disturbance_metrics import DisturbanceSummary, summarize_disturbance
from emboteam.config import MODES
from emboteam.exec.episode import Episode

#: how Table 1 names the modes
LABELS = {"full": "EmboTeam", "no-btc": "w/o BTC", "no-hp": "w/o HP", "no-pfg-hp": "w/o PFG & HP",
          "smart-llm": "SMART-LLM", "lamma-p": "LaMMA-P"}

COLUMNS = ["Disturbance", "Method", "Front end", "Faults", "n", "SR", "savable", "SR of savable",
           "unsavable: typed end", "unsavable: max wall s", "joiner took over", "lost releases / lock timeouts",
           "late flag reads"]


def _pct(x: float | None) -> str:
    return "–" if x is None else f"{100 * x:.1f}"


def disturbance_row(spec: str, mode: str, frontend: str, fault_level: float, s: DisturbanceSummary) -> list[str]:
    joiner = f"{s.joiner_took_over}/{s.joined}" if s.joined else "–"
    typed = f"{s.unsavable_typed}/{s.unsavable}" if s.unsavable else "–"
    wall = f"{s.unsavable_wall_max:.2f}" if s.unsavable_wall_max is not None else "–"
    return [f"`{spec}`", LABELS.get(mode, mode), f"`{frontend}`", f"{fault_level:g}", str(s.n), _pct(s.sr),
            f"{s.savable}/{s.savable + s.unsavable}" + (f" (+{s.unknown} ?)" if s.unknown else ""),
            _pct(s.sr_savable), typed, wall, joiner, f"{s.lost_releases} / {s.lock_timeouts}", str(s.late_reads)]


def disturbance_rows(episodes: Sequence[Episode]) -> list[list[str]]:
    groups: dict[tuple[str, str, float, str], list[Episode]] = {}
    for e in episodes:
        if e.disturbance is not None:
            groups.setdefault((e.disturbance.spec, e.frontend, e.fault_level, e.mode), []).append(e)

    def rank(key: tuple[str, str, float, str]) -> tuple[str, str, float, int]:
        spec, frontend, level, mode = key
        return (spec, frontend, level, MODES.index(mode) if mode in MODES else len(MODES))

    rows = []
    for key in sorted(groups, key=rank):
        s = summarize_disturbance(groups[key])
        if s is not None:
            spec, frontend, level, mode = key
            rows.append(disturbance_row(spec, mode, frontend, level, s))
    return rows


def render_rows(rows: Sequence[Sequence[str]]) -> list[str]:
    lines = ["| " + " | ".join(COLUMNS) + " |", "| " + " | ".join(["---"] * 4 + ["---:"] * (len(COLUMNS) - 4)) + " |"]
    return lines + ["| " + " | ".join(r) + " |" for r in rows]


def disturbance_section(episodes: Sequence[Episode]) -> list[str]:
    """Markdown lines of the section ([] when no episode was disturbed by options)."""
    rows = disturbance_rows(episodes)
    if not rows:
        return []
    return ["## Disturbances", "",
            "SR and SR of savable in percent; savable = episodes whose goal the planner could still reach "
            "from the state after the disturbance with the robots left (a success counts as savable); "
            "wall s = wall-clock seconds from the disturbance to the end.", "",
            *render_rows(rows), ""]
