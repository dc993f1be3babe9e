"""The local model as a scorer of close readings (issue 25, item 4).

The offline reader ranks its candidate readings by a prior (``Reading.candidates``, best
first, each with an end-state ``sentence`` and a log-prior ``score``). Where the top
candidates are within ``margin`` of each other the prior is unsure; only then are those
close candidates scored by the language model (PMI of the sentence given the instruction,
:mod:`emboteam.llm.scoring`) and re-ranked by ``prior + weight * pmi``. A reading the prior
is sure of costs no call, and a model score can reorder only the close ones; the rest
keep their order after them.

The candidates are anything with a ``sentence`` and a ``score`` (:class:`RankedCandidate`),
so this module does not depend on the reader's class. Which close candidates the model may
judge against the prior's first depends on the *kinds of doubt* they settle differently
(:meth:`RankerSettings.lead_for`): the 0.5B model is right more often than the prior on
some kinds and wrong more often on others (docs/llm.md, the per-kind table).
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Generic, Literal, Protocol, TypeVar

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from emboteam.errors import EmboTeamError
from emboteam.llm.client import LLMClient
from emboteam.llm.scoring import ScoreRequest, ScoreResponse
from emboteam.pfg.doubt_gate import DoubtGate
from emboteam.world.scene import Scene

#: the margin, weight and PMI lead the hybrid front end uses, fitted on the development
#: rounds by ``benchmarks/pmi_dev_rounds.py`` (the fit, its date and command are in the
#: file's ``fitted`` entry; docs/llm.md has the grid). Data, checked at load.
SETTINGS_FILE = Path(__file__).with_name("model_ranker.json")

#: how the model's lead of a close candidate over the prior's first is formed: ``sentence``
#: the difference of the whole sentences' PMIs; ``clauses`` the PMIs of the clauses the two
#: do not share, where leaving a clause out is never a gain (:func:`clause_lead`)
Calibration = Literal["sentence", "clauses"]


class ModelRankerDataError(EmboTeamError):
    """The model ranker's settings file is missing or malformed."""


class KindPermission(BaseModel):
    """Whether the model may judge readings that differ from the prior's first in one kind
    of doubt, and what the fit on the development rounds said."""

    model_config = ConfigDict(extra="forbid")

    #: the model may overturn the prior's first over a doubt of this kind
    judge: bool
    #: the PMI lead needed over the first for this kind (None: the file's ``min_lead``)
    min_lead: float | None = Field(None, ge=0, le=20)
    #: the fit's counts for this kind (model right / prior right / both / neither)
    fit: str = Field(min_length=1)


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
    #: the rule that chose ``kinds`` from the fit (stated, so a refit applies it again)
    kinds_rule: str = Field("", max_length=2000)
    #: how the model's lead over the first is formed (:data:`Calibration`)
    calibration: Calibration = "sentence"
    #: per kind of doubt (``Resolution.kind``): may the model judge it; a kind not listed
    #: may not be judged (a new kind has no evidence yet). Empty: every kind may be.
    kinds: dict[str, KindPermission] = Field(default_factory=dict)
    #: the reading's own doubt signals that open the gate on a sure prior
    #: (:mod:`emboteam.pfg.doubt_gate`); none: only close priors are scored
    doubt_gate: DoubtGate = Field(default_factory=DoubtGate)

    def lead_for(self, kinds: Iterable[str]) -> float | None:
        """The PMI lead a close candidate needs to overturn the prior's first when the two
        settle doubts of ``kinds`` differently; None when the model may not judge them
        (a kind not allowed, or no differing doubt at all)."""
        kinds = frozenset(kinds)
        if not kinds:
            return None
        if not self.kinds:
            return self.min_lead
        leads = []
        for kind in kinds:
            permission = self.kinds.get(kind)
            if permission is None or not permission.judge:
                return None
            leads.append(self.min_lead if permission.min_lead is None else permission.min_lead)
        return max(leads)


def differing_kinds(first: Iterable[tuple[str, str, str]], other: Iterable[tuple[str, str, str]]) -> frozenset[str]:
    """The kinds of doubt two candidates settle differently, from their resolutions as
    ``(kind, span, label)``: the kind of the close call between them."""
    return frozenset(r[0] for r in set(first) ^ set(other))


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
           weight: float, max_scored: int = MAX_SCORED, tail: Sequence[C] = (), min_lead: float = 0.0,
           lead_of: Callable[[C], float] | None = None) -> Reranking[C]:
    """``candidates`` (best first by prior) re-ranked where the prior is unsure.

    The leading candidates within ``margin`` of the first (at most ``max_scored``) are
    scored in one :meth:`LLMClient.score` call and ordered by ``prior + weight * pmi``;
    the others follow in their order. The first by that order that either is the prior's
    first or leads its PMI by more than ``min_lead`` (``lead_of(candidate)`` when given)
    comes first; the rest keep the combined order. With fewer than two close candidates, or close
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
    needed = lead_of or (lambda _: min_lead)
    winner = next(r for r in scored if r is first or (r.pmi or 0.0) - (first.pmi or 0.0) > needed(r.candidate))
    scored = [winner, *(r for r in scored if r is not winner)]
    rest = [Ranked(c, p, None, p) for c, p in zip(candidates[n:], priors[n:], strict=True)]
    return Reranking((*scored, *rest, *_unscored(tail)), scored=True,
                     overturned=scored[0].candidate is not candidates[0], response=response)


def clause_lead(first: Sequence[str], other: Sequence[str], pmi: Mapping[str, float], *,
                drops: bool = False) -> float | None:
    """How far ``other`` leads ``first`` by the PMIs of the clauses they do not share (the
    clauses both say cancel): the mean PMI of the clauses only ``other`` says minus the mean
    of those only ``first`` says, a side with none counting 0 (a neutral clause).

    A reading that only leaves clauses of the first out is not judged (None), unless
    ``drops``: a clause the instruction does not strongly predict often has a negative PMI,
    so a score in which a missing clause counts 0 rewards leaving requested things out
    (docs/llm.md, "The sentence's form"). ``pmi`` maps each clause sentence to its PMI."""
    said = set(other)
    gone = [c for c in dict.fromkeys(first) if c not in said]
    new = [c for c in dict.fromkeys(other) if c not in set(first)]
    if not new and not (drops and gone):
        return None
    return _mean(pmi[c] for c in new) - _mean(pmi[c] for c in gone)


def _mean(values: Iterable[float]) -> float:
    got = list(values)
    return sum(got) / len(got) if got else 0.0


def differing_clauses(first: Sequence[str], others: Sequence[Sequence[str]], *, drops: bool = False,
                      limit: int = 16) -> tuple[tuple[str, ...], tuple[int, ...]]:
    """The clause sentences to score for comparing ``others`` with ``first`` (those not
    shared, without repeats, at most ``limit``: one request) and the indices of the others
    they allow to judge (by :func:`clause_lead`; an other whose clauses would pass the
    limit is left out)."""
    asked: dict[str, None] = {}
    judged: list[int] = []
    for i, other in enumerate(others):
        gone = [c for c in first if c not in set(other)]
        new = [c for c in other if c not in set(first)]
        if not new and not (drops and gone):
            continue
        more = dict.fromkeys([*asked, *new, *gone])
        if len(more) > limit:
            break
        asked = more
        judged.append(i)
    return tuple(asked), tuple(judged)


def rerank_by_clauses(candidates: Sequence[C], *, client: LLMClient, objects: str, instruction: str,
                      margin: float, weight: float, clauses_of: Callable[[C], Sequence[str]],
                      max_scored: int = MAX_SCORED, tail: Sequence[C] = (), min_lead: float = 0.0,
                      lead_of: Callable[[C], float] | None = None) -> Reranking[C]:
    """:func:`rerank` with the ``clauses`` calibration: the close candidates are compared
    with the prior's first by :func:`clause_lead` (``clauses_of(candidate)``: its end state
    as one sentence per condition); the clauses none of them differ in are not asked, a
    candidate that only leaves clauses out is not judged, and when none is judged nothing
    is asked. ``Ranked.pmi`` is the candidate's clause lead over the first (0 for the first)."""
    priors = [float(c.score) for c in candidates]
    n = min(close_count(priors, margin), max_scored)
    own = [tuple(dict.fromkeys(clauses_of(c))) for c in candidates[:n]]
    texts, judged_at = differing_clauses(own[0], own[1:]) if n >= 2 else ((), ())
    if not judged_at:
        return Reranking((*_unscored(candidates), *_unscored(tail)), scored=False, overturned=False)
    response = client.score(ScoreRequest(objects=objects, instruction=instruction, candidates=texts))
    pmi = dict(zip(texts, response.pmi, strict=True))
    first = Ranked(candidates[0], priors[0], 0.0, priors[0])
    scored = [first]
    for i in judged_at:
        lead = clause_lead(own[0], own[i + 1], pmi)
        assert lead is not None         # differing_clauses judged it
        scored.append(Ranked(candidates[i + 1], priors[i + 1], lead, priors[i + 1] + weight * lead))
    scored.sort(key=lambda r: -r.combined)      # stable: the first wins a tie
    needed = lead_of or (lambda _: min_lead)
    winner = next(r for r in scored if r is first or (r.pmi or 0.0) > needed(r.candidate))
    scored = [winner, *(r for r in scored if r is not winner)]
    picked = {id(r.candidate) for r in scored}
    rest = [c for c in candidates if id(c) not in picked]
    return Reranking((*scored, *_unscored(rest), *_unscored(tail)), scored=True,
                     overturned=winner is not first, response=response)


def _unscored(candidates: Sequence[C]) -> tuple[Ranked[C], ...]:
    return tuple(Ranked(c, float(c.score), None, float(c.score)) for c in candidates)


def rerank_in_scene(candidates: Sequence[C], *, client: LLMClient, scene: Scene, instruction: str,
                    margin: float, weight: float, min_lead: float = 0.0,
                    lead_needed: Callable[[C, C], float | None] | None = None,
                    clauses_of: Callable[[C], Sequence[str]] | None = None) -> Reranking[C]:
    """:func:`rerank` with the objects summary of ``scene`` for the instruction and the
    candidates' sentences: the one call a front end makes. ``lead_needed(first, other)``
    says what PMI lead ``other`` needs to overturn the prior's ``first``, or None when the
    model may not judge the doubt between them (a kind on which it was no better than the
    prior): those candidates are not scored and keep their place by the prior after the
    scored ones; when none may be judged, nothing is asked. With ``clauses_of`` (a
    candidate's end state, one sentence per condition) the ``clauses`` calibration
    (:func:`rerank_by_clauses`) stands for the whole sentences' PMI."""
    if lead_needed is None or not candidates:
        return _rerank_scene(list(candidates), [], client, scene, instruction, (margin, weight, min_lead), None,
                             clauses_of)
    first = candidates[0]
    leads = {id(c): lead_needed(first, c) for c in candidates[1:]}
    judged = [first, *(c for c in candidates[1:] if leads[id(c)] is not None)]
    rest = [c for c in candidates[1:] if leads[id(c)] is None]

    def lead_of(c: C) -> float:
        return leads.get(id(c)) or 0.0

    return _rerank_scene(judged, rest, client, scene, instruction, (margin, weight, min_lead), lead_of, clauses_of)


def _rerank_scene(candidates: Sequence[C], tail: Sequence[C], client: LLMClient, scene: Scene, instruction: str,
                  settings: tuple[float, float, float], lead_of: Callable[[C], float] | None,
                  clauses_of: Callable[[C], Sequence[str]] | None = None) -> Reranking[C]:
    margin, weight, min_lead = settings
    # over every candidate, judged or not: a sentence's PMI then does not depend on which
    # others the model may judge (and is the one benchmarks/pmi_dev_rounds.py recorded)
    objects = objects_summary(scene, (instruction, *(c.sentence for c in (*candidates, *tail))))
    if clauses_of is not None:
        return rerank_by_clauses(candidates, client=client, objects=objects, instruction=instruction,
                                 margin=margin, weight=weight, clauses_of=clauses_of, tail=tail,
                                 min_lead=min_lead, lead_of=lead_of)
    return rerank(candidates, client=client, objects=objects, instruction=instruction, margin=margin,
                  weight=weight, tail=tail, min_lead=min_lead, lead_of=lead_of)
