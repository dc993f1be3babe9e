"""A small typed description of PDDL action schemas, and its evaluation on a WorldState.

The domain (:mod:`emboteam.pddl.domain`) is written once in this form and used twice: it
is rendered to PDDL text for Fast Downward, and it is grounded in Python to fill each plan
step's ``pre``/``post`` literals and to read which facts a step depends on. One source,
so the planner's domain and the executor's checks cannot drift apart.

The forms are deliberately restricted so that grounding yields plain literals:

- a precondition is a literal, or ``forall vars: guard -> literal`` (:class:`Implies`),
  where the guard holds only static facts and equalities;
- an effect is ``forall vars: when conjunction -> literals`` (:class:`Effect`); the
  conjunction may use fluents, statics and derived predicates, evaluated before the step.

Disjunctions and existentials live in the derived predicates (hand-written PDDL axioms
with a matching evaluator in :mod:`emboteam.pddl.vocabulary`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import cache

from emboteam.world.actions import Skill

#: a quantified or schema variable with its PDDL type (``robot`` or ``thing``)
Param = tuple[str, str]


@dataclass(frozen=True, slots=True)
class Atom:
    """A literal over variables (``?r``) and constants; ``=`` is equality."""

    pred: str
    args: tuple[str, ...]
    positive: bool = True

    def negate(self) -> Atom:
        return Atom(self.pred, self.args, not self.positive)

    def variables(self) -> frozenset[str]:
        return _variables(self.args)

    def bind(self, binding: Mapping[str, str]) -> Atom:
        get = binding.get
        return Atom(self.pred, tuple([get(a, a) for a in self.args]), self.positive)

    def pddl(self) -> str:
        atom = f"({' '.join((self.pred, *self.args))})"
        return atom if self.positive else f"(not {atom})"


@cache
def _variables(args: tuple[str, ...]) -> frozenset[str]:
    """The variables among an atom's arguments (memoised: grounding asks per evaluation)."""
    return frozenset(a for a in args if a.startswith("?"))


def A(text: str) -> Atom:
    """``A("at ?r ?o")``: a positive atom."""
    pred, *args = text.split()
    return Atom(pred, tuple(args))


def N(text: str) -> Atom:
    """``N("at ?r ?o")``: a negative literal."""
    return A(text).negate()


@dataclass(frozen=True, slots=True)
class Implies:
    """``forall vars: guard -> then``; with no vars, a plain implication."""

    vars: tuple[Param, ...]
    guard: tuple[Atom, ...]
    then: Atom

    def pddl(self) -> str:
        body = f"(imply {_conj(self.guard)} {self.then.pddl()})"
        return body if not self.vars else f"(forall ({_params(self.vars)}) {body})"


@dataclass(frozen=True, slots=True)
class Effect:
    """``forall vars: when -> then`` (either part may be empty)."""

    then: tuple[Atom, ...]
    when: tuple[Atom, ...] = ()
    vars: tuple[Param, ...] = ()

    def pddl(self) -> str:
        body = _conj(self.then)
        if self.when:
            body = f"(when {_conj(self.when)} {body})"
        return body if not self.vars else f"(forall ({_params(self.vars)}) {body})"


@dataclass(frozen=True, slots=True)
class Schema:
    """One PDDL action; ``target``/``receptacle`` name the parameters that become the
    simulator :class:`~emboteam.world.actions.Action`'s fields (others, such as the knife
    a slice needs, are implied by the state)."""

    name: str
    skill: Skill
    params: tuple[Param, ...]
    pre: tuple[Atom | Implies, ...]
    effects: tuple[Effect, ...]
    target: str
    receptacle: str | None = None

    def pddl(self) -> str:
        pre = "\n      ".join(p.pddl() for p in self.pre)
        eff = "\n      ".join(e.pddl() for e in self.effects) or ""
        return (f"  (:action {self.name}\n    :parameters ({_params(self.params)})\n"
                f"    :precondition (and\n      {pre})\n    :effect (and\n      {eff}))")


def _conj(atoms: Sequence[Atom]) -> str:
    if len(atoms) == 1:
        return atoms[0].pddl()
    return "(and " + " ".join(a.pddl() for a in atoms) + ")"


def _params(params: Sequence[Param]) -> str:
    return " ".join(f"{v} - {t}" for v, t in params)


# ---- evaluation -----------------------------------------------------------------------

#: truth of a ground atom (positive reading); equality is handled here
Truth = Callable[[str, tuple[str, ...]], bool]


def holds(atom: Atom, binding: Mapping[str, str], truth: Truth) -> bool:
    get = binding.get
    args = tuple([get(a, a) for a in atom.args])
    value = args[0] == args[1] if atom.pred == "=" else truth(atom.pred, args)
    return value if atom.positive else not value


#: told about every condition evaluated: (condition, binding, names of quantified variables)
Observer = Callable[[Atom, Mapping[str, str], frozenset[str]], None]


#: values a variable can take that may satisfy a condition (``within ?x Fridge_1``: what is
#: in the fridge), or None when the condition gives no such shortcut
Generator = Callable[[Atom, Mapping[str, str], str], Sequence[str] | None]


_Schedule = tuple[frozenset[str], list[Atom], list[list[Atom]]]
#: schedules by the identity of their (schema-constant) inputs; the inputs are kept in
#: the entry so an id is never reused while it is cached
_SCHEDULES: dict[tuple[int, int, tuple[str, ...]], tuple[object, object, _Schedule]] = {}


def _schedule(variables: Sequence[Param], conditions: Sequence[Atom], base: tuple[str, ...]) -> _Schedule:
    """Which conditions are tested before any variable is bound (``first``) and after each
    one (``ready[i]``): the same for every grounding of a schema, so computed once."""
    key = (id(variables), id(conditions), base)
    hit = _SCHEDULES.get(key)
    if hit is not None and hit[0] is variables and hit[1] is conditions:
        return hit[2]
    bound = set(base)
    ready: list[list[Atom]] = []
    first = [c for c in conditions if c.variables() <= bound]
    pending = [c for c in conditions if not c.variables() <= bound]
    for name, _type in variables:
        bound.add(name)
        now = [c for c in pending if c.variables() <= bound]
        pending = [c for c in pending if c not in now]
        ready.append(now)
    if pending:
        raise ValueError(f"conditions {pending} use unbound variables")
    out = (frozenset(name for name, _ in variables), first, ready)
    if len(_SCHEDULES) > 4096:
        _SCHEDULES.clear()
    _SCHEDULES[key] = (variables, conditions, out)
    return out


def bindings(variables: Sequence[Param], conditions: Sequence[Atom], base: Mapping[str, str],
             domain: Callable[[str], Sequence[str]], truth: Truth,
             observe: Observer | None = None, generate: Generator | None = None
             ) -> Iterator[dict[str, str]]:
    """Every extension of ``base`` to ``variables`` under which all ``conditions`` hold.

    Variables are bound in order and each condition is tested as soon as its variables
    are bound, so a static condition on the first variable (``(cools ?f)``) prunes the
    search before the next variable is enumerated. ``observe`` sees each evaluation (the
    short-circuit order makes the evaluated conditions exactly those the outcome depends
    on: what the merge reads as a step's dependencies). ``generate`` narrows a variable's
    values from a condition that enumerates them (the condition is still tested, and
    observed once with the variable unbound: its outcome depends on the whole set).
    """
    quantified, first, ready = _schedule(variables, conditions, tuple(base))

    def test(c: Atom, b: Mapping[str, str]) -> bool:
        if observe is not None:
            observe(c, b, quantified)
        return holds(c, b, truth)

    if not all(test(c, base) for c in first):
        return
    yield from _extend(_Search(variables, ready, domain, test, observe, generate, quantified), 0, dict(base))


@dataclass(frozen=True, slots=True)
class _Search:
    """What :func:`_extend` needs from :func:`bindings`: passed along, not closed over, so
    the recursion makes no reference cycle (a self-recursive closure does, and the
    thousands a plan's grounding made left their states for the cycle collector)."""

    variables: Sequence[Param]
    ready: list[list[Atom]]
    domain: Callable[[str], Sequence[str]]
    test: Callable[[Atom, Mapping[str, str]], bool]
    observe: Observer | None
    generate: Generator | None
    quantified: frozenset[str]


def _extend(search: _Search, i: int, current: dict[str, str]) -> Iterator[dict[str, str]]:
    """Bind variable ``i`` and the ones after it, in order, testing each condition as soon
    as its variables are bound (:func:`bindings`)."""
    if i == len(search.variables):
        yield dict(current)
        return
    name, type_ = search.variables[i]
    ready, test = search.ready[i], search.test
    values: Sequence[str] | None = None
    if search.generate is not None:
        for c in ready:
            values = search.generate(c, current, name)
            if values is not None:
                if search.observe is not None:
                    search.observe(c, current, search.quantified)
                break
    for value in search.domain(type_) if values is None else values:
        current[name] = value
        if all(test(c, current) for c in ready):
            yield from _extend(search, i + 1, current)
    current.pop(name, None)
