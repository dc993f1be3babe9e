"""Scoring candidate sentences by pointwise mutual information (PMI) with an instruction.

A small model is a poor free-form reviewer but a useful judge of which of a few readings
fits the words (issue 25: 75 % right on ambiguous cases with Qwen2.5-Coder-0.5B, against
35 % for the raw log-probability sum, which prefers short sentences). Each candidate
reading is said as one English sentence about the end state, and scored as

    PMI = log P(sentence | objects + instruction) - log P(sentence | objects only)

summed over the sentence's tokens, both prompts in the ChatML chat template (the
template of Qwen2.5 and SmolLM2) with the sentence as the assistant's answer. The second
term calibrates away how likely a sentence is on its own (length, common words), as
SayCan does for skills.

:class:`ScoreRequest` is provider-independent, like :class:`~emboteam.llm.messages.LLMRequest`:
its key is a hash of the rendered prompts and candidates, so a cassette recorded with
llama.cpp in process replays for the same request anywhere (``--llm replay:DIR``).
"""

from __future__ import annotations

import hashlib
import json
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

#: bumped when the canonical form or the prompt wording changes: old cassettes then miss
SCORE_KEY_VERSION = 1

#: the assistant's persona line; Qwen2.5's own template adds a system turn when none is given
SYSTEM = "You are a helpful assistant."
_ASK = "In one sentence, describe how things should be when the task is done."
_ASK_WITHOUT_INSTRUCTION = "In one sentence, describe how some things in this room could be left."


def chatml(system: str, user: str) -> str:
    """The ChatML text of a system and a user turn, open for the assistant's answer."""
    return (f"<|im_start|>system\n{system}<|im_end|>\n<|im_start|>user\n{user}<|im_end|>\n"
            "<|im_start|>assistant\n")


def conditional_prompt(objects: str, instruction: str) -> str:
    """The prompt of log P(sentence | objects + instruction). It starts like
    :func:`unconditional_prompt`, so a prefix cache shares the objects part."""
    return chatml(SYSTEM, f"Objects in the room: {objects}\nTask: {instruction.strip()}\n{_ASK}")


def unconditional_prompt(objects: str) -> str:
    """The prompt of log P(sentence | objects only): the calibration term."""
    return chatml(SYSTEM, f"Objects in the room: {objects}\n{_ASK_WITHOUT_INSTRUCTION}")


class ScoreRequest(BaseModel):
    """Score ``candidates`` (end-state sentences) against ``instruction`` in a room with
    ``objects`` (a short summary: the prompt is evaluated once per task, so its length is
    the cost)."""

    model_config = ConfigDict(frozen=True)

    stage: str = Field("pfg.score", description="the usage ledger key")
    objects: str = Field(min_length=1)
    instruction: str = Field(min_length=1)
    candidates: tuple[str, ...] = Field(min_length=1, max_length=16)

    @property
    def conditional(self) -> str:
        return conditional_prompt(self.objects, self.instruction)

    @property
    def unconditional(self) -> str:
        return unconditional_prompt(self.objects)

    def canonical(self) -> dict[str, Any]:
        """What defines the request: the rendered prompts and the candidates."""
        return {"v": SCORE_KEY_VERSION, "kind": "score", "stage": self.stage, "conditional": self.conditional,
                "unconditional": self.unconditional, "candidates": list(self.candidates)}

    def key(self) -> str:
        blob = json.dumps(self.canonical(), sort_keys=True, separators=(",", ":"), ensure_ascii=False)
        return hashlib.sha256(blob.encode("utf-8")).hexdigest()


class CandidateScore(BaseModel):
    """The log-probabilities (natural log, summed over the sentence's tokens) of one sentence."""

    model_config = ConfigDict(frozen=True)

    sentence: str
    conditional: float = Field(description="log P(sentence | objects + instruction)")
    unconditional: float = Field(description="log P(sentence | objects only)")
    tokens: int = Field(ge=1, description="tokens in the sentence")

    @property
    def pmi(self) -> float:
        return self.conditional - self.unconditional


class ScoreResponse(BaseModel):
    """The scores, in the order of the request's candidates.

    ``input_tokens``: the tokens of every scored sequence (prompt + sentence), what the
    model would evaluate without a cache; ``evaluated_tokens``: what it did evaluate (the
    prefix cache's saving is the difference; an HTTP server does not say, so there it
    equals ``input_tokens``)."""

    model_config = ConfigDict(frozen=True)

    scores: tuple[CandidateScore, ...]
    input_tokens: int = 0
    evaluated_tokens: int = 0
    latency: float = 0.0
    model: str = ""
    replayed: bool = False

    @property
    def pmi(self) -> list[float]:
        return [s.pmi for s in self.scores]

    def stored(self) -> dict[str, Any]:
        """The JSON a cassette keeps (``replayed`` is set on load)."""
        return self.model_dump(mode="json", exclude={"replayed"})
