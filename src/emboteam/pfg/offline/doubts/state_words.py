"""The words of device end states (:mod:`.device_state`): state words with their family
and polarity, the words that flip, stop, carry a state or say its present one, and
purposes that imply a state. Data (``state_words.json``), checked at load: a malformed
entry is a :class:`~emboteam.pfg.offline.knowledge.KnowledgeDataError` naming the file and
the entry.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import Literal

from pydantic import Field, field_validator

from emboteam.pfg.offline.knowledge import Strict as _Closed
from emboteam.pfg.offline.knowledge import known_types, read

STATE_WORDS_FILE = Path(__file__).with_name("state_words.json")

Words = list[str]
Family = Literal["switch", "open"]


class StateWord(_Closed):
    """One word said after a device that asks its state."""

    words: Words = Field(min_length=1, max_length=1)
    family: Family
    polarity: bool
    #: False: the word may be something else ("of"): the reading keeps its own as an
    #: alternative at a higher prior (label ``heard``)
    certain: bool = True
    #: the device types the word is a state of (empty: any device of its family)
    types: list[str] = Field(default_factory=list)
    why: str = Field(min_length=1)

    _check_types = field_validator("types")(known_types)


class Purpose(_Closed):
    """A purpose or complaint that implies a device's state ("watching the news")."""

    words: Words = Field(min_length=1)
    types: list[str] = Field(min_length=1)
    family: Family
    polarity: bool
    #: True: only a device of ``types`` named in the same sentence; False: the scene's first
    near: bool
    #: True: a complaint about the state the device's own words say ("a lamp burning all
    #: night is a waste"): it comes before them
    complaint: bool = False
    why: str = Field(min_length=1)

    _check_types = field_validator("types")(known_types)


class StateWords(_Closed):
    about: str = ""
    words: list[StateWord]
    #: words that start a noun phrase: "on"/"off" before one is a preposition ("off the bed")
    before_object: list[str]
    #: verbs whose particle "on"/"off" right after them is no state ("hang on", "get on with it")
    particle_of: list[str]
    #: prepositions before a thing named after the device that only say which device it is
    #: ("the lamp on the desk", "the water of the sink"): the search goes on past it
    modifier_preps: list[str]
    #: what may follow a word that is not ``certain`` for it to be the state ("the lamp of
    #: thanks"; not "for a couple of minutes"): these words, a mark or the end
    heard_end: list[str]
    #: words that make the next state a condition, not the goal ("if it is open, close it")
    conditions: list[str]
    #: words just before a device that make its sentence a role ("whoever opens drawers
    #: opens them"): no end state
    roles: list[str]
    #: words that make a later state of the same device the end one ("the cupboard open
    #: first, shut after")
    later: list[str]
    #: words before the state that flip it ("never left on")
    flip: list[Words]
    #: words that end the search (a complaint, "still on"; a condition, "if it is on")
    stop: list[str]
    #: "same as now": the device's present state
    present: list[Words]
    #: "and so is the desk lamp": the state said of the device before
    carry: list[Words]
    #: a copula right before the state word: a state described, maybe a complaint (weaker)
    copulas: list[str]
    #: words before a device that make its state a description like a copula's ("so gloomy
    #: with the blinds shut")
    describing: list[str]
    #: words between the device and a copula's state that make it wanted ("is always on")
    wishes: list[str]
    #: the things an open word switches (a calque: "close the light", "open the water")
    calque_types: list[str]
    reach: int = Field(7, ge=1, le=20)
    purposes: list[Purpose]

    _check_calques = field_validator("calque_types")(known_types)

    @field_validator("words")
    @classmethod
    def _one_per_word(cls, v: list[StateWord]) -> list[StateWord]:
        seen: set[str] = set()
        for w in v:
            if w.words[0] in seen:
                raise ValueError(f"word {w.words[0]!r} listed twice")
            seen.add(w.words[0])
        return v


@cache
def load_state_words(path: Path = STATE_WORDS_FILE) -> StateWords:
    return read(path, StateWords)


@cache
def state_word_index() -> dict[str, StateWord]:
    """The shipped state words by word (one lookup per token, no scan of the list)."""
    return {w.words[0]: w for w in load_state_words().words}


@cache
def purpose_phrases() -> tuple[list[Words], dict[tuple[str, ...], Purpose]]:
    """The purposes' phrases (one list for the life of the process: :func:`.rule_words.find`
    indexes a phrase list by its identity) and each phrase's purpose."""
    purposes = load_state_words().purposes
    return [p.words for p in purposes], {tuple(p.words): p for p in purposes}
