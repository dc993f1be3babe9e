"""The PDDL formulas we write ourselves (derived-predicate bodies, goal formulas), read back
as trees, so the SAS emitter (:mod:`emboteam.pddl.sas`) can ground them.

Only the forms :mod:`emboteam.pddl.domain` and :mod:`emboteam.pddl.goal_compiler` produce
are accepted: ``and``, ``or``, ``not``, ``exists`` and atoms (``=`` included). Anything else
is a :class:`~emboteam.pddl.errors.PlannerInputError`, never a silent misreading. Written
by hand because a PDDL library would parse whole domains and problems, and we only need
these expressions (a few dozen characters each).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

from emboteam.pddl.errors import PlannerInputError
from emboteam.pddl.schema import Atom, Param

SExpr = str | list["SExpr"]


def parse_sexpr(text: str) -> SExpr:
    """One s-expression; symbols are kept as written (PDDL is case-insensitive, our names
    are not, and we only read our own output)."""
    tokens = text.replace("(", " ( ").replace(")", " ) ").split()
    pos = 0

    def read() -> SExpr:
        nonlocal pos
        if pos >= len(tokens):
            raise PlannerInputError(f"unbalanced PDDL formula: {text!r}")
        tok = tokens[pos]
        pos += 1
        if tok == ")":
            raise PlannerInputError(f"unexpected ')' in PDDL formula: {text!r}")
        if tok != "(":
            return tok
        out: list[SExpr] = []
        while pos < len(tokens) and tokens[pos] != ")":
            out.append(read())
        if pos >= len(tokens):
            raise PlannerInputError(f"unbalanced PDDL formula: {text!r}")
        pos += 1
        return out

    expr = read()
    if pos != len(tokens):
        raise PlannerInputError(f"trailing text after PDDL formula: {text!r}")
    return expr


@dataclass(frozen=True, slots=True)
class And:
    parts: tuple[Formula, ...]


@dataclass(frozen=True, slots=True)
class Or:
    parts: tuple[Formula, ...]


@dataclass(frozen=True, slots=True)
class Exists:
    vars: tuple[Param, ...]
    body: Formula


#: a formula in negation normal form: negation only on atoms (``Atom.positive``)
Formula = Atom | And | Or | Exists


def _params(expr: SExpr) -> tuple[Param, ...]:
    if not isinstance(expr, list):
        raise PlannerInputError(f"expected a parameter list, got {expr!r}")
    out: list[Param] = []
    names: list[str] = []
    i = 0
    while i < len(expr):
        tok = expr[i]
        if not isinstance(tok, str):
            raise PlannerInputError(f"bad parameter list {expr!r}")
        if tok == "-":
            if i + 1 >= len(expr) or not isinstance(expr[i + 1], str):
                raise PlannerInputError(f"bad parameter list {expr!r}")
            type_ = expr[i + 1]
            assert isinstance(type_, str)
            out += [(n, type_) for n in names]
            names = []
            i += 2
            continue
        names.append(tok)
        i += 1
    if names:
        raise PlannerInputError(f"untyped parameters {names} in {expr!r}")
    return tuple(out)


def to_formula(expr: SExpr, positive: bool = True) -> Formula:
    """An s-expression as a formula in negation normal form."""
    if isinstance(expr, str) or not expr:
        raise PlannerInputError(f"expected a PDDL formula, got {expr!r}")
    head = expr[0]
    if head == "not":
        if len(expr) != 2:
            raise PlannerInputError(f"'not' takes one formula: {expr!r}")
        return to_formula(expr[1], not positive)
    if head in ("and", "or"):
        parts = tuple(to_formula(e, positive) for e in expr[1:])
        conj = (head == "and") == positive
        return And(parts) if conj else Or(parts)
    if head == "exists":
        if not positive:
            raise PlannerInputError(f"negated 'exists' is not supported here: {expr!r}")
        if len(expr) != 3:
            raise PlannerInputError(f"'exists' takes parameters and a body: {expr!r}")
        return Exists(_params(expr[1]), to_formula(expr[2]))
    if not all(isinstance(a, str) for a in expr):
        raise PlannerInputError(f"unsupported PDDL formula {expr!r}")
    words = [a for a in expr if isinstance(a, str)]
    return Atom(words[0], tuple(words[1:]), positive)


def parse_formula(text: str) -> Formula:
    return to_formula(parse_sexpr(text))


def dnf(f: Formula) -> list[tuple[tuple[Param, ...], tuple[Atom, ...]]]:
    """Disjuncts ``(existential vars, conjunction)``: used for axiom bodies, which are
    small (the translator does the same for rule bodies)."""
    if isinstance(f, Atom):
        return [((), (f,))]
    if isinstance(f, Exists):
        return [(f.vars + v, c) for v, c in dnf(f.body)]
    if isinstance(f, Or):
        return [d for p in f.parts for d in dnf(p)]
    out: list[tuple[tuple[Param, ...], tuple[Atom, ...]]] = [((), ())]
    for p in f.parts:
        out = [(v1 + v2, c1 + c2) for v1, c1 in out for v2, c2 in dnf(p)]
    return out


@dataclass(frozen=True)
class DerivedRule:
    """``head(params) <- exists vars: body`` (one disjunct of a derived predicate)."""

    pred: str
    params: tuple[Param, ...]
    vars: tuple[Param, ...]
    body: tuple[Atom, ...]


@cache
def derived_rules(definitions: tuple[str, ...]) -> tuple[DerivedRule, ...]:
    """``(:derived (p ?x - t ...) body)`` texts as rules, one per disjunct of the body."""
    out: list[DerivedRule] = []
    for text in definitions:
        expr = parse_sexpr(text)
        if not (isinstance(expr, list) and len(expr) == 3 and expr[0] == ":derived"
                and isinstance(expr[1], list) and expr[1] and isinstance(expr[1][0], str)):
            raise PlannerInputError(f"not a derived predicate: {text!r}")
        pred = expr[1][0]
        params = _params(expr[1][1:])
        for vars_, body in dnf(to_formula(expr[2])):
            out.append(DerivedRule(pred, params, vars_, body))
    return tuple(out)
