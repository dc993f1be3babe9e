"""Ground PDDL literals: the unit of plan preconditions/effects and of BT condition nodes."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict


class Literal(BaseModel):
    """A ground PDDL literal, e.g. ``(holding robot1 Apple_1)`` or its negation."""

    model_config = ConfigDict(frozen=True)

    predicate: str
    args: tuple[str, ...] = ()
    positive: bool = True

    def __str__(self) -> str:
        atom = f"({' '.join((self.predicate, *self.args))})"
        return atom if self.positive else f"(not {atom})"
