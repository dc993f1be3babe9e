"""Typed errors of the offline parser: what a user sees when an instruction cannot be
turned into goal conditions (one line, the phrase at fault, what would have worked)."""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.errors import EmboTeamError


class OfflineParseError(EmboTeamError):
    """The instruction has no actionable verb, is too vague, or uses a construction the
    offline parser does not cover."""

    def __init__(self, message: str, phrase: str | None = None,
                 suggestions: Sequence[str] = ()) -> None:
        self.phrase = phrase
        self.suggestions = tuple(suggestions)
        if self.suggestions:
            message = f"{message}; closest objects in this scene: {', '.join(self.suggestions)}"
        super().__init__(message)


class GroundingError(OfflineParseError):
    """A noun phrase names nothing in the scene (unknown word, a type the floor plan lacks,
    more objects than there are, or an object that cannot do what is asked)."""

    #: the phrase was too vague to ground ("things", "the room"), not wrong: another
    #: clause of the instruction may still say what to do
    vague: bool = False
