"""Typed errors of the offline parser: what a user sees when an instruction cannot be
turned into goal conditions (one line, the phrase at fault, what would have worked)."""

from __future__ import annotations

from collections.abc import Callable, Sequence

from emboteam.errors import EmboTeamError


class OfflineParseError(EmboTeamError):
    """The instruction has no actionable verb, is too vague, or uses a construction the
    offline parser does not cover.

    ``suggestions`` may be given as a function: ranking the scene's objects by spelling
    costs milliseconds, and the parser raises and catches many errors on the way to a
    parse (a clause that turns out to be small talk), so they are ranked only when the
    error is shown.
    """

    def __init__(self, message: str, phrase: str | None = None,
                 suggestions: Sequence[str] | Callable[[], Sequence[str]] = (), *,
                 vague: bool = False) -> None:
        self.phrase = phrase
        self.message = message
        self._suggest = suggestions
        self._suggestions: tuple[str, ...] | None = None
        #: the clause was too vague to act on ("tidy up", "things"), not wrong: when another
        #: clause of the instruction says what to do, this one is skipped with a note
        self.vague = vague
        super().__init__(message)

    @property
    def suggestions(self) -> tuple[str, ...]:
        """The scene's objects closest to the phrase at fault."""
        if self._suggestions is None:
            found = self._suggest() if callable(self._suggest) else self._suggest
            self._suggestions = tuple(found)
        return self._suggestions

    def __str__(self) -> str:
        if self.suggestions:
            return f"{self.message}; closest objects in this scene: {', '.join(self.suggestions)}"
        return self.message


class GroundingError(OfflineParseError):
    """A noun phrase names nothing in the scene (unknown word, a type the floor plan lacks,
    more objects than there are, or an object that cannot do what is asked)."""


class IncapableError(GroundingError):
    """The phrase names objects of the scene, but none can do what is asked ("no egg can be
    switched"): in a complaint, the words described something else ("the egg has gone off")."""
