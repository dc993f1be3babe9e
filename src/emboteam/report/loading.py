"""Reading a run directory (``episode.json`` + ``trace.jsonl``) with errors a user can act on.

The one reader of a saved episode: a plain read would surface a raw ``FileNotFoundError``,
``JSONDecodeError`` or pydantic ``ValidationError``; the report is what people open after
a run went wrong, so each problem becomes a :class:`ReportError` naming the file (and line) at fault.
"""

from __future__ import annotations

import json
from pathlib import Path

from pydantic import ValidationError

from emboteam.errors import EmboTeamError
from emboteam.exec.episode import Episode
from emboteam.exec.trace import TraceEvent


class ReportError(EmboTeamError):
    """A run or benchmark directory the report cannot be built from."""


def _first_error(exc: ValidationError) -> str:
    err = exc.errors()[0]
    where = ".".join(str(p) for p in err["loc"]) or "(top level)"
    more = f" (and {exc.error_count() - 1} more)" if exc.error_count() > 1 else ""
    return f"{where}: {err['msg']}{more}"


def read_trace(path: Path, problems: list[str] | None = None) -> list[TraceEvent]:
    """The events of ``trace.jsonl``, in file order; a bad line is reported by number.

    With a ``problems`` list, a bad line is skipped and described there instead: a run
    that crashed mid-write leaves a truncated last line, and the events before it are
    still worth a report."""
    events: list[TraceEvent] = []
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise ReportError(f"cannot read {path}: {exc}") from None
    for number, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        try:
            events.append(TraceEvent.model_validate(json.loads(line)))
        except json.JSONDecodeError as exc:
            why = f"{path}:{number}: not JSON ({exc.msg})"
        except ValidationError as exc:
            why = f"{path}:{number}: not a trace event: {_first_error(exc)}"
        else:
            continue
        if problems is None:
            raise ReportError(why)
        problems.append(f"{why}; line left out of the report")
    return events


def load_episode_dir(directory: Path, problems: list[str] | None = None) -> Episode:
    """The episode saved in ``directory`` by :meth:`Episode.save`, with its trace (a
    missing ``trace.jsonl`` means an episode that ended before acting: empty trace).
    ``problems``: see :func:`read_trace`."""
    if not directory.is_dir():
        raise ReportError(f"{directory} is not a directory")
    path = directory / "episode.json"
    if not path.is_file():
        raise ReportError(f"{directory} has no episode.json: not the output of `emboteam run --out`")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise ReportError(f"cannot read {path}: {exc}") from None
    except json.JSONDecodeError as exc:
        raise ReportError(f"{path}: not JSON ({exc.msg} at line {exc.lineno})") from None
    if not isinstance(data, dict):
        raise ReportError(f"{path}: expected a JSON object, found {type(data).__name__}")
    trace_path = directory / "trace.jsonl"
    trace = read_trace(trace_path, problems) if trace_path.exists() else []
    try:
        return Episode.model_validate({**data, "trace": trace})
    except ValidationError as exc:
        raise ReportError(f"{path}: not an episode: {_first_error(exc)}") from None
