"""Decompose, solve, eliminate, merge: the hybrid planner's main pass.

The subtasks are planned in dependency order, in *rounds*: the subtasks whose dependencies
are planned are grouped into clusters and allocated to robots (capability, then balanced
expected work: *decompose*), grouped into planning units, and the units are solved in
parallel by Fast Downward from the state the plans accepted so far leave (*solve*). Each
unit's plan loses the steps its goals do not need (*eliminate*, and the visits merged),
is replayed on the symbolic state and accepted, or goes back to the next round (its goal
protected, its allocation redone); a unit Fast Downward cannot solve is retried with every
candidate object and the whole team. The accepted sequence loses the steps the whole goal
does not need (:mod:`.trim`) and is *merged* into a validated partial order (:mod:`.merge`).
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence

from emboteam.hp.allocation import allocate
from emboteam.hp.contention import bottleneck_first, spot_seconds
from emboteam.hp.eliminate import eliminate
from emboteam.hp.interleave import interleave, worth_it
from emboteam.hp.merge import GroundedStep, SeqStep
from emboteam.hp.requirements import Need, covers, need_of
from emboteam.hp.rounds import Attempt, Unit, attribute, clusters, helpers, make_units, polish
from emboteam.hp.stages import trim
from emboteam.hp.stages.context import Context, Draft, Fallback, Invalid, Record
from emboteam.hp.stages.merge import merge_causal
from emboteam.hp.stages.replay import replay
from emboteam.hp.visits import merge_visits
from emboteam.pddl.errors import PlannerMemoryError, PlanningError
from emboteam.pddl.goal_compiler import shared_view
from emboteam.pddl.problem import Problem, build_problem
from emboteam.pddl.runner import SolveResult
from emboteam.pfg.taskspec import Subtask
from emboteam.world.actions import Action, Skill
from emboteam.world.checker import check_condition, condition_holds
from emboteam.world.goals import Condition
from emboteam.world.state import WorldState

Protected = dict[str, tuple[Condition, frozenset[str]]]


def plan_decomposed(ctx: Context, prefer: Mapping[str, str] | None = None,
                    notes: list[str] | None = None) -> Draft:
    """Plan in rounds, merge, validate (:class:`Fallback` when decomposition cannot work).
    ``prefer``: a robot per cluster id (from :func:`emboteam.hp.rebalance.rebalance`);
    ``notes``: where to say what happened (default: the context's)."""
    rounds = _Rounds(ctx, prefer, ctx.notes if notes is None else notes)
    rounds.run()
    return rounds.merged()


class _Rounds:
    """The state of one decomposed pass: what is accepted, protected, allocated, pending."""

    def __init__(self, ctx: Context, prefer: Mapping[str, str] | None, notes: list[str]) -> None:
        self.ctx, self.prefer, self.notes = ctx, prefer, notes
        self.forward = ctx.start.copy()
        self.universe = ctx.universe.at(self.forward)
        self.accepted: list[GroundedStep] = []
        self.done: set[str] = set()
        self.unit_of: dict[str, str] = {}
        self.protected: Protected = {}
        self.record = Record()
        self.attempts = {t.id: Attempt() for t in ctx.spec.subtasks}
        self.pending = list(ctx.spec.subtasks)
        self.counter = itertools.count(1)
        #: ``forward`` is still the start state (nothing accepted into it yet): the needs
        #: the planner worked out on the start (:attr:`Context.needs`) hold for it as they are
        self.at_start = True

    # ---- the rounds ---------------------------------------------------------------------
    def run(self) -> None:
        rounds = 0
        while self.pending:
            rounds += 1
            if rounds > 3 * len(self.ctx.spec.subtasks) + 3:
                raise Fallback("subtasks keep undoing each other")
            ready = [t for t in self.pending if all(d in self.done for d in t.depends_on)]
            self._allocate([t for t in ready if t.id not in self.record.assigned])
            units = make_units(ready, self.record.assigned, self.attempts, self.counter, self.record.cluster,
                               self.ctx.config.unit_conditions)
            base = self.forward.copy()
            self._round(base, self._problems(units, base))
            self.pending = [t for t in self.pending if t.id not in self.done]

    def _allocate(self, fresh: Sequence[Subtask]) -> None:
        """Decompose: cluster the subtasks not allocated yet and allocate the clusters."""
        if not fresh:
            return
        team, forward, record = self.ctx.team, self.forward, self.record
        load = {r: sum(g.seconds for g in self.accepted if g.robot == r) for r in team}
        groups = clusters(fresh, forward, team)
        needs = self._needs(groups)
        for a in allocate(groups, needs, forward, team, load, self.prefer):
            members = a.subtask.split("+")
            for m in members:
                record.assigned[m] = a.robots
                record.cluster[m] = a.subtask
            record.candidates[a.subtask] = () if a.note == "as specified" else tuple(
                r for r in team if all(covers([forward.robots[r].profile], n) for n in needs[a.subtask]))
            if a.note != "as specified":
                self.notes.append(f"{', '.join(members)}: {a.note} -> {', '.join(a.robots)}")

    def _needs(self, groups: Sequence[Subtask]) -> dict[str, list[Need]]:
        """The needs of each cluster's conditions on ``forward``: while nothing is accepted
        into it, those the planner worked out on the start state (the same function of the
        same state and team: the first round of every decomposed pass, re-allocation's
        included, computes none again); else with one view of ``forward`` for all."""
        known: dict[int, Need] = {}
        if self.at_start:
            for t in self.ctx.spec.subtasks:
                known.update((id(c), n) for c, n in zip(t.goal, self.ctx.needs.get(t.id, ()), strict=False))
        view = shared_view(self.forward)
        return {g.id: [known[id(c)] if id(c) in known else need_of(c, self.forward, self.ctx.team, view)
                       for c in g.goal] for g in groups}

    def _problems(self, units: Sequence[Unit], base: WorldState) -> list[tuple[Unit, Problem]]:
        """The round's problems; units already satisfied are accepted first, so their
        goals are protected in the problems of the others."""
        for u in [u for u in units if _nothing_to_do(u, base)]:
            self._accept(u, [])
        units = [u for u in units if u.subtasks[0].id not in self.done]
        self.pending = [t for t in self.pending if t.id not in self.done]
        todo: list[tuple[Unit, Problem]] = []
        for u in units:
            problem = build_problem(base, u.conditions, u.robots, name=u.id, narrow=u.narrow)
            overlap = [c for c, objs in self.protected.values() if objs & set(problem.objects)]
            extra = [c for c in overlap if str(c) not in {str(p) for p in u.protect}]
            if u.protect or extra:
                u.protect = [*u.protect, *extra]
                problem = build_problem(base, u.conditions, u.robots, name=u.id, narrow=u.narrow, protect=u.protect)
            todo.append((u, problem))
        return todo

    def _round(self, base: WorldState, todo: Sequence[tuple[Unit, Problem]]) -> None:
        """Solve the round's problems, accept the units one by one (users of the round's
        most contended spot first), interleave what was accepted."""
        round_start = len(self.accepted)
        round_plans: list[tuple[Unit, list[SeqStep]]] = []
        early = _Early(self, todo, base)
        results = self.ctx.solver.solve_all([p for _, p in todo], then=early)
        uses = [spot_seconds(base, p.decode(r.plan)) if isinstance(r, SolveResult) and r.solved else None
                for (_, p), r in zip(todo, results, strict=True)]
        for (u, problem), result in bottleneck_first(list(zip(todo, results, strict=True)), uses):
            if isinstance(result, PlannerMemoryError) and len(u.subtasks) > 1:
                for t in u.subtasks:  # too big to solve at once: one subtask at a time
                    self.attempts[t.id].solo = True
                self.notes.append(f"{u.describe()}: {result}; planned one subtask at a time")
                continue
            if isinstance(result, PlanningError):
                raise result
            if not result.solved:
                self._retry_unsolvable(u)
                continue
            options = early.options.get(id(u))
            if options is None:
                options = self._options(u, polish(problem.decode(result.plan)), base)
            steps = self._take(u, options, base)
            if steps is not None:
                round_plans.append((u, steps))
        if len(round_plans) > 1:
            self._interleave(base, round_plans, round_start)

    # ---- one unit -----------------------------------------------------------------------
    def _options(self, u: Unit, actions: list[tuple[str, Action]], base: WorldState) -> list[list[tuple[str, Action]]]:
        """Eliminate: the unit's plan without the steps its goals do not need, and with its
        visits merged, tried before the planner's own."""
        options = [actions]
        if self.ctx.config.eliminate == "off" or not all(t.final for t in u.subtasks):
            # with an intermediate goal nothing would keep the steps that reach it: it need
            # not hold at the end
            return options
        # u.protect holds every accepted goal on the problem's objects; goals on others are
        # checked when the unit is replayed
        shorter = eliminate(base, actions, [*u.conditions, *u.protect])
        if len(shorter) < len(actions):
            options.insert(0, shorter)
        if self.ctx.config.merge_visits and not any(t.depends_on for t in u.subtasks):
            # not where the unit waits for another subtask: what its robot does before the
            # wait is free (opening the fridge while a slice is cut), and fewer seconds of
            # work can end later
            fewer = merge_visits(base, options[0], [*u.conditions, *u.protect])
            if fewer != options[0]:
                options.insert(0, fewer)
        return options

    def _take(self, u: Unit, options: list[list[tuple[str, Action]]], base: WorldState) -> list[SeqStep] | None:
        """Replay the unit's plan (``options``: :meth:`_options`, the shorter first) and
        accept it, or send it back to the next round; the steps accepted, or None."""
        why: str | None = None
        missing: list[Condition] = []
        broken: list[Condition] = []
        for option in options:
            steps = [SeqStep(r, a, t, u.id) for (r, a), t in zip(option, attribute(option, u, base), strict=True)]
            trial = self.forward.copy()
            grounded, why = replay(trial, steps, self.universe)
            missing, broken = [], []
            if why is None:
                missing = [c for c in u.conditions if not condition_holds(c, trial)]
                broken = [c for c, _ in self.protected.values() if not condition_holds(c, trial)]
            if why is None and not missing and not broken:
                self._accept(u, grounded, after=trial)
                return steps
        if why is None and missing:
            why = "misses " + ", ".join(str(c) for c in missing)
        elif why is None:
            why = "undoes " + ", ".join(str(c) for c in broken)
            for t in u.subtasks:
                self.attempts[t.id].protect.update({str(c): c for c in broken})
        self._reject(u, why)
        return None

    def _reject(self, u: Unit, why: str) -> None:
        for t in u.subtasks:
            self.record.assigned.pop(t.id, None)  # re-allocate from the state it now faces
            self.record.cluster.pop(t.id, None)
            self.attempts[t.id].tries += 1
            if self.attempts[t.id].tries > 3:
                raise Fallback(f"subtask {t.id} {why} whatever the order")
        self.notes.append(f"{u.describe()}: replanned ({why})")

    def _retry_unsolvable(self, u: Unit) -> None:
        """Fast Downward found no plan for a unit: retry once with every candidate object
        and more robots (those able to fill its roles, least loaded first), then give up
        (a typed error if nothing was planned yet, else the joint fallback)."""
        a = [self.attempts[t.id] for t in u.subtasks]
        if any(not x.wide for x in a):
            wide = helpers(u, self.forward, self.ctx.team, self.accepted)
            for x in a:
                x.narrow, x.wide = False, wide
                x.tries += 1
            return
        if not self.accepted and not u.protect:
            raise self.ctx.solver.unsolvable(u.describe(), u.conditions, self.ctx.start, list(u.robots))
        raise Fallback(f"subtask {u.describe()} has no plan from the state the others leave")

    def _accept(self, u: Unit, grounded: list[GroundedStep], after: WorldState | None = None) -> None:
        if after is not None:
            self.forward.objects, self.forward.robots = after.objects, after.robots
            self.at_start = False
        self.accepted.extend(grounded)
        for t in u.subtasks:
            self.done.add(t.id)
            self.unit_of[t.id] = u.id
        _protect(u, self.forward, self.protected)

    def _interleave(self, base: WorldState, plans: Sequence[tuple[Unit, list[SeqStep]]], round_start: int) -> None:
        """Replace the round's unit-by-unit sequence by its time-interleaved replay
        (:mod:`emboteam.hp.interleave`) when that reaches every goal too."""
        if not worth_it(self.accepted[round_start:]):
            return
        goals = [*(c for u, _ in plans for c in u.conditions), *(c for c, _ in self.protected.values())]
        mixed = interleave(base, [steps for _, steps in plans], goals, self.universe)
        if mixed is None:
            return
        del self.accepted[round_start:]
        self.accepted.extend(mixed[0])
        self.forward.objects, self.forward.robots = mixed[1].objects, mixed[1].robots
        self.at_start = False
        for u, _ in plans:
            _protect(u, self.forward, self.protected)

    # ---- eliminate over the whole sequence, merge ---------------------------------------
    def merged(self) -> Draft:
        """The validated plan of the accepted sequence, trimmed when that validates too."""
        ctx = self.ctx
        trimmed = trim.trimmed(self.accepted, ctx.spec, ctx.start, self.universe) \
            if ctx.config.eliminate == "whole" else None
        if trimmed is not None:
            tried: list[str] = []
            try:
                plan = merge_causal(ctx, trimmed, self.unit_of, tried)
            except Invalid:
                pass  # the whole sequence as accepted, below
            else:
                self.notes.extend(tried)
                self.record.sequence = trimmed
                return Draft(plan, self.record)
        try:
            plan = merge_causal(ctx, self.accepted, self.unit_of, self.notes)
        except Invalid as exc:
            raise Fallback(f"the merged plan failed in the simulator: {exc}") from None
        self.record.sequence = list(self.accepted)
        return Draft(plan, self.record)


def _nothing_to_do(u: Unit, state: WorldState) -> bool:
    if not all(condition_holds(c, state) for c in u.conditions):
        return False
    return all(state.robots[r].holding is None or not (
        state.robots[r].profile.can(Skill.PutObject) or state.robots[r].profile.can(Skill.DropHandObject))
        for r in u.robots)


class _Early:
    """The options of each unit (:meth:`_Rounds._options`) worked out as soon as its plan
    is found, in the worker that found it, while the round's other searches run: the
    main thread would otherwise wait for the last search, then eliminate unit by unit.
    The options depend only on the round's start state, the unit and its plan (each unit
    reads ``base``, which nothing writes during the searches), so they are the ones
    :meth:`_Rounds._round` would work out; one that raises is left to it (it raises there,
    in the round's order)."""

    def __init__(self, rounds: _Rounds, todo: Sequence[tuple[Unit, Problem]], base: WorldState) -> None:
        self.rounds, self.todo, self.base = rounds, todo, base
        self.options: dict[int, list[list[tuple[str, Action]]]] = {}  # by id of the unit

    def __call__(self, problem: Problem, result: SolveResult) -> None:
        if not result.solved:
            return
        for u, p in self.todo:
            if p.text != problem.text:
                continue
            try:
                self.options[id(u)] = self.rounds._options(u, polish(p.decode(result.plan)), self.base)
            except Exception:  # worked out again by _round, which raises it in the round's order
                continue


def _protect(u: Unit, forward: WorldState, protected: Protected) -> None:
    """Protect a unit's final goals, with the objects that satisfy them now."""
    for t in u.subtasks:
        if not t.final:
            continue
        for c in t.goal:
            result = check_condition(c, forward)
            objs = set(result.witnesses)
            for w in result.witnesses:
                if w in forward.objects:
                    objs.update(forward.ancestors(w))
            protected[str(c)] = (c, frozenset(objs))
