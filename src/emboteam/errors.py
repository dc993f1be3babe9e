"""The root of EmboTeam's typed errors.

Every error a user can cause (bad input, an unusable configuration, an unsolvable goal)
derives from :class:`EmboTeamError`, so the CLI can print one line and exit non-zero
instead of a traceback. Each stage defines its own subclasses next to its code.
"""

from __future__ import annotations


class EmboTeamError(Exception):
    """Base class of all expected, user-facing errors."""

    #: process exit status the CLI uses for this error family
    exit_code: int = 2


class UnknownSceneError(EmboTeamError):
    """A floor plan that is not among the 120 iTHOR scenes."""


class UnknownObjectError(EmboTeamError):
    """An object id or type that does not exist in the scene or the catalogue."""


class UnknownRobotError(EmboTeamError):
    """A robot profile number or name that does not exist."""


class GoalSyntaxError(EmboTeamError):
    """A goal condition that cannot be parsed or names an unknown predicate."""
