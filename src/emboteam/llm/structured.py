"""Structured answers with a bounded repair loop.

A stage asks for a JSON object of a schema and gives a ``convert`` function that turns
it into its domain type (raising :class:`Rejected` or another validation error with a
message the model can act on). Every answer is checked three ways, whatever the backend
promised: it must be a JSON object, validate against the schema (``jsonschema``), and
convert. A failure goes back to the model as feedback -- its own answer, then the error
-- for at most ``repair_rounds`` more calls; then :class:`LLMMalformedOutput`. Nothing
in an answer is ever executed: it is data, converted into typed values or rejected.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from string import Template
from typing import Any, TypeVar

import jsonschema  # no stubs in the venv (types-jsonschema)
from pydantic import ValidationError

from emboteam.errors import EmboTeamError
from emboteam.llm.client import LLMClient
from emboteam.llm.errors import LLMError, LLMMalformedOutput
from emboteam.llm.messages import LLMRequest, Message
from emboteam.llm.truncated import complete_prefix

log = logging.getLogger(__name__)

T = TypeVar("T")

#: how much of a rejected answer is echoed back (long garbage would eat the context)
_ECHO_LIMIT = 6000

#: the default feedback message (``$errors`` is the list of problems); stages pass their own
#: prompt file's text
FEEDBACK = ("Your answer was rejected:\n$errors\n\nAnswer again with the complete, corrected JSON object "
            "and nothing else.")


class Rejected(ValueError):
    """An answer that is well-formed JSON but wrong for the task (unknown object, cycle,
    a skill the robot lacks ...). Its message is fed back to the model."""


def schema_errors(obj: Any, schema: dict[str, Any], limit: int = 8) -> list[str]:
    """Readable schema violations, shortest path first. Enum violations do not repeat the
    (possibly hundreds of) allowed values: the prompt already lists them; a list over its
    item limit is named by its length and the limit."""
    validator = jsonschema.Draft202012Validator(schema)
    errors = sorted(validator.iter_errors(obj), key=lambda e: (len(e.absolute_path), str(e.absolute_path)))
    out: list[str] = []
    for e in errors[:limit]:
        where = "/".join(str(p) for p in e.absolute_path) or "(top level)"
        if e.validator == "enum":
            out.append(f"{where}: {e.instance!r} is not an allowed value here")
        elif e.validator == "anyOf":
            out.append(f"{where}: {_short(repr(e.instance))} matches none of the allowed forms "
                       f"(an allowed value or null)")
        elif e.validator == "additionalProperties":
            out.append(f"{where}: {e.message}")
        elif e.validator == "maxItems" and isinstance(e.instance, list):
            # the bound, not a cut-off repr of the whole list: what the model must change
            out.append(f"{where}: {len(e.instance)} items, at most {e.validator_value} allowed")
        else:
            out.append(f"{where}: {_short(e.message)}")
    if len(errors) > limit:
        out.append(f"... and {len(errors) - limit} more")
    return out


def _short(text: str, limit: int = 160) -> str:
    return text if len(text) <= limit else text[:limit] + "..."


def _problems(exc: Exception) -> str:
    if isinstance(exc, ValidationError):
        return "\n".join(f"- {'/'.join(str(p) for p in err['loc']) or '(top level)'}: {err['msg']}"
                         for err in exc.errors()[:8])
    return f"- {exc}"


def _cut_off_problems(text: str, max_tokens: int, schema: dict[str, Any], convert: Callable[[dict[str, Any]], T],
                      defaults: dict[str, Any] | None = None) -> str:
    """Feedback on an answer cut at the token limit: the limit, and what the checks find
    in its complete part (a looping model's repetitions), never an acceptance."""
    head = (f"- the answer is not a JSON object: it was cut off at the {max_tokens}-token limit; "
            "state each condition once, in fewer and shorter items")
    partial = complete_prefix(text)
    if partial is None:
        return head
    if defaults:
        partial = {**defaults, **partial}
    problems = [p for p in schema_errors(partial, schema) if "is too short" not in p]
    if not problems:
        try:
            convert(partial)
        except LLMError:
            raise
        except (ValueError, EmboTeamError) as exc:
            problems = [line.removeprefix("- ") for line in _problems(exc).splitlines()]
    if not problems:
        return head
    return head + "\n" + "\n".join(f"- in the part before the cut: {p}" for p in problems)


def ask_structured(client: LLMClient, request: LLMRequest, convert: Callable[[dict[str, Any]], T], *,
                   repair_rounds: int = 2, feedback: str = FEEDBACK,
                   defaults: dict[str, Any] | None = None) -> T:
    """Ask until ``convert`` accepts an answer, at most ``1 + repair_rounds`` calls.

    ``request.json_schema`` must be set. Repair calls are made under the stage
    ``<stage>.repair`` so the usage ledger shows what feedback cost. ``feedback`` is a
    :class:`string.Template` with ``$errors``. ``convert`` may raise
    :class:`Rejected`, ``ValueError``, pydantic's ``ValidationError`` or any
    non-LLM :class:`EmboTeamError` (a planner error, say): its message becomes feedback.
    ``defaults`` fills top-level keys an answer leaves out (a nullable field strict mode
    requires, such as ``clarification``: leaving out a null is not a wrong answer).
    """
    if request.json_schema is None:
        raise ValueError("ask_structured needs a request with a json_schema")
    schema = request.json_schema
    messages = list(request.messages)
    last_error = ""
    for round_no in range(repair_rounds + 1):
        stage = request.stage if round_no == 0 or request.stage.endswith(".repair") else f"{request.stage}.repair"
        response = client.complete(request.model_copy(update={"messages": tuple(messages), "stage": stage}))
        obj = response.parsed
        if obj is not None and defaults:
            obj = {**defaults, **obj}
        if obj is None and response.finish_reason in ("length", "max_tokens"):
            last_error = _cut_off_problems(response.text, request.max_tokens, schema, convert, defaults)
        elif obj is None:
            last_error = "- the answer is not a JSON object"
        else:
            problems = schema_errors(obj, schema)
            if problems:
                last_error = "\n".join(f"- {p}" for p in problems)
            else:
                try:
                    return convert(obj)
                except LLMError:
                    raise
                except (ValueError, EmboTeamError) as exc:
                    last_error = _problems(exc)
        log.info("llm %s: answer rejected (round %d of %d): %s", request.stage, round_no + 1,
                 repair_rounds + 1, last_error.replace("\n", " "))
        messages.append(Message(role="assistant", content=response.text[:_ECHO_LIMIT] or "(empty answer)"))
        messages.append(Message(role="user", content=Template(feedback).safe_substitute(errors=last_error).strip()))
    raise LLMMalformedOutput(f"no acceptable answer after {repair_rounds + 1} call(s); last problems: "
                             f"{last_error.replace(chr(10), ' ')}", stage=request.stage)
