"""A local GGUF model in process through llama-cpp-python (optional extra ``llamacpp``).

Structured output is a grammar: the JSON schema is compiled into a GBNF grammar
(``LlamaGrammar.from_json_schema``) that masks every token the schema does not allow,
so even a tiny model emits schema-shaped JSON. Unlike the HTTP backends, the schema's
length and item-count bounds are kept: the grammar enforces them, which also bounds the
generation.

Time-outs: generation runs in this process, so there is no socket to time out. The
deadline is checked before every batch of the prompt (``Llama.eval`` is wrapped to feed
the prompt in ``n_batch`` chunks: a 1,300-token prompt took 30-50 s on a loaded 2-core
machine) and after every generated token (a stopping criterion). ``create_chat_completion``
takes no stopping criteria, but every llama-cpp-python chat handler generates through
``llama.create_completion``, so that method is wrapped on our own ``Llama`` instance,
under its lock, for the duration of the call. (A logits processor cannot do it: in
llama-cpp-python 0.3 it runs as a ctypes callback whose exceptions are swallowed.)
Retrying would redo the same computation, so a time-out here is final; a recording
cassette stores it, so a replay fails the same way.
"""

from __future__ import annotations

import atexit
import hashlib
import json
import os
import threading
import time
from pathlib import Path
from typing import Any

from emboteam.llm.backend import PermanentFailure
from emboteam.llm.errors import LLMConfigError
from emboteam.llm.messages import LLMRequest, LLMResponse
from emboteam.llm.scoring import ScoreRequest, ScoreResponse
from emboteam.llm.spec import LLMSpec

#: one loaded model per (file, context size): loading costs time and memory
_MODELS: dict[tuple[str, int], tuple[Any, threading.Lock]] = {}
_MODELS_LOCK = threading.Lock()


@atexit.register
def _close_models() -> None:
    """Free the loaded models while Python still runs: llama-cpp-python's own finaliser
    runs after its module is torn down at exit and prints a TypeError traceback."""
    with _MODELS_LOCK:
        for model, _ in _MODELS.values():
            close = getattr(model, "close", None)
            if close is not None:
                close()
        _MODELS.clear()


def _load(path: str, n_ctx: int, n_threads: int | None) -> tuple[Any, threading.Lock]:
    try:
        from llama_cpp.llama import Llama
    except ImportError:
        raise LLMConfigError("the llamacpp backend needs llama-cpp-python: pip install 'emboteam[llamacpp]'") \
            from None
    with _MODELS_LOCK:
        key = (path, n_ctx)
        if key not in _MODELS:
            try:
                # the batch (prompt) threads too: llama-cpp-python defaults them to every core,
                # and on a shared machine a second thread that is not scheduled stalls the first
                # at llama.cpp's spinning barrier (prompt and scoring ran ~10x slower)
                model = Llama(model_path=path, n_ctx=n_ctx, n_threads=n_threads, n_threads_batch=n_threads,
                              seed=0, verbose=False)
            except (ValueError, RuntimeError, OSError) as exc:
                raise LLMConfigError(f"cannot load GGUF model {path}: {exc}") from None
            _MODELS[key] = (model, threading.Lock())
        return _MODELS[key]


#: threads llama.cpp computes with; unset, llama.cpp picks (all cores). Benchmarks on a
#: shared machine set it low.
THREADS_ENV = "EMBOTEAM_LLAMACPP_THREADS"


def _threads_from_env() -> int | None:
    raw = os.environ.get(THREADS_ENV, "").strip()
    if not raw:
        return None
    if not raw.isdigit() or int(raw) < 1:
        raise LLMConfigError(f"{THREADS_ENV} must be a positive integer, not {raw!r}")
    return int(raw)


class _PastDeadline(Exception):
    """Raised between prompt batches once the deadline has passed (caught in ``_generate``)."""


class LlamaCppBackend:
    """A GGUF file; ``spec.model`` is its path."""

    def __init__(self, spec: LLMSpec, *, timeout: float, n_ctx: int = 8192, n_threads: int | None = None) -> None:
        n_threads = n_threads if n_threads is not None else _threads_from_env()
        path = Path(spec.model).expanduser()
        if not path.is_file():
            raise LLMConfigError(f"llamacpp: no GGUF file at {path}")
        self.name = str(spec)
        self.model = path.name
        self._timeout = timeout
        self._llama, self._lock = _load(str(path.resolve()), n_ctx, n_threads)
        self._grammars: dict[str, Any] = {}

    def score(self, request: ScoreRequest) -> ScoreResponse:
        """PMI scores of the candidates (:mod:`emboteam.llm.llamacpp_scoring`)."""
        from emboteam.llm.llamacpp_scoring import LlamaCppScorer

        return LlamaCppScorer(self._llama, self._lock, timeout=self._timeout, model=self.model).score(request)

    def _grammar(self, schema: dict[str, Any]) -> Any:
        from llama_cpp.llama_grammar import LlamaGrammar

        key = hashlib.sha256(json.dumps(schema, sort_keys=True).encode()).hexdigest()
        if key not in self._grammars:
            try:
                # unsorted: the grammar emits properties in schema order (id, description, ...)
                self._grammars[key] = LlamaGrammar.from_json_schema(json.dumps(schema), verbose=False)
            except (ValueError, KeyError, NotImplementedError) as exc:
                raise PermanentFailure("request", f"schema not expressible as a grammar: {exc}") from None
        return self._grammars[key]

    def _generate(self, kwargs: dict[str, Any], deadline: float) -> tuple[Any, bool]:
        """``create_chat_completion`` with a deadline; returns (output, timed_out)."""
        from llama_cpp.llama import StoppingCriteriaList

        timed_out = False

        def past_deadline(_ids: Any, _logits: Any) -> bool:
            nonlocal timed_out
            timed_out = timed_out or time.monotonic() > deadline
            return timed_out

        llama = self._llama
        plain_completion, plain_eval = llama.create_completion, llama.eval

        def create_completion(*args: Any, **kw: Any) -> Any:
            criteria = StoppingCriteriaList([past_deadline])
            if kw.get("stopping_criteria") is not None:
                criteria.extend(kw["stopping_criteria"])
            kw["stopping_criteria"] = criteria
            return plain_completion(*args, **kw)

        def eval_in_batches(tokens: Any) -> None:
            tokens = list(tokens)
            step = max(1, int(llama.n_batch))
            for i in range(0, len(tokens), step):
                if past_deadline(None, None):
                    raise _PastDeadline
                plain_eval(tokens[i:i + step])

        llama.create_completion, llama.eval = create_completion, eval_in_batches
        try:
            return llama.create_chat_completion(**kwargs), timed_out
        except _PastDeadline:
            return None, True
        finally:
            del llama.create_completion, llama.eval  # back to the class's methods

    def send(self, request: LLMRequest) -> LLMResponse:
        kwargs: dict[str, Any] = {
            "messages": [{"role": m.role, "content": m.content} for m in request.messages],
            "max_tokens": request.max_tokens,
            "temperature": request.temperature,
            "seed": request.seed,
        }
        if request.json_schema is not None:
            kwargs["grammar"] = self._grammar(request.json_schema)
        start = time.monotonic()
        with self._lock:
            try:
                out, timed_out = self._generate(kwargs, start + self._timeout)
            except ValueError as exc:  # prompt longer than the context window, bad template
                raise PermanentFailure("request", str(exc)) from None
            except RuntimeError as exc:  # llama.cpp's own failures (decode errors)
                raise PermanentFailure("server", f"llama.cpp failed: {exc}") from None
        latency = time.monotonic() - start
        if timed_out or out is None:
            raise PermanentFailure("timeout", f"generation outlived the {self._timeout:g} s time-out "
                                   f"({latency:.1f} s)")
        choice = out["choices"][0]
        usage = out.get("usage") or {}
        return LLMResponse(
            text=choice["message"].get("content") or "",
            finish_reason=str(choice.get("finish_reason") or ""),
            input_tokens=int(usage.get("prompt_tokens", 0)),
            output_tokens=int(usage.get("completion_tokens", 0)),
            latency=latency,
            model=self.model,
        )
