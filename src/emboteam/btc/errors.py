"""Typed errors of the behavior-tree compiler and its exporters."""

from __future__ import annotations

from emboteam.errors import EmboTeamError


class PlanCompileError(EmboTeamError):
    """A merged plan that cannot become a behavior tree: unknown producer steps, cyclic
    dependencies, robots or predicates the world does not know."""


class ExportError(EmboTeamError):
    """A tree export that cannot be produced (e.g. no Graphviz ``dot`` binary for PNG/SVG)."""
