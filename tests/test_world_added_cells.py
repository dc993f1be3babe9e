"""Cells added to AI2-THOR 2.1's grids for 5.x objects the grid does not reach
(world/data/nav/added_cells.json, scripts/build_added_cells.py)."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

from emboteam.sim.simulator import Simulator
from emboteam.world.actions import Action, Skill
from emboteam.world.navfit import nav_fit
from emboteam.world.navgrid import GRID, STEPS, added_cells, load_base_grid, load_grid
from emboteam.world.poses import REACH
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]


def test_the_data_is_what_the_script_derives() -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    proc = subprocess.run([sys.executable, str(ROOT / "scripts" / "build_added_cells.py"), "--check"],
                          capture_output=True, text=True, env=env, check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_every_added_cell_joins_the_grid_and_reaches_what_its_reason_names() -> None:
    data = added_cells()
    assert len(data) >= 20  # the issue: 22 floor plans misfit
    for fp, cells in data.items():
        base, grid, scene = load_base_grid(fp), load_grid(fp), load_scene(fp)
        assert set(grid.added) == set(cells), fp  # every one is connected to the grid
        assert not set(cells) & base.cells
        for cell, why in cells.items():
            assert any((cell[0] + di, cell[1] + dj) in grid.cells for di, dj in STEPS)
            for part in why.split("; "):
                role, _, oid = part.rpartition(" ")
                o = scene.get(oid)
                # the object was out of reach of the 2.1 grid; a "within reach" cell reaches it
                assert all(math.hypot(c[0] * GRID - o.position[0], c[1] * GRID - o.position[2]) > REACH
                           for c in base.cells), (fp, oid)
                if role == "within reach of":
                    d = math.hypot(cell[0] * GRID - o.position[0], cell[1] * GRID - o.position[2])
                    assert d <= REACH, (fp, cell, oid)


def test_an_object_off_the_old_grid_is_driven_to_and_picked_up() -> None:
    scene = load_scene("FloorPlan29")
    assert "Egg_1" not in nav_fit("FloorPlan29").unposed
    sim = Simulator(scene, parse_team("1"), avoidance=True)
    assert sim.execute("robot1", Action(skill=Skill.GoToObject, target="Egg_1")).success
    cell = sim.traffic.cell("robot1", sim.now).cell
    egg = scene.get("Egg_1").position
    assert math.hypot(cell[0] * GRID - egg[0], cell[1] * GRID - egg[2]) <= REACH


def test_floor_plans_without_misfits_keep_alfreds_grid() -> None:
    assert "FloorPlan1" not in added_cells()
    assert load_grid("FloorPlan1") is load_base_grid("FloorPlan1")
