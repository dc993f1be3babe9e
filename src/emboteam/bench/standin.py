"""A perfect-model stand-in: a loopback OpenAI-compatible server that knows the answers.

It measures *routing*, never model quality: given the ground-truth goals of a set of
tasks, it answers every PFG request as a model that always knows what the user meant:

- a decomposition (``pfg``, ``pfg.repair``, the hybrid front end's fallback): the task's
  ground-truth goals, one subtask per condition (:class:`~emboteam.pfg.oracle.OracleFrontend`),
  in the answer form of :func:`~emboteam.pfg.schema.taskspec_to_answer`;
- a review (``pfg.review``, ``hp.validate``): "ok" when the draft under review states the
  ground-truth goal (or a goal the caller declared right with :meth:`PerfectModel.accept`),
  otherwise the correction (the ground-truth subtasks).

So a front-end mode's success rate with the stand-in is its *ceiling*: what it would reach
with a model that never errs, given where it asks the model and what it lets the model
change. ``benchmarks/frontend_routing.py`` uses it.

How it knows the task: it is started with the tasks (instruction, floor plan, ground-truth
goal) and finds, in the request's user turns from the last one back, the longest
registered instruction (compared with whitespace collapsed, after the same quoting the
front ends apply). A floor plan named in that turn picks among tasks with the same text.

Schema-driven and tolerant: the kind of request is read from its JSON schema, not from
prompt wording (a ``subtasks`` array is a decomposition; with a boolean ``ok`` or an enum
holding ``"ok"`` beside it, a review), and the answer is fitted to the request's schema
(properties it does not name dropped, required ones it lacks filled with the schema's
null, false, empty or first-enum value), so prompt and schema changes do not break it.

Only a loopback address is accepted. Hand-written on :mod:`http.server` (no new
dependency): two routes, JSON in, JSON out. ``python -m emboteam.bench.standin --suite
mace-thor`` serves a suite for your own routing measurements.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import threading
from collections import Counter
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from ipaddress import ip_address
from typing import Any

from emboteam.errors import EmboTeamError
from emboteam.world.goals import Condition, Goal

#: printed by the benchmark and the ``python -m`` entry: what the numbers mean
DISCLAIMER = ("the model is a stand-in that knows every task's ground-truth goal: it measures "
              "routing (where a front end asks the model and what it lets the model change), "
              "never model quality")

MODEL_NAME = "emboteam-perfect-standin"


class StandInError(EmboTeamError):
    """A stand-in that cannot be built (a non-loopback host, conflicting ground truths)."""


@dataclass(frozen=True)
class KnownTask:
    """What the stand-in knows about one task."""

    instruction: str
    floor_plan: str
    goal: Goal


def _squash(text: str) -> str:
    """Text compared for matching: the front ends' quoting, whitespace collapsed, lower case."""
    return " ".join(text.replace("<<<", "«").replace(">>>", "»").split()).lower()


def _type_of(name: str) -> str:
    """``Apple_1`` -> ``Apple``; ``Apple_1_Slice_2`` -> ``AppleSliced``; a type stays."""
    from emboteam.world.scene import is_object_id

    if not is_object_id(name):
        return name
    head = name.split("_", 1)[0]
    return head + "Sliced" if "_Slice" in name else head


def condition_key(cond: Condition) -> tuple[Any, ...]:
    """A condition up to the choice of instance: ids count as their type, so a draft that
    names ``Fridge_1`` where the truth says ``Fridge`` is still right in a one-fridge room."""
    subject = tuple(sorted({_type_of(n) for n in ((cond.subject.id,) if cond.subject.id else cond.subject.types)}))
    receptacle = None
    if cond.receptacle is not None:
        names = (cond.receptacle.id,) if cond.receptacle.id else cond.receptacle.types
        receptacle = tuple(sorted({_type_of(n) for n in names}))
    return (cond.predicate.value, subject, receptacle, cond.count, cond.liquid)


def goal_matches(conditions: Iterable[Condition], truth: Goal) -> bool:
    """Whether a draft's final conditions state the ground-truth goal (as sets of keys)."""
    return {condition_key(c) for c in conditions} == {condition_key(c) for c in truth.conditions}


# ---- the request: which task, which kind, which draft ---------------------------------------
def _user_turns(body: dict[str, Any]) -> list[str]:
    out = []
    for m in body.get("messages") or ():
        if isinstance(m, dict) and m.get("role") == "user":
            content = m.get("content")
            if isinstance(content, list):  # content parts
                content = " ".join(str(p.get("text", "")) for p in content if isinstance(p, dict))
            out.append(str(content or ""))
    return out


def _json_values(text: str) -> Iterator[Any]:
    """Every JSON object embedded in ``text`` (a draft, a proposed subtask per line)."""
    decoder = json.JSONDecoder()
    i = text.find("{")
    while i >= 0:
        try:
            value, end = decoder.raw_decode(text, i)
        except ValueError:
            i = text.find("{", i + 1)
            continue
        yield value
        i = text.find("{", end)


def draft_subtasks(text: str) -> list[dict[str, Any]]:
    """The subtasks shown in a review's task turn, in whatever JSON layout the prompt uses
    (one ``{"subtasks": [...]}`` object, or one subtask object per line)."""
    found: list[dict[str, Any]] = []
    for value in _json_values(text):
        if isinstance(value, dict) and isinstance(value.get("subtasks"), list):
            found += [s for s in value["subtasks"] if isinstance(s, dict)]
        elif isinstance(value, dict) and isinstance(value.get("goal"), list):
            found.append(value)
    return found


def draft_conditions(subtasks: Sequence[dict[str, Any]]) -> list[Condition] | None:
    """The final conditions of shown subtasks, or None when one cannot be read."""
    from emboteam.llm.structured import Rejected
    from emboteam.pfg.schema import condition_from_answer

    conds: list[Condition] = []
    for s in subtasks:
        if s.get("final", True) is False:
            continue
        for raw in s.get("goal") or ():
            try:
                conds.append(condition_from_answer({"receptacle": None, "count": 1, "liquid": None, **raw}))
            except (Rejected, KeyError, ValueError, TypeError):
                return None
    return conds


def _decision_field(schema: dict[str, Any]) -> str | None:
    """The property a review answers its verdict in: a boolean ``ok``, or a string enum
    that holds ``"ok"`` (``verdict``)."""
    for name, prop in (schema.get("properties") or {}).items():
        if not isinstance(prop, dict):
            continue
        if name == "ok" and prop.get("type") == "boolean":
            return str(name)
        if prop.get("type") == "string" and "ok" in (prop.get("enum") or ()):
            return str(name)
    return None


# ---- fitting an answer to the request's schema ---------------------------------------------
def _empty(schema: dict[str, Any]) -> Any:
    """The value a required property the stand-in has nothing for gets."""
    if "anyOf" in schema:
        if any(isinstance(b, dict) and b.get("type") == "null" for b in schema["anyOf"]):
            return None
        return _empty(schema["anyOf"][0])
    if "enum" in schema:
        return schema["enum"][0]
    kind = schema.get("type")
    if isinstance(kind, list):
        return None if "null" in kind else _empty({**schema, "type": kind[0]})
    defaults: dict[str, Any] = {"array": [], "boolean": False, "integer": schema.get("minimum", 0), "number": 0,
                                "string": "", "null": None, "object": {}}
    return defaults.get(str(kind))


def fit(value: Any, schema: Any) -> Any:
    """``value`` reshaped to ``schema``: unknown object properties dropped, missing required
    ones filled (:func:`_empty`), strings cut to ``maxLength``; the rest kept as it is."""
    if not isinstance(schema, dict):
        return value
    if "anyOf" in schema and value is not None:
        branches = [b for b in schema["anyOf"] if isinstance(b, dict) and b.get("type") != "null"]
        return fit(value, branches[0]) if len(branches) == 1 else value
    kind = schema.get("type")
    if kind == "object" and isinstance(value, dict):
        props = schema.get("properties") or {}
        out = {k: fit(v, props[k]) for k, v in value.items() if k in props}
        for name in schema.get("required") or props:
            if name not in out and name in props:
                out[name] = _empty(props[name])
        return out
    if kind == "array" and isinstance(value, list):
        return [fit(v, schema.get("items")) for v in value]
    if kind == "string" and isinstance(value, str) and "maxLength" in schema:
        return value[: schema["maxLength"]]
    return value


# ---- the model --------------------------------------------------------------------------
class PerfectModel:
    """The answers, independent of HTTP: ``answer(body) -> (status, dict-or-error)``."""

    def __init__(self, tasks: Iterable[KnownTask]) -> None:
        self.tasks: dict[str, list[KnownTask]] = {}
        for t in tasks:
            self.tasks.setdefault(_squash(t.instruction), []).append(t)
        # longest first: an instruction that contains another registered one wins
        self._keys = sorted(self.tasks, key=len, reverse=True)
        self.counts: Counter[str] = Counter()
        self._lock = threading.Lock()
        #: (instruction, floor plan) -> condition-key sets known to do what the task asks
        #: besides the ground truth's own (:meth:`accept`)
        self._accepted: dict[tuple[str, str], set[frozenset[tuple[Any, ...]]]] = {}

    def accept(self, instruction: str, floor_plan: str, conditions: Iterable[Condition]) -> None:
        """Also answer "ok" to a draft stating ``conditions``: a perfect model knows that a
        goal worded differently from the ground truth still does what the user asked (the
        benchmark calls this for a reading whose episode reached the ground truth)."""
        keys = frozenset(condition_key(c) for c in conditions)
        with self._lock:
            self._accepted.setdefault((_squash(instruction), floor_plan), set()).add(keys)

    def is_right(self, task: KnownTask, conditions: Sequence[Condition] | None) -> bool:
        if conditions is None:
            return False
        if goal_matches(conditions, task.goal):
            return True
        keys = frozenset(condition_key(c) for c in conditions)
        with self._lock:
            return keys in self._accepted.get((_squash(task.instruction), task.floor_plan), set())

    def _count(self, what: str) -> None:
        with self._lock:
            self.counts[what] += 1

    def find_task(self, body: dict[str, Any]) -> tuple[KnownTask, str] | str:
        """The task a request is about and its task turn, or why none was found."""
        for turn in reversed(_user_turns(body)):
            text = _squash(turn)
            key = next((k for k in self._keys if k and k in text), None)
            if key is None:
                continue
            candidates = self.tasks[key]
            named = [t for t in candidates if re.search(rf"\b{re.escape(t.floor_plan)}\b", turn)]
            pool = named or candidates
            goals = {str(t.goal) for t in pool}
            if len(goals) > 1:
                return (f"{len(pool)} registered tasks share this instruction with different goals "
                        f"({', '.join(sorted(t.floor_plan for t in pool))}); register one of them")
            return pool[0], turn
        return "no registered instruction in the request's user turns"

    def answer(self, body: dict[str, Any]) -> tuple[int, dict[str, Any]]:
        from emboteam.pfg.oracle import OracleFrontend
        from emboteam.pfg.schema import taskspec_to_answer

        schema = _response_schema(body)
        if schema is None or "subtasks" not in (schema.get("properties") or {}):
            self._count("refused: not a PFG request")
            return 400, {"error": "the stand-in answers PFG requests only (a JSON schema with 'subtasks')"}
        found = self.find_task(body)
        if isinstance(found, str):
            self._count("refused: unknown task")
            return 400, {"error": f"stand-in: {found}"}
        task, turn = found
        truth = taskspec_to_answer(OracleFrontend(task.goal).spec(task.instruction))
        decision = _decision_field(schema)
        if decision is None:
            self._count("decompose")
            return 200, fit(truth, schema)
        right = self.is_right(task, draft_conditions(draft_subtasks(turn)))
        self._count("review: ok" if right else "review: corrected")
        prop = schema["properties"][decision]
        if prop.get("type") == "boolean":
            verdict: Any = right
        else:
            verdict = "ok" if right else next((v for v in prop["enum"] if v != "ok"), "corrected")
        reply: dict[str, Any] = {decision: verdict, "subtasks": [] if right else truth["subtasks"],
                                 "reason": "the draft states the goal" if right
                                 else "the draft does not state the goal; corrected"}
        return 200, fit(reply, schema)


def _response_schema(body: dict[str, Any]) -> dict[str, Any] | None:
    fmt = body.get("response_format") or {}
    if not isinstance(fmt, dict):
        return None
    schema = (fmt.get("json_schema") or {}).get("schema") if fmt.get("type") == "json_schema" else None
    return schema if isinstance(schema, dict) else None


# ---- HTTP ---------------------------------------------------------------------------------
LOOPBACK_NAMES = ("localhost",)


def check_loopback(host: str) -> None:
    """Refuse any address but a loopback one: the stand-in is for tests and benchmarks."""
    try:
        loopback = host in LOOPBACK_NAMES or ip_address(host).is_loopback
    except ValueError:
        loopback = False
    if not loopback:
        raise StandInError(f"the stand-in listens on a loopback address only (127.0.0.1), not {host!r}")


class StandInServer:
    """The perfect model behind ``/v1/chat/completions`` on a loopback port, in a daemon
    thread. Use as a context manager; :attr:`spec` is the ``--llm`` value that reaches it."""

    def __init__(self, tasks: Iterable[KnownTask], *, host: str = "127.0.0.1", port: int = 0) -> None:
        check_loopback(host)
        self.model = PerfectModel(tasks)
        model = self.model

        class Handler(BaseHTTPRequestHandler):
            def log_message(self, format: str, *args: Any) -> None:  # one line per call is noise here
                pass

            def _send(self, status: int, payload: dict[str, Any]) -> None:
                data = json.dumps(payload).encode()
                self.send_response(status)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(data)))
                self.end_headers()
                self.wfile.write(data)

            def do_GET(self) -> None:
                if self.path.rstrip("/").endswith("/models"):
                    self._send(200, {"object": "list", "data": [{"id": MODEL_NAME, "object": "model"}]})
                else:
                    self._send(404, {"error": {"message": f"no route {self.path}"}})

            def do_POST(self) -> None:
                if not self.path.rstrip("/").endswith("/chat/completions"):
                    self._send(404, {"error": {"message": f"no route {self.path}"}})
                    return
                try:
                    body = json.loads(self.rfile.read(int(self.headers.get("Content-Length") or 0)) or b"{}")
                except ValueError:
                    self._send(400, {"error": {"message": "the body is not JSON"}})
                    return
                status, answer = model.answer(body if isinstance(body, dict) else {})
                if status != 200:
                    self._send(status, {"error": {"type": "invalid_request_error", "message": answer["error"]}})
                    return
                text = json.dumps(answer, separators=(",", ":"))
                prompt_chars = sum(len(t) for t in _user_turns(body))
                self._send(200, {
                    "id": "standin", "object": "chat.completion", "created": 0, "model": MODEL_NAME,
                    "choices": [{"index": 0, "finish_reason": "stop",
                                 "message": {"role": "assistant", "content": text}}],
                    # estimates (4 characters a token): the stand-in has no tokenizer
                    "usage": {"prompt_tokens": prompt_chars // 4, "completion_tokens": len(text) // 4,
                              "total_tokens": (prompt_chars + len(text)) // 4}})

        self._server = ThreadingHTTPServer((host, port), Handler)
        self._server.daemon_threads = True
        self.host = host
        self.port = int(self._server.server_address[1])
        self._thread: threading.Thread | None = None

    @property
    def base_url(self) -> str:
        return f"http://{self.host}:{self.port}/v1"

    @property
    def spec(self) -> str:
        return f"openai:{MODEL_NAME}@{self.base_url}"

    def start(self) -> StandInServer:
        self._thread = threading.Thread(target=self._server.serve_forever, name="standin", daemon=True)
        self._thread.start()
        return self

    def close(self) -> None:
        self._server.shutdown()
        self._server.server_close()
        if self._thread is not None:
            self._thread.join(timeout=5)

    def __enter__(self) -> StandInServer:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.close()


def known_tasks(tasks: Iterable[Any]) -> list[KnownTask]:
    """KnownTasks from benchmark tasks (anything with ``instruction``, ``floor_plan`` and a
    ``ground_truth`` goal); tasks without a goal are skipped."""
    return [KnownTask(t.instruction, t.floor_plan, t.ground_truth) for t in tasks
            if t.ground_truth is not None and t.ground_truth.conditions]


def main(argv: Sequence[str] | None = None) -> int:
    from emboteam.bench.suites import load_suite

    ap = argparse.ArgumentParser(prog="python -m emboteam.bench.standin", description=__doc__.split("\n\n")[0])
    ap.add_argument("--suite", action="append", required=True, help="mace-thor | smart-llm:PATH (repeatable)")
    ap.add_argument("--host", default="127.0.0.1", help="a loopback address (default 127.0.0.1)")
    ap.add_argument("--port", type=int, default=0, help="0: any free port (printed)")
    args = ap.parse_args(argv)
    try:
        tasks = known_tasks(t for s in args.suite for t in load_suite(s).tasks)
        server = StandInServer(tasks, host=args.host, port=args.port)
    except EmboTeamError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(f"stand-in for {len(tasks)} task(s) at {server.base_url}: use --llm {server.spec}\nnote: {DISCLAIMER}",
          flush=True)
    try:
        server._server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server._server.server_close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
