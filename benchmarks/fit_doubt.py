"""Fit the doubt detector's weights (emboteam.pfg.doubt) on development rounds only.

Reads the per-task rows of ``benchmarks/frontend_routing.py --out DIR`` (features of the
offline reading, and whether it was right: the offline episode succeeds where the oracle
does) and searches a small grid of weights and thresholds for :func:`doubt_score`:

- among the combinations flagging at most ``--max-right`` of the right readings on the
  fitting rounds, the one flagging the most wrong readings; ties go to fewer right
  readings flagged, then to the simplest (fewest non-zero weights).

The fitting rounds are the blind rounds up to ``--fit-until`` (default 29), the held-out
halves read as development data and the offline development sets; every other round
(later blind rounds, MACE-THOR, rounds added later) only measures the result. The grid
is searched exhaustively (a few thousand combinations, numpy-free on purpose: the rows
are a few thousand).

    .venv/bin/python benchmarks/fit_doubt.py /tmp/routing/rows.jsonl [more rows.jsonl ...]

Prints the weights, the threshold and the fitted rounds to paste into pfg/doubt.py, and
the detector's shares on the fitted and the other rounds.
"""

from __future__ import annotations

import argparse
import itertools
import json
import re
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from emboteam.pfg.doubt import signals

SIGNALS = ("notes", "note_count", "unexplained", "words_per_condition", "turns", "ambiguous", "quantity")
GRID: dict[str, tuple[float, ...]] = {
    "notes": (0.0, 1.0), "note_count": (0.0, 0.5), "unexplained": (0.0, 0.5, 1.0),
    "words_per_condition": (0.0, 0.05, 0.1, 0.2), "turns": (0.0, 0.5, 1.0), "ambiguous": (0.0, 0.5, 1.0),
    "quantity": (0.0, 1.0),
}
THRESHOLDS = (0.5, 1.0, 1.5, 2.0)


def is_fitting_round(name: str, fit_until: int) -> bool:
    m = re.fullmatch(r"blind_r(\d+)", name)
    if m:
        return int(m.group(1)) <= fit_until
    return name.endswith("-heldout") or name.startswith("offline_dev")


def labelled(rows: Sequence[dict[str, Any]]) -> list[tuple[str, dict[str, float], bool]]:
    """(round, signals, wrong) for every reading the oracle can score; failed parses left
    out (they are always flagged: nothing to fit)."""
    return [(r["round"], signals(r["features"]), not r["offline_success"]) for r in rows
            if r["oracle_success"] and r["features"].get("error") is None]


def shares(data: Sequence[tuple[str, dict[str, float], bool]], weights: dict[str, float],
           threshold: float) -> tuple[int, int, int, int]:
    wf = wn = rf = rn = 0
    for _, x, wrong in data:
        flagged = sum(weights[k] * x[k] for k in SIGNALS) >= threshold
        if wrong:
            wn += 1
            wf += flagged
        else:
            rn += 1
            rf += flagged
    return wf, wn, rf, rn


def fit(data: Sequence[tuple[str, dict[str, float], bool]], max_right: float) -> tuple[dict[str, float], float]:
    best: tuple[Any, ...] | None = None
    for combo in itertools.product(*(GRID[k] for k in SIGNALS)):
        weights = dict(zip(SIGNALS, combo, strict=True))
        for threshold in THRESHOLDS:
            wf, _, rf, rn = shares(data, weights, threshold)
            if rn and rf / rn > max_right:
                continue
            key = (wf, -rf, -sum(1 for w in combo if w))
            if best is None or key > best[0]:
                best = (key, weights, threshold)
    if best is None:
        raise SystemExit("no combination flags few enough right readings")
    return best[1], best[2]


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("rows", nargs="+", type=Path)
    ap.add_argument("--fit-until", type=int, default=29, help="blind rounds up to this number are fitted on")
    ap.add_argument("--max-right", type=float, default=0.15, help="at most this share of right readings flagged")
    args = ap.parse_args(argv)
    rows = [json.loads(line) for p in args.rows for line in p.read_text().splitlines() if line.strip()]
    data = labelled(rows)
    fitting = [d for d in data if is_fitting_round(d[0], args.fit_until)]
    other = [d for d in data if not is_fitting_round(d[0], args.fit_until)]
    weights, threshold = fit(fitting, args.max_right)
    print("WEIGHTS =", json.dumps(weights))
    print("THRESHOLD =", threshold)
    print("FITTED_ON =", sorted({d[0] for d in fitting}))
    notes_only = {k: float(k == "notes") for k in SIGNALS}
    for name, part in (("fitted rounds", fitting), ("other rounds", other)):
        wf, wn, rf, rn = shares(part, weights, threshold)
        nwf, _, nrf, _ = shares(part, notes_only, 1.0)
        print(f"{name}: wrong flagged {wf}/{wn}, right flagged {rf}/{rn} "
              f"(the parser's notes alone: {nwf}/{wn}, {nrf}/{rn})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
