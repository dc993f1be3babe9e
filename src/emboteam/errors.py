"""The root of EmboTeam's typed errors.

Every error a user can cause (bad input, an unusable configuration, an unsolvable goal)
derives from :class:`EmboTeamError`, so the CLI can print one line and exit non-zero
instead of a traceback. Each stage defines its own subclasses next to its code.
"""

from __future__ import annotations

# The exit codes of every ``emboteam`` command (docs/cli.md). Scripts and CI jobs branch on
# them, so each failure family has its own code and no command exits 0 on a task it did
# not do.
#: the goal was reached (``run``), or the job was done (every other command)
EXIT_OK = 0
#: the episode ran and did not reach its goal (``run``), or did only the part of it the
#: planner could plan (``run``, ``plan``: ``not_attempted`` lists the rest)
EXIT_FAILED = 1
#: bad input or configuration: an unknown task, option or file, a bad ``--out``, a goal
#: the scene or team cannot have, an instruction that cannot be understood
EXIT_BAD_INPUT = 2
#: a service the command needs could not be used: the LLM endpoint is unreachable, timed
#: out, rate-limited or failing, a Ray cluster cannot be joined
EXIT_SERVICE = 3
#: a bug in EmboTeam (``EX_SOFTWARE`` of sysexits.h); EMBOTEAM_DEBUG=1 shows the traceback
EXIT_INTERNAL = 70
#: interrupted by Ctrl-C (128 + SIGINT, as shells report it)
EXIT_INTERRUPTED = 130

#: (code, meaning) for the docs and ``--help``
EXIT_CODES: tuple[tuple[int, str], ...] = (
    (EXIT_OK, "goal reached (run) / job done (every other command)"),
    (EXIT_FAILED, "the episode ran and did not reach its goal, or did only the part of it that could be planned"),
    (EXIT_BAD_INPUT, "bad input or configuration (options, task, instruction, --out, goal)"),
    (EXIT_SERVICE, "a service could not be used (LLM endpoint unreachable, timed out, failing)"),
    (EXIT_INTERNAL, "internal error: a bug (EMBOTEAM_DEBUG=1 shows the traceback)"),
    (EXIT_INTERRUPTED, "interrupted (Ctrl-C)"),
)


class EmboTeamError(Exception):
    """Base class of all expected, user-facing errors."""

    #: process exit status the CLI uses for this error family (see EXIT_CODES)
    exit_code: int = EXIT_BAD_INPUT
    #: what an episode had read when the error ended it (its notes and the reading's
    #: fields: candidates, unexplained mentions), so a failed episode still shows why it
    #: read what it did; set by the pipeline, empty for errors raised before any reading
    read_so_far: dict[str, object] | None = None


def exit_code_of(error_name: str) -> int | None:
    """The exit code of the :class:`EmboTeamError` subclass called ``error_name`` (an
    episode records its error as ``"ClassName: message"``), or None if no loaded class
    has that name. Walks the subclasses, so every stage's own errors are covered."""
    pending: list[type[EmboTeamError]] = [EmboTeamError]
    while pending:
        cls = pending.pop()
        if cls.__name__ == error_name:
            return cls.exit_code
        pending.extend(cls.__subclasses__())
    return None


class OutputPathError(EmboTeamError):
    """An ``--out`` the command cannot write: an existing file where a folder is needed, a
    folder where a file is needed, a missing parent, a read-only or full file system."""


class UnknownSceneError(EmboTeamError):
    """A floor plan that is not among the 120 iTHOR scenes."""


class UnknownObjectError(EmboTeamError):
    """An object id or type that does not exist in the scene or the catalogue."""


class UnknownRobotError(EmboTeamError):
    """A robot profile number or name that does not exist."""


class GoalSyntaxError(EmboTeamError):
    """A goal condition that cannot be parsed or names an unknown predicate."""


class ServiceUnavailableError(EmboTeamError):
    """A service a command needs does not answer (a Ray cluster); the LLM layer has its
    own subclasses (emboteam.llm.errors) with the same exit code."""

    exit_code = EXIT_SERVICE
