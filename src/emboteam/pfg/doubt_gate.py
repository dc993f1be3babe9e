"""When the reading itself is in doubt, the model may score readings the prior is sure of.

The model ranker (:mod:`emboteam.pfg.model_ranker`) asks the local model only where the
top candidates' priors are close. On fresh rounds the prior is often sure and wrong, so the
model is never asked, yet the reading may carry its own evidence of doubt: a scene thing the
instruction mentions and the reading leaves unexplained, an assumption or unsure note, an
unsure condition. This module measures those signals (:func:`doubt_signals`) and says
whether a reading's signals open the gate (:meth:`DoubtGate.opens`): each rule is data in
``pfg/model_ranker.json`` (``doubt_gate``), chosen on development rounds only by
``benchmarks/doubt_gate_dev.py`` by how often the model's overturn was right.

When the gate opens, the top candidates (at most ``top_k``, wherever their priors are) are
scored in one call and the choice still follows ``prior + weight * pmi`` with the PMI lead
the gate requires: a far prior needs a large model lead to be overturned.
"""

from __future__ import annotations

from collections.abc import Sequence

from pydantic import BaseModel, ConfigDict, Field, field_validator

from emboteam.llm.scoring import ScoreRequest
from emboteam.pfg.candidates import Candidate
from emboteam.pfg.reading import Reading
from emboteam.world.state import WorldState

#: the signals a rule may name (:func:`doubt_signals`)
SIGNALS = ("unexplained_mentions", "unexplained_nouns", "assumed_notes", "unsure_notes", "unread_notes",
           "vague_notes", "unsure_conditions", "ambiguous_nouns", "quantity_unread", "alternatives")


class GateRule(BaseModel):
    """One named doubt signal that opens the gate when it reaches ``at_least``."""

    model_config = ConfigDict(extra="forbid")

    #: the signal (one of :data:`SIGNALS`)
    signal: str
    #: the gate opens when the signal is at least this
    at_least: float = Field(1.0, gt=0)
    #: the counts on the development rounds it was chosen on
    fit: str = Field(min_length=1)

    @field_validator("signal")
    @classmethod
    def _known(cls, signal: str) -> str:
        if signal not in SIGNALS:
            raise ValueError(f"unknown signal {signal!r}; one of {', '.join(SIGNALS)}")
        return signal


class DoubtGate(BaseModel):
    """The rules that open the model ranker's gate on a sure prior, and what the model
    then needs to overturn it."""

    model_config = ConfigDict(extra="forbid")

    #: the rule that chose ``rules`` (stated, so a refit applies it again)
    rule: str = ""
    #: named rules; none: the gate opens only on close priors
    rules: dict[str, GateRule] = Field(default_factory=dict)
    #: how many of the top candidates are scored when a rule opens the gate
    top_k: int = Field(3, ge=2, le=5)
    #: the PMI lead over the prior's first a candidate needs when the gate was opened by a
    #: signal (the prior is sure: the model must be surer)
    min_lead: float = Field(2.0, ge=0, le=20)
    #: the combined order's weight of the PMI when the gate was opened by a signal
    weight: float = Field(1.0, ge=0, le=20)
    #: only candidates within this prior distance of the first are scored (far ones are
    #: readings the words hardly allow)
    max_gap: float = Field(100.0, ge=0, le=100)
    #: whether the model may pick a candidate that only leaves out clauses of the prior's
    #: first: whole-sentence PMI rewards a shorter reading (docs/llm.md, "The sentence's
    #: form": on drops the model was right 0 times, the prior 10, on r30-r45)
    judge_drops: bool = False

    def opened_by(self, signals: dict[str, float]) -> tuple[str, ...]:
        """The names of the rules ``signals`` meet."""
        return tuple(name for name, r in self.rules.items() if signals.get(r.signal, 0.0) >= r.at_least)


def _distinct(candidates: Sequence[Candidate], top_k: int, max_gap: float) -> list[Candidate]:
    """The leading candidates with distinct sentences within ``max_gap`` of the first, at
    most ``top_k``."""
    out: list[Candidate] = []
    seen: set[str] = set()
    for c in candidates:
        if len(out) == top_k:
            break
        if c.sentence in seen or (out and out[0].score - c.score > max_gap):
            continue
        seen.add(c.sentence)
        out.append(c)
    return out


def doubt_signals(reading: Reading, instruction: str, state: WorldState) -> dict[str, float]:
    """The reading's own evidence of doubt, by the names of :data:`SIGNALS`."""
    from emboteam.pfg.doubt import doubt_features

    features = doubt_features(reading, instruction, state)
    notes = features["notes"]
    return {"unexplained_mentions": float(len(reading.unexplained)),
            "unexplained_nouns": float(len(features["unexplained"])),
            "assumed_notes": float(notes.get("assumed", 0)), "unsure_notes": float(notes.get("unsure", 0)),
            "unread_notes": float(notes.get("unread", 0)), "vague_notes": float(notes.get("vague", 0)),
            "unsure_conditions": float(features["unsure"]), "ambiguous_nouns": float(len(features["ambiguous"])),
            "quantity_unread": float(features["quantity"]),
            "alternatives": float(len({c.sentence for c in reading.candidates}) - 1 if reading.candidates else 0)}


def only_drops(first: Sequence[str], other: Sequence[str]) -> bool:
    """Whether a reading's clauses (``other``) only leave out some of the first's."""
    return set(other) < set(first)


def gate_candidates(candidates: Sequence[Candidate], top_k: int, max_gap: float = 100.0,
                    judge_drops: bool = True) -> list[Candidate]:
    """The candidates a signal-opened gate scores: the leading ``top_k`` with distinct
    sentences, without (unless ``judge_drops``) those that only leave out clauses of the
    first; none when fewer than two remain."""
    from emboteam.pfg.sentences import clause_sentences

    chosen = _distinct(candidates, top_k, max_gap)
    if not judge_drops and chosen:
        first = clause_sentences(chosen[0].goals)
        chosen = [chosen[0], *(c for c in chosen[1:] if not only_drops(first, clause_sentences(c.goals)))]
    return chosen if len(chosen) >= 2 else []


def gate_request(candidates: Sequence[Candidate], objects: str, instruction: str, top_k: int,
                 max_gap: float = 100.0, judge_drops: bool = True) -> ScoreRequest | None:
    """The one score request of a signal-opened gate (``objects``: the summary over every
    candidate, ``model_ranker.objects_summary``, as the close-prior ranker's); None when
    there is nothing to tell apart."""
    chosen = gate_candidates(candidates, top_k, max_gap, judge_drops)
    if not chosen:
        return None
    return ScoreRequest(objects=objects, instruction=instruction, candidates=tuple(c.sentence for c in chosen))
