"""Text the command line shows that came from a user or a file: an instruction, a task
id, a suite's file name, an error message quoting them.

Such text may hold control characters (``\\x1b[31m`` pasted into an instruction, a
suite file written by a script); printed raw they would drive the terminal (colours,
cursor moves, a retitled window). :func:`printable` writes them as Python escapes
instead, so what the user typed is shown, not obeyed. The one error object every
command prints under ``--json`` is built here too (:func:`error_object`), so ``run``,
``plan`` and the rest report a failure the same way (docs/cli.md).
"""

from __future__ import annotations

import re

from emboteam.errors import exit_code_of

# C0 controls but newline and tab are folded by one_line(); DEL; C1 controls; and the
# invisible format characters that reorder text (bidi overrides: "Trojan source")
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u200e\u200f\u202a-\u202e\u2066-\u2069]")


def _escape(match: re.Match[str]) -> str:
    code = ord(match.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def printable(text: str) -> str:
    """``text`` with every control character written as an escape (``\\x1b``)."""
    return _CONTROL.sub(_escape, text)


def one_line(text: str) -> str:
    """One printable line: whitespace runs (newlines included) become one space."""
    return printable(" ".join(text.split()))


def split_error(error: str) -> tuple[str | None, str]:
    """An episode's recorded error (``"ClassName: message"``) as (class name, message as
    commands show it): the message without the class name of a typed error, as ``plan``
    raises it. An error that is not one of ours keeps its text whole, with no type."""
    name, sep, rest = error.partition(":")
    if sep and name.strip().isidentifier() and exit_code_of(name.strip()) is not None:
        return name.strip(), rest.strip()
    return None, error


def user_message(error: str) -> str:
    """The message of an episode's recorded error as commands show it (:func:`split_error`)."""
    return split_error(error)[1]


def error_object(message: str, code: int, error_type: str | None = None) -> dict[str, object]:
    """The JSON object of a failed command: ``success`` false, ``error`` (one line,
    control characters escaped, no class name), ``error_type`` (the class of a typed
    error, e.g. ``GroundingError``, ``LLMTimeout``; ``UsageError`` for a bad option;
    None when there is none) and ``exit_code``."""
    return {"success": False, "error": one_line(message), "error_type": error_type, "exit_code": code}
