"""Measure Table 1's Dyn. Team / State Sync / Dyn. Replan columns: EmboTeam, the no-BTC
ablation, LaMMA-P and SMART-LLM on MACE-THOR (ground-truth goals, fault rate 0.2, 3 seeds)
under the same seeded disturbances, and write the "Disturbances" section of docs/results.md.

    .venv/bin/python benchmarks/disturbances.py [--out /tmp/disturbances] [--workers 2] [--skip-run]

Each disturbance is one ``emboteam bench`` run (resumable: rerun after an interruption and it
continues); the section is rebuilt from each run's ``summary.json``. Only the part of
docs/results.md between the ``disturbances`` markers is replaced.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from emboteam.bench.disturbance_metrics import DisturbanceSummary  # noqa: E402
from emboteam.bench.disturbance_table import LABELS, disturbance_row, render_rows  # noqa: E402

EMBOTEAM = str(Path(sys.executable).parent / "emboteam")
MODES = ["--ablation", "full", "--ablation", "no-btc", "--baseline", "lamma-p", "--baseline", "smart-llm"]
COMMON = ["--suite", "mace-thor", "--frontend", "oracle", "--faults", "0.2", "--seeds", "3"]
#: name -> options; the Table 1 column each measures
SETTINGS: dict[str, tuple[list[str], str]] = {
    "breakdown": (["--breakdown", "random@0.3"], "Dyn. Team"),
    "join": (["--join", "random@30%"], "Dyn. Team"),
    "moves": (["--moves", "random@0.5"], "Dyn. Replan"),
    "msg-loss": (["--msg-loss", "0.5"], "State Sync"),
    "msg-delay": (["--msg-delay", "3"], "State Sync"),
}
START, END = "<!-- disturbances:start -->", "<!-- disturbances:end -->"
ORDER = ["full", "no-btc", "lamma-p", "smart-llm"]


def command(name: str, out: Path, workers: int) -> list[str]:
    return [EMBOTEAM, "bench", *COMMON, *SETTINGS[name][0], *MODES, "--workers", str(workers),
            "--out", str(out / name), "--json"]


def run(name: str, out: Path, workers: int) -> None:
    args = command(name, out, workers)
    if (out / name / "results.sqlite").exists():
        args.append("--resume")
    print("$", " ".join(args), file=sys.stderr, flush=True)
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)


def summaries(out: Path, name: str) -> dict[str, DisturbanceSummary]:
    data = json.loads((out / name / "summary.json").read_text())
    return {m: DisturbanceSummary.model_validate(s) for m, s in data.get("disturbance_by_mode", {}).items()}


def pct(x: float | None) -> str:
    return "–" if x is None else f"{100 * x:.1f}"


def section(out: Path) -> str:
    found = {name: summaries(out, name) for name in SETTINGS if (out / name / "summary.json").exists()}
    shown = " ".join(["emboteam bench", *COMMON, *MODES, "--workers 2"])
    lines = [START, "## Disturbances: breakdowns, joiners, moved objects, a lossy blackboard", "",
             "Table 1's Dyn. Team, State Sync and Dyn. Replan columns, measured: every method on MACE-THOR "
             "with ground-truth goals, fault rate 0.2, seeds 0–2, under the same seeded disturbance (the same "
             "robot breaks down at the same moment, the same object is moved, in every mode). *SR of savable* "
             "counts successes among the episodes whose goal the planner could still reach from the state after "
             "the disturbance with the robots left (docs/metrics.md). Regenerate with:", "",
             "```", ".venv/bin/python benchmarks/disturbances.py --workers 2", "```", "",
             "which runs, per disturbance,", "", "```", shown + " --breakdown random@0.3   # or:",
             "    --join random@30% | --moves random@0.5 | --msg-loss 0.5 | --msg-delay 3", "```", ""]
    head = ["Method", "Breakdown: SR of savable", "Join: SR", "Join: joiner took over", "Moved object: SR",
            "Lost lock releases: SR", "Late flags: SR"]
    lines += ["| " + " | ".join(head) + " |", "| --- |" + " ---: |" * (len(head) - 1)]
    for mode in ORDER:
        b, j, m, lo, de = (found.get(n, {}).get(mode) for n in ("breakdown", "join", "moves", "msg-loss", "msg-delay"))
        took = f"{j.joiner_took_over}/{j.joined}" if j and j.joined else "–"
        lines.append("| " + " | ".join([LABELS.get(mode, mode), pct(b.sr_savable if b else None),
                                        pct(j.sr if j else None), took, pct(m.sr if m else None),
                                        pct(lo.sr if lo else None), pct(de.sr if de else None)]) + " |")
    rows = [disturbance_row(s.spec, mode, "oracle", 0.2, s)
            for name in SETTINGS for mode in ORDER if (s := found.get(name, {}).get(mode)) is not None]
    lines += ["", "Every disturbance and method in detail (n counts the episodes that reached execution: an "
              "episode whose planning failed before it, such as LaMMA-P's admissible search timing out on "
              "fp15-cook-egg, has no disturbance record; the baselines' low SR is mostly the fault rate 0.2, "
              "which they do not recover from, see the fault sweep above):", "", *render_rows(rows), ""]
    return "\n".join(lines) + "\n" + END


def write(out: Path) -> None:
    path = ROOT / "docs" / "results.md"
    page = path.read_text()
    text = section(out)
    if START in page and END in page:
        before, rest = page.split(START, 1)
        page = before + text + rest.split(END, 1)[1]
    else:
        page = page.rstrip("\n") + "\n\n" + text + "\n"
    path.write_text(page)
    print(f"wrote the disturbances section of {path}", file=sys.stderr)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("/tmp/disturbances"))
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--skip-run", action="store_true", help="only rebuild the section from --out")
    ap.add_argument("--only", action="append", choices=sorted(SETTINGS), help="run only these disturbances")
    args = ap.parse_args()
    # `emboteam bench --out` refuses a missing parent folder (a typo should not scatter
    # results); this script owns --out, so it makes the folder its runs go into.
    args.out.mkdir(parents=True, exist_ok=True)
    if not args.skip_run:
        for name in args.only or SETTINGS:
            run(name, args.out, args.workers)
    write(args.out)


if __name__ == "__main__":
    main()
