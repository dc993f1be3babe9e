"""Grounding our own PDDL problems: relaxed reachability, then ground operators, axioms and
a goal over the reachable facts, ready to be written as a finite-domain (SAS) task
(:mod:`emboteam.pddl.sas`).

Why by hand: Fast Downward's translator does exactly this for any PDDL, but it is a
second Python process per call (most of a call's 0.1-0.2 s); our problems are small and
come from one fixed set of schemas (:data:`emboteam.pddl.domain.SCHEMAS`), so grounding
them here costs a few milliseconds and the search binary can read the result directly.

The semantics follow the translator's (Helmert 2009, "Concise finite-domain
representations for PDDL planning tasks"):

1. **Reachability** is a Datalog fixpoint over the relaxed task: an action instance is
   reachable when its positive preconditions are, its positive effects (with reachable
   positive effect conditions) then are; derived predicates are rules. Negative
   conditions are ignored there (an over-approximation, as in the translator), except on
   static predicates and equality, which are exact.
2. **Operators** are the reachable instances with every precondition: a negative
   condition on a fact that can never be true is dropped; universal preconditions
   (``forall vars: static guard -> literal``) are expanded; conditional effects become
   SAS conditional effects, their quantified variables ranging over the reachable facts
   that satisfy their positive conditions. When one instance both adds and deletes a
   fact, the add wins (PDDL semantics in Fast Downward): the delete's condition is
   strengthened by the negation of the add's.
3. **Constants**: a fluent no operator changes keeps its initial value; conditions on it
   are decided here (a precondition that fails drops the operator).
4. **Axioms** are the derived predicates' rules over the reachable facts; the goal is
   compiled like the translator does a non-conjunctive goal: every disjunction becomes a
   fresh derived atom with one rule per disjunct, so the goal itself is a conjunction.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache

from emboteam.pddl.errors import PlannerInputError
from emboteam.pddl.formula import And, DerivedRule, Exists, Formula, Or, derived_rules, parse_formula
from emboteam.pddl.schema import Atom, Implies, Param, Schema

#: a ground atom: (predicate, *arguments)
Fact = tuple[str, ...]
#: a ground literal: the fact and whether it must hold
Lit = tuple[Fact, bool]


@dataclass(frozen=True, slots=True)
class GroundEffect:
    conditions: tuple[Lit, ...]
    fact: Fact
    value: bool


@dataclass(frozen=True, slots=True)
class GroundOperator:
    #: ``put robot1 apple_1 fridge_1``: the plan line Fast Downward writes, in parentheses
    name: str
    pre: tuple[Lit, ...]
    effects: tuple[GroundEffect, ...]


@dataclass(frozen=True, slots=True)
class GroundAxiom:
    head: Fact
    body: tuple[Lit, ...]


@dataclass
class GroundTask:
    """A grounded problem. ``verdict`` is ``"trivial"`` when the goal holds by construction
    (nothing to plan), ``"unreachable"`` when relaxed reachability proves it unsolvable
    (as the translator's exit 10 does), else ``"search"``."""

    verdict: str
    fluents: list[Fact] = field(default_factory=list)
    derived: dict[Fact, int] = field(default_factory=dict)
    init: frozenset[Fact] = frozenset()
    goal: tuple[Lit, ...] = ()
    operators: list[GroundOperator] = field(default_factory=list)
    axioms: list[GroundAxiom] = field(default_factory=list)


# ---- facts and joins -------------------------------------------------------------------

class _Facts:
    """Facts by predicate, with per-(predicate, bound positions) indexes rebuilt lazily."""

    def __init__(self) -> None:
        self.by_pred: dict[str, set[tuple[str, ...]]] = {}
        self.version: dict[str, int] = {}
        self._index: dict[tuple[str, tuple[int, ...]], tuple[int, dict[tuple[str, ...], list[tuple[str, ...]]]]] = {}

    def add(self, fact: Fact) -> bool:
        rel = self.by_pred.setdefault(fact[0], set())
        args = fact[1:]
        if args in rel:
            return False
        rel.add(args)
        self.version[fact[0]] = self.version.get(fact[0], 0) + 1
        return True

    def __contains__(self, fact: Fact) -> bool:
        rel = self.by_pred.get(fact[0])
        return rel is not None and fact[1:] in rel

    def index(self, pred: str, positions: tuple[int, ...]) -> dict[tuple[str, ...], list[tuple[str, ...]]]:
        """The facts of ``pred`` by their arguments at ``positions`` (a non-empty tuple),
        in the relation's order; built again only when the relation has grown."""
        rel = self.by_pred.get(pred, set())
        version = self.version.get(pred, 0)
        hit = self._index.get((pred, positions))
        if hit is None or hit[0] != version:
            table: dict[tuple[str, ...], list[tuple[str, ...]]] = {}
            for args in rel:
                if len(args) > positions[-1]:
                    table.setdefault(tuple(args[p] for p in positions), []).append(args)
            hit = (version, table)
            self._index[(pred, positions)] = hit
        return hit[1]


@dataclass(frozen=True, slots=True)
class _Match:
    """Join step: look the atom up among the facts, binding its unknown arguments.

    ``spec`` gives each argument's kind (``const``, ``bound``, ``new``, ``repeat``: a new
    variable seen earlier in the atom); the rest is ``spec`` worked out once for
    :meth:`_Query.run`: the index key (constant or variable per position), the positions
    whose values bind new variables, the repeats with the position of their first
    occurrence, and the type checks by position."""

    pred: str
    positions: tuple[int, ...]
    spec: tuple[tuple[str, str], ...]
    checks: tuple[tuple[str, str], ...]
    key: tuple[tuple[bool, str], ...] = ()
    news: tuple[tuple[int, str], ...] = ()
    repeats: tuple[tuple[int, int], ...] = ()
    typed: tuple[tuple[int, str], ...] = ()

    @classmethod
    def of(cls, pred: str, positions: tuple[int, ...], spec: tuple[tuple[str, str], ...],
           checks: tuple[tuple[str, str], ...]) -> _Match:
        first: dict[str, int] = {}
        for i, (kind, val) in enumerate(spec):
            if kind == "new":
                first[val] = i
        return cls(pred, positions, spec, checks,
                   key=tuple((spec[p][0] == "const", spec[p][1]) for p in positions),
                   news=tuple((i, val) for i, (kind, val) in enumerate(spec) if kind == "new"),
                   repeats=tuple((i, first[val]) for i, (kind, val) in enumerate(spec) if kind == "repeat"),
                   typed=tuple((first[v], t) for v, t in checks))


@dataclass(frozen=True, slots=True)
class _Enum:
    """A variable no positive atom binds: every object of its type."""

    name: str
    type_: str


class _Query:
    """The bindings of ``free`` variables (given values for ``bound`` ones) under which the
    positive ``atoms`` are facts and the ``filters`` (equalities, negative static atoms)
    hold. The evaluation order is fixed once: most-bound atom first, statics on ties."""

    def __init__(self, atoms: Sequence[Atom], filters: Sequence[Atom], free: Sequence[Param],
                 bound: frozenset[str], statics: frozenset[str]) -> None:
        known = set(bound)
        todo = list(atoms)
        pending = list(filters)
        #: an Atom is a filter (tested once its variables are bound)
        self.steps: list[Atom | _Match | _Enum] = []
        self.free = tuple(free)
        #: the predicates whose facts the bindings depend on (a run gives the same rows
        #: while none of them gets a new fact)
        self.preds = tuple(sorted({a.pred for a in (*atoms, *filters) if a.pred != "="}))
        types = dict(free)

        def place_filters() -> None:
            nonlocal pending
            ready = [f for f in pending if f.variables() <= known]
            pending = [f for f in pending if f not in ready]
            self.steps.extend(ready)

        place_filters()
        while todo:
            best = max(todo, key=lambda a: (len(a.variables() & known) - len(a.variables() - known),
                                            a.pred in statics))
            todo.remove(best)
            spec: list[tuple[str, str]] = []
            fresh: list[str] = []
            for arg in best.args:
                if not arg.startswith("?"):
                    spec.append(("const", arg))
                elif arg in known:
                    spec.append(("bound", arg))
                elif arg in fresh:
                    spec.append(("repeat", arg))
                else:
                    spec.append(("new", arg))
                    fresh.append(arg)
            positions = tuple(i for i, (k, _) in enumerate(spec) if k in ("const", "bound"))
            if not fresh:  # every argument known: a membership test, no index needed
                self.steps.append(best)
                place_filters()
                continue
            checks = tuple((v, types[v]) for v in fresh if v in types)
            self.steps.append(_Match.of(best.pred, positions, tuple(spec), checks))
            known.update(fresh)
            place_filters()
        for name, type_ in free:
            if name not in known:
                self.steps.append(_Enum(name, type_))
                known.add(name)
                place_filters()
        if pending:
            raise PlannerInputError(f"conditions {pending} use unbound variables")

    def run(self, base: Mapping[str, str], facts: _Facts, domain: Callable[[str], Sequence[str]],
            kinds: Mapping[str, frozenset[str]]) -> list[dict[str, str]]:
        """Every binding, extended step by step (breadth first: plain lists are much
        cheaper than a recursion of generators in CPython). The facts do not change during
        a run, so each step looks its relation (or index) up once for all rows."""
        rows: list[dict[str, str]] = [dict(base)]
        for step in self.steps:
            if not rows:
                break
            if isinstance(step, Atom):
                rows = _filtered(step, rows, facts)
            elif isinstance(step, _Enum):
                name, values = step.name, domain(step.type_)
                rows = [{**b, name: v} for b in rows for v in values]
            else:
                rows = _matched(step, rows, facts, kinds)
        return rows


def _filtered(step: Atom, rows: list[dict[str, str]], facts: _Facts) -> list[dict[str, str]]:
    """The rows under which ``step`` (every variable bound) holds: equality, or the atom
    among the facts (or not, for a negative one)."""
    pred, atom_args, positive = step.pred, step.args, step.positive
    if pred == "=":
        x, y = atom_args
        return [b for b in rows if (b.get(x, x) == b.get(y, y)) == positive]
    rel = facts.by_pred.get(pred)
    if rel is None:
        return [] if positive else rows
    return [b for b in rows if (tuple([b.get(a, a) for a in atom_args]) in rel) == positive]


def _matched(step: _Match, rows: list[dict[str, str]], facts: _Facts,
             kinds: Mapping[str, frozenset[str]]) -> list[dict[str, str]]:
    """Each row extended by every fact of ``step``'s atom that agrees with it, in the
    order of the facts (a fact of another arity, a repeat that differs or a value not of
    its variable's type is skipped)."""
    rel = facts.by_pred.get(step.pred)
    if not rel:
        return []
    width, key, news, repeats = len(step.spec), step.key, step.news, step.repeats
    typed = [(i, kinds[t]) for i, t in step.typed]
    table = facts.index(step.pred, step.positions) if step.positions else None
    every = list(rel) if table is None else []
    out: list[dict[str, str]] = []
    for b in rows:
        found = every if table is None else table.get(tuple([val if const else b[val] for const, val in key]), ())
        for args in found:
            if len(args) != width:
                continue
            if repeats and any(args[i] != args[j] for i, j in repeats):
                continue
            if typed and not all(args[i] in kind for i, kind in typed):
                continue
            nb = dict(b)
            for i, name in news:
                nb[name] = args[i]
            out.append(nb)
    return out


# ---- the compiled domain -------------------------------------------------------------------

@dataclass(frozen=True)
class _EffectPlan:
    effect_vars: tuple[Param, ...]
    query: _Query
    #: negative conditions on fluents/derived predicates (conditions, not filters)
    negative: tuple[Atom, ...]
    #: positive conditions on fluents/derived predicates (kept as SAS conditions)
    positive: tuple[Atom, ...]
    then: tuple[Atom, ...]
    #: fluent/derived predicates the effect's bindings depend on (reachability reruns it
    #: for an action only when one of them got new facts)
    deps: tuple[str, ...] = ()


@dataclass(frozen=True)
class _SchemaPlan:
    schema: Schema
    query: _Query
    deps: frozenset[str]
    pre_fluent: tuple[Atom, ...]
    implies: tuple[tuple[Implies, _Query], ...]
    effects: tuple[_EffectPlan, ...]


@dataclass(frozen=True)
class _RulePlan:
    rule: DerivedRule
    query: _Query
    deps: frozenset[str]
    negative: tuple[Atom, ...]
    positive: tuple[Atom, ...]


@dataclass(frozen=True)
class CompiledDomain:
    schemas: tuple[_SchemaPlan, ...]
    rules: tuple[_RulePlan, ...]
    fluents: frozenset[str]
    derived: frozenset[str]
    #: layer of each derived predicate (stratified: a negative dependency is one layer up)
    layers: dict[str, int]

    def is_static(self, pred: str) -> bool:
        return pred not in self.fluents and pred not in self.derived


def _split(atoms: Sequence[Atom], statics: Callable[[str], bool]) -> tuple[list[Atom], list[Atom], list[Atom]]:
    """(join atoms: positive non-equality; filters: equality and negative statics;
    negative fluent/derived conditions)."""
    join: list[Atom] = []
    filters: list[Atom] = []
    negative: list[Atom] = []
    for a in atoms:
        if a.pred == "=":
            filters.append(a)
        elif a.positive:
            join.append(a)
        elif statics(a.pred):
            filters.append(a)
        else:
            negative.append(a)
    return join, filters, negative


def _layers(rules: Sequence[DerivedRule], derived: frozenset[str]) -> dict[str, int]:
    layer = dict.fromkeys(derived, 0)
    for _ in range(len(derived) + 2):
        changed = False
        for r in rules:
            for a in r.body:
                if a.pred in derived:
                    need = layer[a.pred] + (0 if a.positive else 1)
                    if layer[r.pred] < need:
                        layer[r.pred] = need
                        changed = True
        if not changed:
            return layer
    raise PlannerInputError("derived predicates depend negatively on themselves (not stratifiable)")


@cache
def compile_domain(schemas: tuple[Schema, ...], derived_texts: tuple[str, ...]) -> CompiledDomain:
    """The query plans of a domain, built once per process."""
    rules = derived_rules(derived_texts)
    derived = frozenset(r.pred for r in rules)
    fluents = frozenset(a.pred for s in schemas for e in s.effects for a in e.then)
    if fluents & derived:
        raise PlannerInputError(f"actions change derived predicates {sorted(fluents & derived)}")

    def static(p: str) -> bool:
        return p not in fluents and p not in derived

    mentioned = {a.pred for s in schemas for a in s.pre if isinstance(a, Atom)}
    mentioned |= {a.pred for s in schemas for e in s.effects for a in e.when}
    mentioned |= {a.pred for r in rules for a in r.body}
    statics = frozenset(p for p in mentioned if static(p))
    plans: list[_SchemaPlan] = []
    for s in schemas:
        atoms = [a for a in s.pre if isinstance(a, Atom)]
        join, filters, negative = _split(atoms, static)
        query = _Query(join, filters, s.params, frozenset(), statics)
        bound = frozenset(v for v, _ in s.params)
        implies = []
        for imp in s.pre:
            if isinstance(imp, Implies):
                if any(not static(g.pred) and g.pred != "=" for g in imp.guard):
                    raise PlannerInputError(f"{s.name}: a universal precondition's guard must be static")
                gj, gf, _ = _split(imp.guard, static)
                implies.append((imp, _Query(gj, gf, imp.vars, bound, statics)))
        effects = []
        deps = {a.pred for a in join}
        for e in s.effects:
            ej, ef, en = _split(e.when, static)
            effects.append(_EffectPlan(e.vars, _Query(ej, ef, e.vars, bound, statics), tuple(en),
                                       tuple(a for a in ej if not static(a.pred)), e.then,
                                       tuple(sorted({a.pred for a in ej if not static(a.pred)}))))
            deps.update(a.pred for a in ej)
        plans.append(_SchemaPlan(s, query, frozenset(deps), tuple(a for a in negative), tuple(implies),
                                 tuple(effects)))
    rule_plans = []
    for r in rules:
        join, filters, negative = _split(r.body, static)
        rule_plans.append(_RulePlan(r, _Query(join, filters, r.params + r.vars, frozenset(), statics),
                                    frozenset(a.pred for a in join), tuple(negative),
                                    tuple(a for a in join if not static(a.pred))))
    return CompiledDomain(tuple(plans), tuple(rule_plans), fluents, derived, _layers(rules, derived))


# ---- grounding -------------------------------------------------------------------------------

def _fact(atom: Atom, b: Mapping[str, str]) -> Fact:
    return (atom.pred, *[b.get(a, a) for a in atom.args])


class _Grounder:
    def __init__(self, domain: CompiledDomain, robots: Sequence[str], things: Sequence[str],
                 init: Sequence[Fact]) -> None:
        self.d = domain
        self.kinds = {"robot": frozenset(robots), "thing": frozenset(things)}
        self.lists = {"robot": tuple(robots), "thing": tuple(things)}
        self.init = frozenset(init)
        self.facts = _Facts()
        self._effect_seen: dict[tuple[int, int, tuple[str, ...]], tuple[int, ...]] = {}
        #: the bindings found at that stamp (reused for the operators when still current)
        self._effect_rows: dict[tuple[int, int, tuple[str, ...]], list[dict[str, str]]] = {}
        #: a query without given values -> the versions of its predicates and its rows then
        #: (the operators and axioms ask again what the fixpoint's last round found)
        self._rows: dict[int, tuple[tuple[int, ...], list[dict[str, str]]]] = {}
        for f in init:
            self.facts.add(f)

    def domain(self, type_: str) -> Sequence[str]:
        return self.lists.get(type_, ())

    def actions(self, plan: _SchemaPlan) -> list[dict[str, str]]:
        return self._every(plan.query)

    def _every(self, query: _Query) -> list[dict[str, str]]:
        """``query``'s bindings from no given values; the rows of its last run while its
        predicates have no new facts (callers read the rows, never change them)."""
        version = self.facts.version
        stamp = tuple([version.get(p, 0) for p in query.preds])
        kept = self._rows.get(id(query))
        if kept is not None and kept[0] == stamp:
            return kept[1]
        rows = query.run({}, self.facts, self.domain, self.kinds)
        self._rows[id(query)] = (stamp, rows)
        return rows

    def reach(self) -> None:
        """The relaxed fixpoint; a schema or rule is evaluated again only when a predicate
        it joins over got new facts."""
        seen: dict[int, tuple[int, ...]] = {}
        items: list[tuple[int, frozenset[str], Callable[[], list[Fact]]]] = []
        for i, sp in enumerate(self.d.schemas):
            items.append((i, sp.deps, lambda i=i, sp=sp: self._schema_heads(i, sp)))  # type: ignore[misc]
        for j, rp in enumerate(self.d.rules):
            items.append((1000 + j, rp.deps, lambda rp=rp: self._rule_heads(rp)))  # type: ignore[misc]
        changed = True
        while changed:
            changed = False
            for key, deps, heads in items:
                stamp = tuple(self.facts.version.get(p, 0) for p in sorted(deps))
                if seen.get(key) == stamp:
                    continue
                new = heads()
                seen[key] = stamp
                for f in new:
                    if self.facts.add(f):
                        changed = True

    def _schema_heads(self, index: int, sp: _SchemaPlan) -> list[Fact]:
        out: list[Fact] = []
        version = self.facts.version
        params = [v for v, _ in sp.schema.params]
        adding = [(j, ep, positives) for j, ep in enumerate(sp.effects)
                  if (positives := [a for a in ep.then if a.positive])]
        for b in self.actions(sp):
            key = tuple([b[v] for v in params])
            for j, ep, positives in adding:
                stamp = tuple(version.get(p, 0) for p in ep.deps)
                if self._effect_seen.get((index, j, key)) == stamp:
                    continue  # same action, nothing new its effect could bind to
                self._effect_seen[(index, j, key)] = stamp
                rows = self._effect_rows[(index, j, key)] = ep.query.run(b, self.facts, self.domain, self.kinds)
                for eb in rows:
                    out += [_fact(a, eb) for a in positives]
        return out

    def _rule_heads(self, rp: _RulePlan) -> list[Fact]:
        head = rp.rule
        return [(head.pred, *(b[v] for v, _ in head.params))
                for b in self._every(rp.query)]

    # ---- after the fixpoint ------------------------------------------------------------
    def lit(self, atom: Atom, b: Mapping[str, str]) -> Lit | bool:
        """A condition as a literal, or True/False when decided by reachability."""
        f = _fact(atom, b)
        if atom.pred == "=":
            return (f[1] == f[2]) == atom.positive
        if self.d.is_static(atom.pred):
            return (f in self.facts) == atom.positive
        if f not in self.facts:
            return not atom.positive
        return (f, atom.positive)

    def operators(self) -> list[GroundOperator]:
        out: list[GroundOperator] = []
        for index, sp in enumerate(self.d.schemas):
            for b in self.actions(sp):
                op = self._operator(index, sp, b)
                if op is not None:
                    out.append(op)
        return out

    def _effect_bindings(self, index: int, j: int, ep: _EffectPlan, b: dict[str, str],
                         key: tuple[str, ...]) -> list[dict[str, str]]:
        stamp = tuple(self.facts.version.get(p, 0) for p in ep.deps)
        if self._effect_seen.get((index, j, key)) == stamp:
            return self._effect_rows[(index, j, key)]
        return ep.query.run(b, self.facts, self.domain, self.kinds)

    def _operator(self, index: int, sp: _SchemaPlan, b: dict[str, str]) -> GroundOperator | None:
        pre: dict[Fact, bool] = {}
        for a in sp.schema.pre:
            if not isinstance(a, Atom) or a.pred == "=" or self.d.is_static(a.pred):
                continue  # statics and equalities are decided by the query; implications below
            lit = self.lit(a, b)
            if lit is False:
                return None
            if lit is not True:
                if pre.get(lit[0], lit[1]) != lit[1]:
                    return None
                pre[lit[0]] = lit[1]
        for imp, q in sp.implies:
            for gb in q.run(b, self.facts, self.domain, self.kinds):
                lit = self.lit(imp.then, gb)
                if lit is False:
                    return None
                if lit is not True:
                    if pre.get(lit[0], lit[1]) != lit[1]:
                        return None
                    pre[lit[0]] = lit[1]
        effects: list[GroundEffect] = []
        key = tuple(b[v] for v, _ in sp.schema.params)
        for j, ep in enumerate(sp.effects):
            for eb in self._effect_bindings(index, j, ep, b, key):
                conds: dict[Fact, bool] = {}
                ok = True
                for a in (*ep.positive, *ep.negative):
                    lit = self.lit(a, eb)
                    if lit is False:
                        ok = False
                        break
                    if lit is True:
                        continue
                    if pre.get(lit[0], lit[1]) != lit[1] or conds.get(lit[0], lit[1]) != lit[1]:
                        ok = False  # contradicts the precondition or itself: never fires
                        break
                    if lit[0] not in pre:
                        conds[lit[0]] = lit[1]
                if not ok:
                    continue
                cond = tuple(sorted(conds.items()))
                for a in ep.then:
                    f = _fact(a, eb)
                    if not a.positive and f not in self.facts:
                        continue  # deleting what can never hold
                    effects.append(GroundEffect(cond, f, a.positive))
        name = " ".join([sp.schema.name, *(b[v] for v, _ in sp.schema.params)]).lower()
        return GroundOperator(name, tuple(sorted(pre.items())), tuple(_add_wins(effects)))

    def axioms(self) -> list[GroundAxiom]:
        out: list[GroundAxiom] = []
        for rp in self.d.rules:
            head = rp.rule
            for b in self._every(rp.query):
                body: dict[Fact, bool] = {}
                ok = True
                for a in (*rp.positive, *rp.negative):
                    lit = self.lit(a, b)
                    if lit is False:
                        ok = False
                        break
                    if lit is not True:
                        if body.get(lit[0], lit[1]) != lit[1]:
                            ok = False
                            break
                        body[lit[0]] = lit[1]
                if ok:
                    out.append(GroundAxiom((head.pred, *(b[v] for v, _ in head.params)), tuple(sorted(body.items()))))
        return out


def _add_wins(effects: Sequence[GroundEffect]) -> list[GroundEffect]:
    """Make an instance's adds and deletes of one fact exclusive, the add winning: each
    delete also requires that no add of the same fact fires."""
    adds: dict[Fact, list[tuple[Lit, ...]]] = {}
    for e in effects:
        if e.value:
            adds.setdefault(e.fact, []).append(e.conditions)
    out: dict[GroundEffect, None] = {}
    for e in effects:
        if e.value or e.fact not in adds:
            out.setdefault(e, None)
            continue
        if any(not c for c in adds[e.fact]):
            continue  # an unconditional add: the delete never has an effect
        splits: list[dict[Fact, bool]] = [dict(e.conditions)]
        for add in adds[e.fact]:
            grown: list[dict[Fact, bool]] = []
            for s in splits:
                if any(s.get(f) is (not v) for f, v in add):
                    grown.append(s)  # this add cannot fire here
                    continue
                for f, v in add:
                    if f not in s:
                        grown.append({**s, f: not v})
            splits = grown
            if len(splits) > 64:
                raise PlannerInputError(f"too many conflicting effects on {e.fact}")
        for s in splits:
            out.setdefault(GroundEffect(tuple(sorted(s.items())), e.fact, False), None)
    return list(out)


# ---- constants -------------------------------------------------------------------------------

def _fold_constants(ops: list[GroundOperator], axioms: list[GroundAxiom], init: frozenset[Fact],
                    derived: frozenset[str]) -> tuple[list[GroundOperator], list[GroundAxiom], set[Fact]]:
    """Decide conditions on fluents no operator changes (their initial value is final)."""
    changed = {e.fact for op in ops for e in op.effects}

    def fold(lits: Sequence[Lit]) -> tuple[Lit, ...] | None:
        out: list[Lit] = []
        for f, v in lits:
            if f[0] in derived or f in changed:
                out.append((f, v))
            elif (f in init) != v:
                return None
        return tuple(out)

    new_ops: list[GroundOperator] = []
    for op in ops:
        pre = fold(op.pre)
        if pre is None:
            continue
        effects = []
        for e in op.effects:
            c = fold(e.conditions)
            if c is not None:
                effects.append(GroundEffect(c, e.fact, e.value))
        if effects:
            new_ops.append(GroundOperator(op.name, pre, tuple(effects)))
    new_axioms = []
    for ax in axioms:
        body = fold(ax.body)
        if body is not None:
            new_axioms.append(GroundAxiom(ax.head, body))
    return new_ops, new_axioms, changed


# ---- the goal -------------------------------------------------------------------------------

class _GoalCompiler:
    """Goal formulas -> a conjunction of literals plus derived atoms for disjunctions."""

    def __init__(self, g: _Grounder, changed: set[Fact]) -> None:
        self.g = g
        self.changed = changed
        self.axioms: list[GroundAxiom] = []
        self.aux: dict[Fact, int] = {}

    def literal(self, atom: Atom) -> Lit | bool:
        if atom.variables():
            raise PlannerInputError(f"goal atom {atom.pddl()} is not ground")
        lit = self.g.lit(atom, {})
        if lit is True or lit is False:
            return lit
        f, v = lit
        if f[0] not in self.g.d.derived and f not in self.changed:
            return (f in self.g.init) == v
        return lit

    def conjunction(self, f: Formula) -> list[Lit] | bool:
        """Literals whose conjunction is ``f`` (True: always; False: never)."""
        if isinstance(f, Atom):
            lit = self.literal(f)
            return lit if isinstance(lit, bool) else [lit]
        if isinstance(f, Exists):
            raise PlannerInputError("existential goals are not supported by the SAS emitter")
        if isinstance(f, And):
            out: list[Lit] = []
            for p in f.parts:
                sub = self.conjunction(p)
                if sub is False:
                    return False
                if sub is not True:
                    out += sub
            return out or True
        assert isinstance(f, Or)
        disjuncts: list[list[Lit]] = []
        for p in f.parts:
            sub = self.conjunction(p)
            if sub is True:
                return True
            if sub is not False:
                disjuncts.append(sub)
        if not disjuncts:
            return False
        if len(disjuncts) == 1:
            return disjuncts[0]
        head: Fact = (f"goal-or-{len(self.aux) + 1}",)
        layer = 0
        for d in disjuncts:
            self.axioms.append(GroundAxiom(head, tuple(d)))
            for fact, v in d:
                if fact in self.aux or fact[0] in self.g.d.derived:
                    base = self.aux.get(fact, self.g.d.layers.get(fact[0], 0))
                    layer = max(layer, base + (0 if v else 1))
        self.aux[head] = layer
        return [(head, True)]


def ground_task(domain: CompiledDomain, robots: Sequence[str], things: Sequence[str], init: Sequence[Fact],
                goals: Sequence[str]) -> GroundTask:
    """Ground a problem of ``domain``: the objects by type, the initial facts (statics
    included) and the goal formulas (conjoined)."""
    g = _Grounder(domain, robots, things, init)
    g.reach()
    ops = g.operators()
    axioms = g.axioms()
    ops, axioms, changed = _fold_constants(ops, axioms, g.init, domain.derived)
    gc = _GoalCompiler(g, changed)
    goal = gc.conjunction(And(tuple(parse_formula(t) for t in goals)))
    if goal is True:
        return GroundTask("trivial")
    if goal is False:
        return GroundTask("unreachable")
    wanted: dict[Fact, bool] = {}
    for f, v in goal:  # the search wants each goal variable once
        if wanted.setdefault(f, v) != v:
            return GroundTask("unreachable")
    goal = list(wanted.items())
    axioms += gc.axioms
    used = {f for op in ops for f, _ in op.pre} | {f for op in ops for e in op.effects for f, _ in e.conditions}
    used |= {e.fact for op in ops for e in op.effects} | {f for f, _ in goal}
    used |= {f for ax in axioms for f, _ in ax.body}
    derived_facts = {ax.head for ax in axioms} | {f for f in used if f[0] in domain.derived}
    layers = {f: gc.aux[f] if f in gc.aux else domain.layers[f[0]] for f in derived_facts}
    fluents = sorted(f for f in used if f not in layers)
    return GroundTask("search", fluents=fluents, derived=dict(sorted(layers.items())), init=g.init,
                      goal=tuple(goal), operators=_canonical_operators(ops), axioms=_canonical_axioms(axioms))


def _canonical_operators(ops: Sequence[GroundOperator]) -> list[GroundOperator]:
    """Operators (and their effects) in a fixed order. The grounding joins over sets of
    strings, whose order changes with Python's hash seed; Fast Downward breaks ties by
    operator order, so without this the same problem got different plans in different
    processes (and the sweep's makespans moved with them)."""
    out = [GroundOperator(op.name, op.pre, tuple(sorted(op.effects, key=lambda e: (e.fact, e.value, e.conditions))))
           for op in ops]
    return sorted(out, key=lambda op: op.name)


def _canonical_axioms(axioms: Sequence[GroundAxiom]) -> list[GroundAxiom]:
    """Axioms in a fixed order (see :func:`_canonical_operators`)."""
    return sorted((GroundAxiom(ax.head, tuple(sorted(ax.body))) for ax in axioms), key=lambda ax: (ax.head, ax.body))
