"""Loopback LLM servers for the tests: real HTTP on 127.0.0.1, scripted answers and
injected faults, speaking the OpenAI chat-completions and the Anthropic messages wire
formats, so the official clients run unmodified against them.

Each server has a script: a list of :class:`Reply` (or callables taking the request
body and returning one) served in order; when it runs out, ``default`` answers (a 500
"script exhausted" unless set), so a test that calls more than it expects fails loudly.
Every request body and its headers are kept in ``requests`` / ``headers``.
"""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any, Literal

Flavor = Literal["openai", "anthropic"]


@dataclass
class Reply:
    status: int = 200
    content: str | None = None
    refusal: str | None = None
    raw: bytes | None = None
    delay: float = 0.0
    headers: dict[str, str] = field(default_factory=dict)
    finish_reason: str | None = None
    input_tokens: int | None = None
    output_tokens: int | None = None

    @classmethod
    def answer(cls, obj: Any, **kw: Any) -> Reply:
        """The model answers ``obj`` (a dict/list is sent as JSON text, a str verbatim)."""
        return cls(content=obj if isinstance(obj, str) else json.dumps(obj), **kw)

    @classmethod
    def error(cls, status: int, *, retry_after: str | None = None, message: str = "injected fault") -> Reply:
        headers = {"Retry-After": retry_after} if retry_after is not None else {}
        body = {"error": {"type": "injected", "message": message}}
        return cls(status=status, raw=json.dumps(body).encode(), headers=headers)

    @classmethod
    def hang(cls, seconds: float) -> Reply:
        return cls(content="{}", delay=seconds)

    @classmethod
    def garbage(cls, body: bytes = b"<html>502 bad gateway, not JSON") -> Reply:
        return cls(raw=body)

    @classmethod
    def refuse(cls, text: str = "I can't help with that.") -> Reply:
        return cls(refusal=text)


Script = list["Reply | Callable[[dict[str, Any]], Reply]"]


class ScriptedServer:
    """A ThreadingHTTPServer in a daemon thread; use as a context manager."""

    def __init__(self, flavor: Flavor, script: Script | None = None, *, default: Reply | None = None,
                 model: str = "scripted-model") -> None:
        self.flavor = flavor
        self.script: Script = list(script or [])
        self.default = default or Reply.error(500, message="script exhausted")
        self.model = model
        self.requests: list[dict[str, Any]] = []
        self.headers: list[dict[str, str]] = []
        self._lock = threading.Lock()
        server = self

        class Handler(BaseHTTPRequestHandler):
            def log_message(self, format: str, *args: Any) -> None:  # keep test output quiet
                pass

            def do_POST(self) -> None:
                length = int(self.headers.get("Content-Length", "0"))
                body = json.loads(self.rfile.read(length) or b"{}")
                path_ok = self.path.rstrip("/").endswith(
                    "/chat/completions" if server.flavor == "openai" else "/v1/messages")
                with server._lock:
                    server.requests.append(body)
                    server.headers.append({k.lower(): v for k, v in self.headers.items()})
                    step = server.script.pop(0) if server.script else server.default
                reply = step(body) if callable(step) else step
                if not path_ok:
                    reply = Reply.error(404, message=f"unknown path {self.path}")
                if reply.delay:
                    time.sleep(reply.delay)
                payload = reply.raw if reply.raw is not None else json.dumps(server._body(body, reply)).encode()
                try:
                    self.send_response(reply.status)
                    self.send_header("Content-Type", "application/json")
                    self.send_header("Content-Length", str(len(payload)))
                    for k, v in reply.headers.items():
                        self.send_header(k, v)
                    self.end_headers()
                    self.wfile.write(payload)
                except (BrokenPipeError, ConnectionResetError):
                    pass  # the client gave up (time-out test)

        self._httpd = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self._httpd.daemon_threads = True
        self._httpd.block_on_close = False
        self._thread = threading.Thread(target=self._httpd.serve_forever, kwargs={"poll_interval": 0.02},
                                        daemon=True)

    # ---- wire formats ------------------------------------------------------------------
    def _body(self, request: dict[str, Any], reply: Reply) -> dict[str, Any]:
        content = reply.content or ""
        tokens_in = reply.input_tokens if reply.input_tokens is not None else len(json.dumps(request)) // 4
        tokens_out = reply.output_tokens if reply.output_tokens is not None else max(1, len(content) // 4)
        if self.flavor == "openai":
            return {
                "id": "chatcmpl-test", "object": "chat.completion", "created": 0, "model": self.model,
                "choices": [{"index": 0, "finish_reason": reply.finish_reason or "stop",
                             "message": {"role": "assistant", "content": None if reply.refusal else content,
                                         "refusal": reply.refusal}}],
                "usage": {"prompt_tokens": tokens_in, "completion_tokens": tokens_out,
                          "total_tokens": tokens_in + tokens_out},
            }
        blocks: list[dict[str, Any]]
        stop = reply.finish_reason
        tool = (request.get("tool_choice") or {}).get("name")
        if reply.refusal:
            blocks, stop = [{"type": "text", "text": reply.refusal}], stop or "refusal"
        elif tool:
            try:
                blocks = [{"type": "tool_use", "id": "toolu_test", "name": tool, "input": json.loads(content)}]
                stop = stop or "tool_use"
            except ValueError:  # a malformed answer cannot be a tool input: send it as text
                blocks = [{"type": "text", "text": content}]
        else:
            blocks = [{"type": "text", "text": content}]
        return {"id": "msg_test", "type": "message", "role": "assistant", "model": self.model, "content": blocks,
                "stop_reason": stop or "end_turn", "stop_sequence": None,
                "usage": {"input_tokens": tokens_in, "output_tokens": tokens_out}}

    # ---- life cycle --------------------------------------------------------------------
    @property
    def base_url(self) -> str:
        host, port = self._httpd.server_address[:2]
        root = f"http://{host}:{port}"
        return f"{root}/v1" if self.flavor == "openai" else root

    def spec(self, model: str = "test-model") -> str:
        return f"{self.flavor}:{model}@{self.base_url}"

    def push(self, *steps: Reply | Callable[[dict[str, Any]], Reply]) -> None:
        with self._lock:
            self.script.extend(steps)

    def __enter__(self) -> ScriptedServer:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._httpd.shutdown()
        self._httpd.server_close()


def free_port() -> int:
    """A loopback port nothing listens on (bound, then released)."""
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


# ---- answer builders shared by the LLM tests -----------------------------------------------
def cond(predicate: str, *subject: str, receptacle: str | None = None, count: int = 1,
         liquid: str | None = None) -> dict[str, Any]:
    """One goal condition in the answer schema of emboteam.pfg.schema."""
    return {"predicate": predicate, "subject": list(subject), "receptacle": receptacle, "count": count,
            "liquid": liquid}


def subtask(sid: str, *goal: dict[str, Any], robot: str | None = None, depends_on: tuple[str, ...] = (),
            final: bool = True, description: str = "do it") -> dict[str, Any]:
    return {"id": sid, "description": description, "robot": robot, "goal": list(goal),
            "depends_on": list(depends_on), "final": final}


def taskspec_answer(*subtasks: dict[str, Any]) -> dict[str, Any]:
    return {"subtasks": list(subtasks)}


#: the weak-model scenario both the front-end and the cut-off tests replay: two placements
#: in FloorPlan1's fridge, and a retry policy that gives up at once
FRIDGE = "Put the apple and the tomato in the fridge."
APPLE = cond("inside", "Apple_1", receptacle="Fridge_1")
TOMATO = cond("inside", "Tomato_1", receptacle="Fridge_1")
