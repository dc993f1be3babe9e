"""The per-kind refit of benchmarks/fit_reading_priors.py keeps the whole fit's guard: a
kind's refitted priors are taken only when they lower neither the development top-1 nor
any round's beyond one task; otherwise the kind stays as shipped. Checked on a small
synthetic record set whose top-1 follows the priors (no reader, no scenes)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))  # benchmarks/ is no package
import fit_reading_priors as frp

from emboteam.pfg.offline.doubts.priors import Priors

SHIPPED = Priors(priors={"harmful": {"as_read": 0.3, "alt": 0.8}, "helpful": {"as_read": 0.9, "alt": 0.1}})
#: what the fit proposes: "harmful" demotes an alternative that was right on round A,
#: "helpful" promotes one that is right on round B
FITTED = Priors(priors={"harmful": {"as_read": 0.9, "alt": 0.1}, "helpful": {"as_read": 0.2, "alt": 0.8}})


def synthetic_scores(_cases: list[Any], priors: Priors) -> dict[str, frp.RoundScore]:
    """Round A: 10 tasks, 3 of them right only when "harmful"'s alternative wins; round B:
    10 tasks, 2 right only when "helpful"'s alternative wins."""
    def wins(kind: str) -> bool:
        table = priors.priors[kind]
        return table["alt"] > table["as_read"]

    return {"A": frp.RoundScore(tasks=10, as_read=5, top1=5 + 3 * wins("harmful")),
            "B": frp.RoundScore(tasks=10, as_read=5, top1=5 + 2 * wins("helpful"))}


def test_refit_that_lowers_a_rounds_top1_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(frp, "fit", lambda _cases, base: base.model_copy(update={"priors": FITTED.priors}))
    priors = frp.refit_kinds([], SHIPPED, {"harmful", "helpful"}, scorer=synthetic_scores)
    assert priors.priors["harmful"] == SHIPPED.priors["harmful"]      # would lose 3 of round A
    assert priors.priors["helpful"] == FITTED.priors["helpful"]       # gains 2 on round B, loses none
    after = synthetic_scores([], priors)
    assert frp.lowers(synthetic_scores([], SHIPPED), after) == []
    assert sum(s.top1 for s in after.values()) == 15


def test_lowers_names_the_total_and_each_round_beyond_noise() -> None:
    before = {"A": frp.RoundScore(tasks=40, top1=20), "B": frp.RoundScore(tasks=40, top1=30)}
    one_lost = {"A": frp.RoundScore(tasks=40, top1=19), "B": frp.RoundScore(tasks=40, top1=31)}
    assert frp.lowers(before, one_lost) == []            # one task of a round is noise; the total holds
    three_lost = {"A": frp.RoundScore(tasks=40, top1=17), "B": frp.RoundScore(tasks=40, top1=34)}
    assert frp.lowers(before, three_lost) == ["A top-1 20 -> 17 of 40"]
    total_lost = {"A": frp.RoundScore(tasks=40, top1=19), "B": frp.RoundScore(tasks=40, top1=30)}
    assert frp.lowers(before, total_lost) == ["top-1 over all rounds 50 -> 49"]
