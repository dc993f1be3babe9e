"""Convert ALFRED's navigation layouts into package data (src/emboteam/world/data/nav/).

Reads ``../shared/data/ai2thor/alfred_layouts/FloorPlanN-layout.npy`` (reachable (x, z)
positions on AI2-THOR's 0.25 m grid, AI2-THOR 2.1) and ``FloorPlanN-openable.json``
(a pose from which ALFRED opened each openable object) and writes one small gzipped JSON
per floor plan: the cells as integer grid indices (x / 0.25, z / 0.25) and the openable
poses. ALFRED is MIT-licensed: its LICENSE is copied beside the data as LICENSE.txt.

Needs numpy (a build-time dependency only: the package reads the JSON):

    python3 scripts/build_nav_data.py
"""

from __future__ import annotations

import gzip
import json
import shutil
import sys
from pathlib import Path

import numpy as np

GRID = 0.25
ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT.parent / "shared" / "data" / "ai2thor" / "alfred_layouts"
TARGET = ROOT / "src" / "emboteam" / "world" / "data" / "nav"


def convert(floor_plan: str) -> dict[str, object]:
    layout = np.load(SOURCE / f"{floor_plan}-layout.npy")
    cells = sorted({(round(float(x) / GRID), round(float(z) / GRID)) for x, z in layout})
    for x, z in layout.tolist():
        if abs(x / GRID - round(x / GRID)) > 1e-6 or abs(z / GRID - round(z / GRID)) > 1e-6:
            raise SystemExit(f"{floor_plan}: ({x}, {z}) is not on the 0.25 m grid")
    openable_path = SOURCE / f"{floor_plan}-openable.json"
    openable = json.loads(openable_path.read_text()) if openable_path.exists() else {}
    return {"floor_plan": floor_plan, "grid": GRID, "source": "ALFRED gen/layouts (MIT)",
            "cells": [list(c) for c in cells],
            "openable": {k: [float(v[0]), float(v[1]), int(v[2]) % 360] for k, v in sorted(openable.items())}}


def main() -> int:
    TARGET.mkdir(parents=True, exist_ok=True)
    plans = sorted((p.name.removesuffix("-layout.npy") for p in SOURCE.glob("FloorPlan*-layout.npy")),
                   key=lambda n: int(n.removeprefix("FloorPlan")))
    total = 0
    for fp in plans:
        data = json.dumps(convert(fp), separators=(",", ":"), sort_keys=True).encode()
        blob = gzip.compress(data, mtime=0)
        (TARGET / f"{fp}.json.gz").write_bytes(blob)
        total += len(blob)
    shutil.copyfile(SOURCE / "LICENSE", TARGET / "LICENSE.txt")
    print(f"{len(plans)} floor plans, {total / 1024:.0f} KiB in {TARGET}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
