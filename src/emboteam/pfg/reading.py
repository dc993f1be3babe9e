"""What a front end read from an instruction, and what it could not read.

A reading is the :class:`~emboteam.pfg.taskspec.TaskSpec` plus one :class:`ReadingNote`
per span the reader did not use (and why), and the goal conditions it chose with doubt.
The notes reach the user (terminal panel, HTML report, ``--json``) and, in the hybrid
front end, the LLM, which is only asked when the reading is doubtful.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from emboteam.pfg.candidates import Candidate, Doubt
from emboteam.pfg.taskspec import TaskSpec

#: unread: words the reader could not use (unknown, unparsable, not groundable in the scene);
#: vague: a chore with no single household reading ("tidy up"); assumed: a reading the
#: reader chose among several plausible ones; unsure: a condition kept with low confidence
#: (a mention that ends in no goal and that nothing explains is ``Reading.unexplained``)
NoteKind = Literal["unread", "vague", "assumed", "unsure"]


@dataclass(frozen=True)
class ReadingNote:
    """One span of the instruction the reader did not act on as written, and why."""

    span: str
    reason: str
    kind: NoteKind = "unread"

    def __str__(self) -> str:
        return f"{self.kind} {self.span!r}: {self.reason}"


@dataclass(frozen=True)
class Reading:
    """A front end's TaskSpec, its notes, and the conditions (``str(Condition)``) it was
    unsure of. The hybrid front end trusts every condition not listed in ``unsure``.

    ``candidates``: the complete readings the words and the scene allow, best first (the
    first is ``spec``'s), each with its goal, its end-state sentence, its prior score and
    the doubts it settles (:mod:`emboteam.pfg.candidates`); empty for a front end that
    makes one guess. ``unexplained``: the words of each mention of a scene thing that
    ends in no goal and that nothing explains. ``doubts``: the points of doubt the
    candidates were made from, each with its alternatives (the views list them)."""

    spec: TaskSpec
    notes: tuple[ReadingNote, ...] = ()
    unsure: tuple[str, ...] = ()
    candidates: tuple[Candidate, ...] = ()
    unexplained: tuple[str, ...] = ()
    doubts: tuple[Doubt, ...] = ()

    @property
    def as_read(self) -> Candidate | None:
        """The reader's own reading among the candidates (before any doubt was settled
        another way), if it made candidates."""
        return next((c for c in self.candidates if c.as_read), None)

    @property
    def doubtful(self) -> bool:
        """Whether an LLM should look at this reading (``--llm-when doubt``)."""
        return bool(self.notes or self.unsure or self.unexplained)
