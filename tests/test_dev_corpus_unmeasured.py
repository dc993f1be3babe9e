"""A blind development round waits for its one fresh measurement before any script reads it.

``development_tasks`` must skip a ``blind_r*/dev`` folder whose ``ABOUT.md`` carries the line
``Status: not yet measured`` (so the lead can merge a new round before measuring it), and
read it as soon as the line is gone. The rounds built here are written by the test itself.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from emboteam.bench.dev_corpus import (
    HELD_OUT_ROUNDS,
    UNMEASURED_MARKER,
    development_tasks,
    is_unmeasured,
)

DATA = Path(__file__).parent / "data"


def _round(root: Path, name: str, about: str | None) -> Path:
    """One blind round with one task (FloorPlan1: the apple into the fridge)."""
    rnd = root / name
    (rnd / "dev").mkdir(parents=True)
    record = {"task": "Put the apple in the fridge.", "robot list": [1],
              "object_states": [{"name": "Fridge", "contains": ["Apple"], "state": None}]}
    (rnd / "dev" / "FloorPlan1.json").write_text(json.dumps(record) + "\n", encoding="utf-8")
    if about is not None:
        (rnd / "ABOUT.md").write_text(about, encoding="utf-8")
    return rnd


def _sets(root: Path) -> list[str]:
    return [d.set for d in development_tasks(root, mace_thor=False)]


def test_round_marked_unmeasured_is_skipped_and_read_once_the_line_is_gone(tmp_path: Path) -> None:
    fresh = _round(tmp_path, "blind_r90", f"# blind_r90\n\n{UNMEASURED_MARKER}\n\nwritten blind\n")
    _round(tmp_path, "blind_r91", "# blind_r91\n\nmeasured fresh, then opened\n")
    _round(tmp_path, "blind_r92", None)
    assert is_unmeasured(fresh)
    assert _sets(tmp_path) == ["blind_r91", "blind_r92"]

    (fresh / "ABOUT.md").write_text("# blind_r90\n\nmeasured fresh, then opened\n", encoding="utf-8")
    assert not is_unmeasured(fresh)
    assert _sets(tmp_path) == ["blind_r90", "blind_r91", "blind_r92"]


def test_marker_counts_only_as_a_line_of_its_own(tmp_path: Path) -> None:
    prose = _round(tmp_path, "blind_r93", "The lead said this round's status: not yet measured, then ran it.\n")
    indented = _round(tmp_path, "blind_r94", f"  {UNMEASURED_MARKER}  \n")
    assert not is_unmeasured(prose)
    assert is_unmeasured(indented)
    assert _sets(tmp_path) == ["blind_r93"]


def test_held_out_rounds_keep_their_tasks_outside_dev() -> None:
    assert {"blind_r54", "blind_r56", "blind_r58", "blind_r60", "blind_r62", "blind_r64",
            "blind_r66", "blind_r68"} <= set(HELD_OUT_ROUNDS)
    for name in HELD_OUT_ROUNDS:
        assert not (DATA / name / "dev").exists(), f"{name} is held out but has a dev folder"


@pytest.mark.parametrize(("dev_round", "held_out"), [("blind_r61", "blind_r62"), ("blind_r63", "blind_r64"),
                                                      ("blind_r65", "blind_r66"), ("blind_r67", "blind_r68")])
def test_a_new_round_waits_for_its_fresh_measurement(dev_round: str, held_out: str) -> None:
    """A development round written with a held-out one is skipped until the lead removes its
    status line; its held-out partner keeps its tasks in ``heldout/`` and is named in the list."""
    assert (DATA / dev_round / "dev").is_dir()
    assert dev_round not in HELD_OUT_ROUNDS
    assert held_out in HELD_OUT_ROUNDS
    if is_unmeasured(DATA / dev_round):
        assert dev_round not in {d.set for d in development_tasks(DATA, mace_thor=False)}


def test_a_held_out_round_is_skipped_by_name_even_with_a_dev_folder(tmp_path: Path) -> None:
    _round(tmp_path, HELD_OUT_ROUNDS[-1], "# held out\n")
    _round(tmp_path, "blind_r91", None)
    assert _sets(tmp_path) == ["blind_r91"]


def test_round_65_waits_for_its_fresh_measurement() -> None:
    """Round 65 is merged unmeasured: its status line keeps every reading script off it, and
    its held-out partner 66 keeps its tasks in ``heldout/`` only."""
    if is_unmeasured(DATA / "blind_r65"):
        assert not any(d.set == "blind_r65" for d in development_tasks(DATA, mace_thor=False))
    assert (DATA / "blind_r66" / "heldout").is_dir()
    assert not (DATA / "blind_r66" / "dev").exists()


def test_round_67_waits_for_its_fresh_measurement() -> None:
    """Round 67 is merged unmeasured: while its status line stands no reading script sees it,
    and its held-out partner 68 keeps its tasks in ``heldout/`` only."""
    if is_unmeasured(DATA / "blind_r67"):
        assert not any(d.set == "blind_r67" for d in development_tasks(DATA, mace_thor=False))
    assert (DATA / "blind_r68" / "heldout").is_dir()
    assert not (DATA / "blind_r68" / "dev").exists()
    assert "blind_r68" not in {d.set for d in development_tasks(DATA, mace_thor=False)}
