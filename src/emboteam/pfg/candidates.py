"""Readings as a choice: the points of doubt of an instruction and the complete readings
they allow.

A reader that guesses once hides its guesses. Here every place where the words allow more
than one reading is a :class:`Doubt` (its kind, the words in doubt, and its alternatives,
the first being the reading as read), each alternative an :class:`Choice` (an edit of the
goal conditions, with a prior). :mod:`emboteam.pfg.ranker` combines them into at most a
few :class:`Candidate` readings, each a complete, checked goal with a plain-English
sentence (what the local model scores, what the person is asked to choose from).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pydantic import BaseModel, ConfigDict

from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Condition

#: the label of a doubt's alternative that keeps the reading as read
AS_READ = "as_read"


@dataclass(frozen=True)
class Choice:
    """One way to settle a point of doubt: drop some goal conditions, add others.

    ``label`` names the alternative for the priors (``as_read``, ``other_type``, ...);
    ``how`` says it in plain English ("'table' as the coffee table")."""

    label: str
    how: str
    drop: tuple[Condition, ...] = ()
    add: tuple[Condition, ...] = ()

    @property
    def as_read(self) -> bool:
        return not self.drop and not self.add


@dataclass(frozen=True)
class Doubt:
    """A point of doubt: its kind (the rule that found it), the words, the alternatives
    (the first keeps the reading as read)."""

    kind: str
    span: str
    choices: tuple[Choice, ...]


@dataclass(frozen=True)
class Resolution:
    """How one candidate settles one doubt (for the views: which words, which way)."""

    kind: str
    span: str
    label: str
    how: str

    def __str__(self) -> str:
        return f"{self.kind} {self.span!r}: {self.how}"


@dataclass(frozen=True)
class Candidate:
    """One complete, checked reading: its goal, as a sentence, its score (a log-prior: the
    sum of the log-priors of how it settles each doubt) and the doubts it settles other
    than as read."""

    goals: tuple[Condition, ...]
    sentence: str
    score: float
    spec: TaskSpec
    resolves: tuple[Resolution, ...] = ()

    @property
    def as_read(self) -> bool:
        """Whether this is the reader's own reading (no doubt settled another way)."""
        return not self.resolves

    def to_json(self) -> dict[str, object]:
        return {"sentence": self.sentence, "goals": [str(c) for c in self.goals],
                "score": round(self.score, 3), "as_read": self.as_read,
                "resolves": [{"kind": r.kind, "span": r.span, "choice": r.label, "how": r.how}
                             for r in self.resolves]}


@dataclass(frozen=True)
class Clarification:
    """A question for the person and the readings it chooses between, best first.

    The same fields as issue 26's ``pfg.clarification.Clarification`` (question, readings
    as plain-English sentences, source), so the two merge into one type; the offline
    reader's also keeps the candidates behind the sentences."""

    question: str
    readings: tuple[str, ...]
    source: str = "offline"
    candidates: tuple[Candidate, ...] = field(default_factory=tuple)

    def to_json(self) -> dict[str, object]:
        return {"question": self.question, "readings": list(self.readings), "source": self.source}

    def render(self) -> str:
        """The question and the numbered readings, as a terminal shows them."""
        return "\n".join([self.question, *(f"  {i}. {r}" for i, r in enumerate(self.readings, start=1))])


class NotAttempted(BaseModel):
    """A requested goal condition the planner could not plan, left out of the run, and
    why (:mod:`emboteam.hp.feasible`); recorded in the episode and ``--json``."""

    model_config = ConfigDict(frozen=True)

    condition: str
    reason: str

    def __str__(self) -> str:
        return f"{self.condition}: {self.reason}"
