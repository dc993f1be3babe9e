""""I cannot tell": a question for the person and the readings it would settle.

Shared by every front end that can be unsure of an instruction (the LLM front end
answers one when the instruction has readings with different end states that the scene
does not settle; the offline reader's close candidates, issue 25, are the same type):

- :class:`Clarification`: the question and the numbered candidate readings, plain English;
- :class:`ClarificationNeeded`: the typed error a front end raises instead of guessing;
  ``run --json`` / ``plan --json`` print its ``clarification`` (``to_json()``);
- :data:`ClarifyHook`: what ``--clarify`` calls to settle one (:func:`ask_terminal` asks
  on a terminal; without one nothing is chosen and the caller says so). The answer is a
  reading, given back to the front end as the person's words.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Literal, TextIO

from pydantic import BaseModel, ConfigDict, Field

from emboteam.errors import EmboTeamError

#: bounds shared with the LLM answer schema (:mod:`emboteam.pfg.schema`)
QUESTION_MAX = 200
READING_MAX = 160
MIN_READINGS, MAX_READINGS = 2, 4


class Clarification(BaseModel):
    """A question for the person and the readings it chooses between (most likely first)."""

    model_config = ConfigDict(frozen=True)

    question: str = Field(min_length=1, max_length=QUESTION_MAX)
    readings: tuple[str, ...] = Field(min_length=MIN_READINGS, max_length=MAX_READINGS)
    #: who asked: the LLM front end, or the offline reader's close candidates
    source: Literal["llm", "offline"] = "llm"

    def to_json(self) -> dict[str, Any]:
        return {"question": self.question, "readings": list(self.readings), "source": self.source}

    def render(self) -> str:
        """The question and the numbered readings, as a terminal shows them."""
        return "\n".join([self.question, *(f"  {i}. {r}" for i, r in enumerate(self.readings, start=1))])


class ClarificationNeeded(EmboTeamError):
    """The front end cannot tell what the instruction asks and says so instead of guessing."""

    def __init__(self, clarification: Clarification) -> None:
        super().__init__(f"the instruction needs a clarification: {clarification.question} "
                         f"(readings: {' | '.join(clarification.readings)})")
        self.clarification = clarification


#: settles a clarification: the chosen reading, or None when nobody can choose
ClarifyHook = Callable[[Clarification], "str | None"]


def ask_terminal(clarification: Clarification, stdin: TextIO, stdout: TextIO) -> str | None:
    """Print the question and the numbered readings, read a number (or the person's own
    words) from ``stdin``; None without a terminal or on an empty answer."""
    if not stdin.isatty():
        return None
    stdout.write(clarification.render() + "\nYour choice (number, or say it in your words): ")
    stdout.flush()
    answer = stdin.readline().strip()
    if not answer:
        return None
    if answer.isdigit() and 1 <= int(answer) <= len(clarification.readings):
        return clarification.readings[int(answer) - 1]
    return answer
