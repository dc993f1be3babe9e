"""The local model as a scorer of close readings (issue 25, item 4).

The offline reader ranks its candidate readings by a prior (``Reading.candidates``, best
first, each with an end-state ``sentence`` and a log-prior ``score``). Where the top
candidates are within ``margin`` of each other the prior is unsure; only then are those
close candidates scored by the language model (PMI of the sentence given the instruction,
:mod:`emboteam.llm.scoring`) and re-ranked by ``prior + weight * pmi``. A reading the prior
is sure of costs no call, and a model score can reorder only the close ones; the rest
keep their order after them.

The candidates are anything with a ``sentence`` and a ``score`` (:class:`RankedCandidate`),
so this module does not depend on the reader's class.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Generic, Protocol, TypeVar

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from emboteam.errors import EmboTeamError
from emboteam.llm.client import LLMClient
from emboteam.llm.scoring import ScoreRequest, ScoreResponse
from emboteam.world.scene import Scene

#: the margin, weight and PMI lead the hybrid front end uses, fitted on the development
#: rounds by ``benchmarks/pmi_dev_rounds.py`` (the fit, its date and command are in the
#: file's ``fitted`` entry; docs/llm.md has the grid). Data, checked at load.
SETTINGS_FILE = Path(__file__).with_name("model_ranker.json")


class ModelRankerDataError(EmboTeamError):
    """The model ranker's settings file is missing or malformed."""


class RankerSettings(BaseModel):
    """How far the model may reorder the prior's candidates."""

    model_config = ConfigDict(extra="forbid")

    #: what was fitted on what, and the command that reproduces the grid
    fitted: str = Field(min_length=1)
    #: candidates within this (log-prior) margin of the first are scored
    margin: float = Field(ge=0, le=10)
    #: ``prior + weight * pmi`` orders the scored ones; 0 turns the model off
    weight: float = Field(ge=0, le=10)
    #: the model overturns the prior's first only when its PMI leads the first's by more
    min_lead: float = Field(0.0, ge=0, le=20)


@cache
def load_ranker_settings(path: Path = SETTINGS_FILE) -> RankerSettings:
    """The settings in ``path``; a bad file is a :class:`ModelRankerDataError` naming it
    and the entry."""
    try:
        raw = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise ModelRankerDataError(f"{path}: cannot read the model ranker's settings: {exc}") from None
    try:
        return RankerSettings.model_validate(raw)
    except ValidationError as exc:
        first = exc.errors()[0]
        where = ".".join(str(x) for x in first["loc"]) or "(top level)"
        raise ModelRankerDataError(f"{path}: entry {where}: {first['msg']}") from None


#: how many candidates the model scores at most (the prompt is shared; each candidate
#: costs its sentence twice)
MAX_SCORED = 5


class RankedCandidate(Protocol):
    """A reading as the ranker needs it: its end-state sentence and its prior (a log-score,
    higher is better)."""

    @property
    def sentence(self) -> str: ...

    @property
    def score(self) -> float: ...


C = TypeVar("C", bound=RankedCandidate)


@dataclass(frozen=True)
class Ranked(Generic[C]):
    """One candidate after re-ranking: its prior, the model's PMI (None when not scored)
    and the combined score the order follows."""

    candidate: C
    prior: float
    pmi: float | None
    combined: float

    def to_json(self) -> dict[str, object]:
        return {"sentence": self.candidate.sentence, "prior": round(self.prior, 4),
                "pmi": None if self.pmi is None else round(self.pmi, 4), "combined": round(self.combined, 4)}


@dataclass(frozen=True)
class Reranking(Generic[C]):
    """The candidates in their new order; ``scored``: whether the model was asked;
    ``overturned``: whether the first candidate changed."""

    ranked: tuple[Ranked[C], ...]
    scored: bool
    overturned: bool
    response: ScoreResponse | None = None

    @property
    def candidates(self) -> tuple[C, ...]:
        return tuple(r.candidate for r in self.ranked)


def type_words(type_: str) -> str:
    """``CoffeeTable`` -> "coffee table" (the scene's types in plain words for the prompt)."""
    return re.sub(r"(?<=[a-z])(?=[A-Z])", " ", type_).lower()


def objects_summary(scene: Scene, texts: Sequence[str] = ()) -> str:
    """The scene's object types in plain words, sorted: the shared part of both scoring
    prompts. With ``texts`` (the instruction and the candidate sentences), only the types
    whose words occur in them: the prompt is most of what is evaluated per task, and the
    calibration term only needs the objects the candidates are about."""
    names = sorted({type_words(o.type) for o in scene.objects if o.type != "Floor"})
    if texts:
        said = " " + " ".join(re.sub(r"[^a-z]+", " ", t.lower()) for t in texts) + " "
        named = [n for n in names if any(f" {w} " in said or f" {w}s " in said for w in n.split())]
        names = named or names
    return ", ".join(names)


def close_count(priors: Sequence[float], margin: float) -> int:
    """How many leading candidates are within ``margin`` of the first (1 when none is)."""
    if not priors:
        return 0
    top = priors[0]
    return sum(1 for p in priors if top - p <= margin)


def rerank(candidates: Sequence[C], *, client: LLMClient, objects: str, instruction: str, margin: float,
           weight: float, max_scored: int = MAX_SCORED, tail: Sequence[C] = (), min_lead: float = 0.0) -> Reranking[C]:
    """``candidates`` (best first by prior) re-ranked where the prior is unsure.

    The leading candidates within ``margin`` of the first (at most ``max_scored``) are
    scored in one :meth:`LLMClient.score` call and ordered by ``prior + weight * pmi``;
    the others follow in their order; the prior's first stays first unless the new first's
    PMI leads its PMI by more than ``min_lead``. With fewer than two close candidates, or close
    candidates that all say the same sentence, nothing is asked. Errors of the call (:class:`~emboteam.llm.errors.LLMError`, e.g.
    ``LLMScoringUnsupported``) propagate: the caller decides what stands instead."""
    priors = [float(c.score) for c in candidates]
    n = min(close_count(priors, margin), max_scored)
    if n < 2 or len({c.sentence for c in candidates[:n]}) < 2:  # one sentence: nothing to tell apart
        ranked = tuple(Ranked(c, p, None, p) for c, p in zip(candidates, priors, strict=True))
        return Reranking((*ranked, *_unscored(tail)), scored=False, overturned=False)
    close = list(candidates[:n])
    response = client.score(ScoreRequest(objects=objects, instruction=instruction,
                                         candidates=tuple(c.sentence for c in close)))
    scored = [Ranked(c, p, s.pmi, p + weight * s.pmi)
              for c, p, s in zip(close, priors[:n], response.scores, strict=True)]
    # stable: equal combined scores keep the prior's order
    scored.sort(key=lambda r: -r.combined)
    first = next(r for r in scored if r.candidate is candidates[0])
    if scored[0] is not first and (scored[0].pmi or 0.0) - (first.pmi or 0.0) <= min_lead:
        scored = [first, *(r for r in scored if r is not first)]
    rest = [Ranked(c, p, None, p) for c, p in zip(candidates[n:], priors[n:], strict=True)]
    return Reranking((*scored, *rest, *_unscored(tail)), scored=True,
                     overturned=scored[0].candidate is not candidates[0], response=response)


def _unscored(candidates: Sequence[C]) -> tuple[Ranked[C], ...]:
    return tuple(Ranked(c, float(c.score), None, float(c.score)) for c in candidates)


def rerank_in_scene(candidates: Sequence[C], *, client: LLMClient, scene: Scene, instruction: str,
                    margin: float, weight: float, min_lead: float = 0.0,
                    prior_only: Callable[[C], bool] | None = None) -> Reranking[C]:
    """:func:`rerank` with the objects summary of ``scene`` for the instruction and the
    candidates' sentences: the one call a front end makes. Candidates ``prior_only``
    marks (readings that settle a doubt the model is known to judge no better than
    chance) are not scored: they keep their place by the prior, and when the first is
    one, nothing is asked."""
    if prior_only is not None:
        if candidates and prior_only(candidates[0]):
            return rerank(candidates[:1], client=client, objects="", instruction=instruction, margin=margin,
                          weight=weight, tail=candidates[1:])
        scored = [c for c in candidates if not prior_only(c)]
        rest = [c for c in candidates if prior_only(c)]
        return _rerank_scene(scored, rest, client, scene, instruction, (margin, weight, min_lead))
    return _rerank_scene(list(candidates), [], client, scene, instruction, (margin, weight, min_lead))


def _rerank_scene(candidates: Sequence[C], tail: Sequence[C], client: LLMClient, scene: Scene, instruction: str,
                  settings: tuple[float, float, float]) -> Reranking[C]:
    margin, weight, min_lead = settings
    objects = objects_summary(scene, (instruction, *(c.sentence for c in candidates)))
    return rerank(candidates, client=client, objects=objects, instruction=instruction, margin=margin,
                  weight=weight, tail=tail, min_lead=min_lead)
