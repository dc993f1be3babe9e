"""Ask the person when the reading is still close (``emboteam run --clarify``).

The close candidates (within the priors' ``close_margin`` of the best) are printed as
numbered plain-English sentences about the end state, and the choice is read from the
terminal. Without a terminal (a pipe, a batch job) nobody can answer: the best reading is
taken and the reader says so. Reading and writing go through the streams given, so a
test can drive it through a pseudo-terminal.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import TextIO

from emboteam.pfg.candidates import Candidate, Clarification
from emboteam.pfg.ranker import close_calls
from emboteam.pfg.reading import Reading, ReadingNote

#: at most this many readings are offered (as issue 26's clarification answer)
MAX_READINGS = 4

QUESTION = "The instruction can be read more than one way. Which end state did you mean?"


def clarification(reading: Reading, margin: float) -> Clarification | None:
    """The question to ask, or None when one reading stands out (or there is one)."""
    close = close_calls(reading.candidates, margin)[:MAX_READINGS]
    if len(close) < 2:
        return None
    return Clarification(QUESTION, tuple(c.sentence for c in close), candidates=close)


def _ask(question: Clarification, stdin: TextIO, stdout: TextIO) -> Candidate:
    options: Sequence[Candidate] = question.candidates
    stdout.write(question.render() + "\n")
    while True:
        stdout.write(f"Your choice [1-{len(options)}, Enter for 1]: ")
        stdout.flush()
        line = stdin.readline()
        if not line:                        # end of input: nobody is answering
            return options[0]
        answer = line.strip()
        if not answer:
            return options[0]
        if answer.isdigit() and 1 <= int(answer) <= len(options):
            return options[int(answer) - 1]
        stdout.write(f"Please type a number from 1 to {len(options)}.\n")


def settle(reading: Reading, margin: float, stdin: TextIO, stdout: TextIO) -> Reading:
    """The reading the person chose (asked on the terminal), or the best one with a note
    saying so when there is no terminal to ask on."""
    question = clarification(reading, margin)
    if question is None:
        return reading
    if not (stdin.isatty() and stdout.isatty()):
        note = ReadingNote(reading.spec.instruction, f"--clarify: no terminal to ask on; took the best of "
                           f"{len(question.candidates)} close readings: {question.candidates[0].sentence}",
                           "assumed")
        return replace(reading, notes=(*reading.notes, note))
    chosen = _ask(question, stdin, stdout)
    rest = tuple(c for c in reading.candidates if c is not chosen)
    note = ReadingNote(reading.spec.instruction, f"chosen by the person: {chosen.sentence}", "assumed")
    return replace(reading, spec=chosen.spec, candidates=(chosen, *rest), notes=(*reading.notes, note),
                   unsure=())
