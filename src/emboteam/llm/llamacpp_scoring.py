"""PMI scoring in process with llama.cpp: token log-probabilities with a prefix cache.

``Llama(logits_all=True)`` would keep a row of logits for every position of the context
(8,192 x 151,936 floats for Qwen2.5: 5 GB), so the sentence's tokens are decoded here
through llama-cpp-python's low-level batch with the logits flag set on exactly the
positions whose next token is scored (the last prompt token and the sentence but its
last token); llama.cpp then returns only those rows.

The prefix cache: the model's KV cache holds the last evaluated sequence
(``Llama.input_ids[:n_tokens]``, the bookkeeping ``Llama.generate`` uses for its own
prefix matching, kept consistent here). A sequence is evaluated from the longest common
prefix with it, so per task the conditional prompt is evaluated once, each candidate
costs its own tokens plus one, and the unconditional prompt shares the system turn and
the objects with the conditional one. ``ScoreResponse.evaluated_tokens`` reports what
was decoded, against ``input_tokens`` without the cache.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Sequence
from typing import Any

import numpy as np

from emboteam.llm.backend import PermanentFailure
from emboteam.llm.scoring import CandidateScore, ScoreRequest, ScoreResponse


def _log_softmax_at(row: np.ndarray, token: int) -> float:
    peak = float(row.max())
    return float(row[token]) - peak - math.log(float(np.exp(row - peak).sum()))


class LlamaCppScorer:
    """Scores on one loaded ``Llama`` (shared with generation, under the same lock)."""

    def __init__(self, llama: Any, lock: threading.Lock, *, timeout: float, model: str) -> None:
        self._llama = llama
        self._lock = lock
        self._timeout = timeout
        self._model = model

    def _tokenize(self, text: str, *, prompt: bool) -> list[int]:
        # a prompt gets the model's own BOS (if its vocabulary asks for one) and its special
        # tokens parsed (<|im_start|>); a sentence is plain text continuing it
        return list(self._llama.tokenize(text.encode("utf-8"), add_bos=prompt, special=prompt))

    def score(self, request: ScoreRequest) -> ScoreResponse:
        start = time.monotonic()
        deadline = start + self._timeout
        with self._lock:
            conditional = self._tokenize(request.conditional, prompt=True)
            unconditional = self._tokenize(request.unconditional, prompt=True)
            sentences = [self._tokenize(s, prompt=False) for s in request.candidates]
            for text, tokens in zip(request.candidates, sentences, strict=True):
                if not tokens:
                    raise PermanentFailure("request", f"the candidate {text!r} has no tokens")
            evaluated = 0
            given: list[float] = []
            alone: list[float] = []
            for prefix, out in ((conditional, given), (unconditional, alone)):
                for sentence in sentences:
                    logprob, decoded = self._sentence_logprob(prefix, sentence, deadline)
                    out.append(logprob)
                    evaluated += decoded
        scores = tuple(CandidateScore(sentence=text, conditional=c, unconditional=u, tokens=len(tokens))
                       for text, tokens, c, u in zip(request.candidates, sentences, given, alone, strict=True))
        total = sum(len(conditional) + len(unconditional) + 2 * len(s) for s in sentences)
        return ScoreResponse(scores=scores, input_tokens=total, evaluated_tokens=evaluated,
                             latency=time.monotonic() - start, model=self._model)

    def _sentence_logprob(self, prefix: Sequence[int], sentence: Sequence[int], deadline: float) -> tuple[float, int]:
        """log P(sentence | prefix) and the number of tokens decoded for it."""
        llama = self._llama
        tokens = [*prefix, *sentence]
        if len(tokens) > llama.n_ctx():
            raise PermanentFailure("request", f"the scoring prompt has {len(tokens)} tokens, more than the "
                                   f"model's context of {llama.n_ctx()}")
        cached = llama.input_ids[:llama.n_tokens]
        common = 0
        for a, b in zip(cached, tokens, strict=False):
            if a != b:
                break
            common += 1
        keep = min(common, len(prefix) - 1)  # the last prompt token's logits score the first word
        first_scored = len(prefix) - 1  # position whose logits predict sentence[0]
        llama._ctx.kv_cache_seq_rm(-1, keep, -1)
        llama.n_tokens = keep
        if hasattr(llama, "_requires_eval"):
            llama._requires_eval = True  # generation after this re-derives its logits
        total = 0.0
        step = max(1, int(llama.n_batch))
        n_vocab = llama.n_vocab()
        for begin in range(keep, len(tokens), step):
            if time.monotonic() > deadline:
                raise PermanentFailure("timeout", f"scoring outlived the {self._timeout:g} s time-out")
            chunk = tokens[begin:begin + step]
            llama._batch.set_batch(batch=chunk, n_past=begin, logits_all=False)
            wanted = [i for i in range(len(chunk)) if first_scored <= begin + i < len(tokens) - 1]
            for i in wanted:
                llama._batch.batch.logits[i] = True
            try:
                llama._ctx.decode(llama._batch)
            except RuntimeError as exc:
                llama.n_tokens = begin  # what is in the cache is valid up to here
                raise PermanentFailure("server", f"llama.cpp failed: {exc}") from None
            llama.input_ids[begin:begin + len(chunk)] = chunk
            llama.n_tokens = begin + len(chunk)
            for i in wanted:
                row = np.ctypeslib.as_array(llama._ctx.get_logits_ith(i), shape=(n_vocab,))
                total += _log_softmax_at(row, tokens[begin + i + 1])
        return total, len(tokens) - keep
