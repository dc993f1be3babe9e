"""The ranker's data: a prior per (kind of doubt, alternative), the confusable states,
the candidate cap. Read from ``priors.json`` beside this module and checked at load (a
clear error naming the file and the entry); written by ``benchmarks/fit_reading_priors.py``.
"""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path

from pydantic import BaseModel, Field, ValidationError

from emboteam.errors import EmboTeamError

PRIORS_FILE = Path(__file__).with_name("priors.json")


class PriorsError(EmboTeamError):
    """The priors file is missing or malformed."""


class Priors(BaseModel):
    """Priors of the alternatives of each kind of doubt (the ``as_read`` alternative of
    each kind included), and what the combination needs."""

    fitted_on: list[str] = Field(default_factory=list, description="the development sets it was fitted on")
    max_candidates: int = Field(8, ge=1, le=8)
    #: the prior of an alternative of a kind this file has no number for
    default_prior: float = Field(0.05, gt=0, lt=1)
    priors: dict[str, dict[str, float]] = Field(default_factory=dict)
    #: predicate (or ``inside:Type``) -> what it may have meant instead
    state_swaps: dict[str, list[str]] = Field(default_factory=dict)
    #: how a candidate reads when its top two scores are within this (log) margin: close
    close_margin: float = Field(1.0, ge=0)
    #: log-score per instruction word a reading accounts for beyond the reading as read
    #: (doubts/coverage.py); 0 ranks by the priors alone
    coverage_weight: float = Field(0.0, ge=0, le=10)

    def prior(self, kind: str, label: str) -> float:
        table = self.priors.get(kind, {})
        key = label if label in table else label.split("->")[0] + "->*" if "->" in label else label
        return table.get(key, self.default_prior)


@cache
def load_priors(path: Path = PRIORS_FILE) -> Priors:
    try:
        raw = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as exc:
        raise PriorsError(f"{path}: cannot read the reading priors: {exc}") from None
    try:
        priors = Priors.model_validate(raw)
    except ValidationError as exc:
        first = exc.errors()[0]
        where = ".".join(str(x) for x in first["loc"])
        raise PriorsError(f"{path}: entry {where}: {first['msg']}") from None
    for kind, table in priors.priors.items():
        for label, p in table.items():
            if not 0 < p <= 1:
                raise PriorsError(f"{path}: entry priors.{kind}.{label}: {p} is not a probability in (0, 1]")
    return priors
