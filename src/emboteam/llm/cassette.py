"""Cassettes: a folder of recorded request/response pairs, for exact replay.

Layout::

    DIR/cassette.json      {"format": "emboteam-llm-cassette", "version": 1,
                            "recorded_with": ["openai:gpt-4o-mini@http://host/v1", ...]}
    DIR/<key>.json         {"key", "stage", "request": <canonical request>, "response": {...}}
                           or, for a call that timed out for good, "failure": {"kind": "timeout", "message"}
    DIR/<key>.json         {"key", "stage", "kind": "score", "request": <canonical score request>,
                            "response": {"scores": [{sentence, conditional, unconditional, tokens}],
                                         input_tokens, evaluated_tokens, latency, model}}
                           a PMI scoring call (:mod:`emboteam.llm.scoring`); its key hashes the
                           rendered scoring prompts and the candidates

``<key>`` is :meth:`LLMRequest.key`, a hash of the provider-independent request, so a
benchmark recorded with one model replays without it, and a request the recording never
saw fails loudly (:class:`LLMReplayMiss`, naming the stage and the key) instead of
being answered by something else. Nothing secret is written: requests hold prompts and
schemas, the spec is stored without URL credentials, API keys never reach this module.
Entries are written atomically (temp file + rename), so parallel workers can record
into one folder. A final time-out (the in-process llama.cpp backend's, which is not
retried) is recorded too: a benchmark run on a slow machine then replays with the same
failed call instead of a replay miss.
"""

from __future__ import annotations

import json
import os
import tempfile
import threading
from pathlib import Path
from typing import Any

from emboteam.llm.backend import Backend, PermanentFailure, ScoringUnsupported
from emboteam.llm.errors import LLMConfigError, LLMReplayMiss
from emboteam.llm.messages import LLMRequest, LLMResponse
from emboteam.llm.scoring import ScoreRequest, ScoreResponse

FORMAT = "emboteam-llm-cassette"
VERSION = 1
META = "cassette.json"

#: response fields stored in an entry (``parsed`` is recomputed from ``text`` on replay)
_STORED = ("text", "refusal", "finish_reason", "input_tokens", "output_tokens", "latency", "model")


def _write_atomic(path: Path, payload: dict[str, Any]) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".json")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            json.dump(payload, fh, indent=1, ensure_ascii=False, sort_keys=True)
            fh.write("\n")
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


class Cassette:
    """Read and write one cassette folder."""

    _meta_lock = threading.Lock()

    def __init__(self, folder: str | Path) -> None:
        self.folder = Path(folder).expanduser()

    def entry_path(self, key: str) -> Path:
        return self.folder / f"{key}.json"

    def open_for_recording(self, recorded_with: str) -> None:
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise LLMConfigError(f"cannot create cassette folder {self.folder}: {exc}") from None
        with self._meta_lock:
            meta: dict[str, Any] = self._read_meta() if (self.folder / META).exists() else {
                "format": FORMAT, "version": VERSION, "recorded_with": []}
            specs: list[str] = list(meta.get("recorded_with") or [])
            if recorded_with not in specs:
                specs.append(recorded_with)
            meta["recorded_with"] = specs
            _write_atomic(self.folder / META, meta)

    def _read_meta(self) -> dict[str, Any]:
        path = self.folder / META
        try:
            meta = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise LLMConfigError(f"{path} is not a cassette index: {exc}") from None
        if not isinstance(meta, dict) or meta.get("format") != FORMAT:
            raise LLMConfigError(f"{path} is not an EmboTeam LLM cassette")
        if meta.get("version") != VERSION:
            raise LLMConfigError(f"{path}: cassette version {meta.get('version')} is not {VERSION}")
        return meta

    def check_readable(self) -> dict[str, Any]:
        if not (self.folder / META).is_file():
            raise LLMConfigError(f"no cassette at {self.folder} (expected {META}; record one first, see docs/llm.md)")
        return self._read_meta()

    def save(self, request: LLMRequest, response: LLMResponse) -> None:
        key = request.key()
        _write_atomic(self.entry_path(key), {
            "key": key, "stage": request.stage, "request": request.canonical(),
            "response": {f: getattr(response, f) for f in _STORED},
        })

    def save_failure(self, request: LLMRequest, failure: PermanentFailure) -> None:
        """A final time-out, replayed as the same failure."""
        key = request.key()
        _write_atomic(self.entry_path(key), {
            "key": key, "stage": request.stage, "request": request.canonical(),
            "failure": {"kind": failure.kind, "message": str(failure)},
        })

    def save_score(self, request: ScoreRequest, response: ScoreResponse) -> None:
        key = request.key()
        _write_atomic(self.entry_path(key), {"key": key, "stage": request.stage, "kind": "score",
                                             "request": request.canonical(), "response": response.stored()})

    def save_score_failure(self, request: ScoreRequest, failure: PermanentFailure) -> None:
        key = request.key()
        _write_atomic(self.entry_path(key), {"key": key, "stage": request.stage, "kind": "score",
                                             "request": request.canonical(),
                                             "failure": {"kind": failure.kind, "message": str(failure)}})

    def _entry(self, key: str, stage: str, canonical: dict[str, Any]) -> tuple[Path, dict[str, Any]]:
        """The stored entry of a request, checked against it; a miss raises LLMReplayMiss."""
        path = self.entry_path(key)
        if not path.is_file():
            raise LLMReplayMiss(f"no recorded response for request {key} in cassette {self.folder}; "
                                f"the prompt, schema or parameters differ from the recording",
                                stage=stage, key=key)
        try:
            entry = json.loads(path.read_text(encoding="utf-8"))
            if entry.get("request") != json.loads(json.dumps(canonical)):
                raise ValueError("stored request differs from the request (corrupt or edited entry)")
        except (OSError, ValueError, AttributeError) as exc:
            raise LLMReplayMiss(f"unusable cassette entry {path}: {exc}", stage=stage, key=key) from None
        return path, entry

    @staticmethod
    def _recorded_failure(entry: dict[str, Any]) -> PermanentFailure | None:
        failure = entry.get("failure")
        if failure is None:
            return None
        if failure.get("kind") != "timeout":
            raise ValueError(f"unknown recorded failure {failure.get('kind')!r}")
        return PermanentFailure("timeout", f"(recorded) {failure['message']}")

    def load(self, request: LLMRequest) -> LLMResponse:
        key = request.key()
        path, entry = self._entry(key, request.stage, request.canonical())
        try:
            recorded = self._recorded_failure(entry)
            if recorded is None:
                stored = entry["response"]
                return LLMResponse(**{f: stored[f] for f in _STORED if f in stored}, replayed=True)
        except (ValueError, KeyError, TypeError, AttributeError) as exc:
            raise LLMReplayMiss(f"unusable cassette entry {path}: {exc}", stage=request.stage, key=key) from None
        raise recorded

    def load_score(self, request: ScoreRequest) -> ScoreResponse:
        key = request.key()
        path, entry = self._entry(key, request.stage, request.canonical())
        try:
            recorded = self._recorded_failure(entry)
            if recorded is None:
                response = ScoreResponse.model_validate({**entry["response"], "replayed": True})
                if [s.sentence for s in response.scores] != list(request.candidates):
                    raise ValueError("the recorded scores are not of the request's candidates")
                return response
        except (ValueError, KeyError, TypeError, AttributeError) as exc:  # pydantic's ValidationError too
            raise LLMReplayMiss(f"unusable cassette entry {path}: {exc}", stage=request.stage, key=key) from None
        raise recorded


class RecordingBackend:
    """Wraps any backend and writes every answered request into a cassette."""

    def __init__(self, inner: Backend, folder: str | Path) -> None:
        self.inner = inner
        self.name = inner.name
        self.cassette = Cassette(folder)
        self.cassette.open_for_recording(inner.name)

    def send(self, request: LLMRequest) -> LLMResponse:
        try:
            response = self.inner.send(request)
        except PermanentFailure as failure:
            if failure.kind == "timeout":  # final (not retried): part of what the run did
                self.cassette.save_failure(request, failure)
            raise
        self.cassette.save(request, response)
        return response

    def score(self, request: ScoreRequest) -> ScoreResponse:
        inner = getattr(self.inner, "score", None)
        if inner is None:
            raise ScoringUnsupported(f"{self.inner.name} gives no token log-probabilities")
        try:
            response: ScoreResponse = inner(request)
        except PermanentFailure as failure:
            if failure.kind == "timeout":
                self.cassette.save_score_failure(request, failure)
            raise
        self.cassette.save_score(request, response)
        return response


class ReplayBackend:
    """Answers from a cassette only; a request it does not hold raises LLMReplayMiss."""

    def __init__(self, folder: str | Path) -> None:
        self.cassette = Cassette(folder)
        meta = self.cassette.check_readable()
        recorded = ", ".join(meta.get("recorded_with", [])) or "unknown"
        self.name = f"replay:{self.cassette.folder} (recorded with {recorded})"

    def send(self, request: LLMRequest) -> LLMResponse:
        return self.cassette.load(request)

    def score(self, request: ScoreRequest) -> ScoreResponse:
        return self.cassette.load_score(request)
