"""The hybrid planner: subtasks -> Fast Downward -> one validated partially ordered plan.

``HybridPlanner(config).plan(spec, state)``:

1. Check the goals against the state (unknown objects, impossible goals, skills or mass
   capacity the team lacks) and fail early with a typed error.
2. Plan the subtasks in dependency order, in *rounds*: the subtasks whose dependencies are
   planned are allocated to robots (capability, then balanced expected work), grouped into
   planning units (one robot's or one small team's subtasks, at most
   ``unit_conditions`` conditions), and the units are solved in parallel by Fast Downward
   from the state the plans accepted so far leave. Units are then accepted one by one,
   each replayed on the symbolic state: a unit whose plan no longer runs there, misses its
   goal or breaks a goal accepted earlier goes back to the next round (with that goal
   protected); a unit Fast Downward cannot solve is retried with every candidate object and
   the whole team.
3. Merge the accepted sequence into a partial order (:mod:`emboteam.hp.merge`), subtask
   dependencies as causal orderings (:mod:`emboteam.hp.subtask_order`: only the steps
   that reach the dependent subtask's goal or undo its dependency's goal wait for the
   dependency), and
   validate it in the simulator, robots concurrently (:mod:`emboteam.hp.validate`). A
   dependency whose causal ordering fails there is made strict (the whole later subtask
   after the earlier one), noted, and the plan validated again.
4. If decomposition fails (subtasks interleave, a unit keeps failing, the merge does not
   validate), plan the whole goal as ONE joint multi-robot problem, deorder it the same way,
   and mark the plan ``joint``.

``merge="concatenate"`` with ``validate=False`` is the paper's no-HP ablation: each
subtask is solved from the state its dependencies leave, robots' lists are concatenated in
subtask order, the only waits are the subtask dependencies, and nothing is simulated.
"""

from __future__ import annotations

import itertools
import logging
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Literal as TypingLiteral

from emboteam.hp import cluster_split, spot_order
from emboteam.hp.allocation import allocate
from emboteam.hp.contention import bottleneck_first, spot_seconds
from emboteam.hp.decompose import decompose_goal
from emboteam.hp.eliminate import eliminate, eliminate_steps
from emboteam.hp.interleave import interleave, worth_it
from emboteam.hp.merge import (
    GroundedStep,
    MergeMode,
    SeqStep,
    StepFailure,
    advance,
    assemble,
    ground_sequence,
    order,
)
from emboteam.hp.plan import MergedPlan
from emboteam.hp.rebalance import Job, finish_of, loads, measured_jobs, rebalance, work_of
from emboteam.hp.requirements import Need, check_team, covers, need_of
from emboteam.hp.rounds import (
    Attempt,
    Unit,
    already_done,
    attribute,
    clusters,
    helpers,
    make_units,
    polish,
    preparations,
)
from emboteam.hp.subtask_order import (
    Dependency,
    DependencyWaits,
    ancestors,
    dependency_waits,
    subtask_dependencies,
)
from emboteam.hp.validate import estimate, simulate, with_times
from emboteam.hp.visits import merge_visits
from emboteam.pddl.domain import Universe
from emboteam.pddl.errors import (
    PlannerMemoryError,
    PlannerTimeoutError,
    PlanningError,
    PlanValidationError,
    UnsolvableSubtaskError,
)
from emboteam.pddl.problem import Problem, build_problem, planning_state
from emboteam.pddl.runner import FastDownward, PlanCache, SolveResult
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.sim.rules import apply_action, check_action
from emboteam.world.actions import Action, Skill
from emboteam.world.checker import check_condition
from emboteam.world.goals import Condition, Goal, ObjectRef
from emboteam.world.state import WorldState

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class PlannerConfig:
    """How the hybrid planner runs (the ablations are configurations, not forks).

    A dataclass rather than a pydantic model: ``validate`` is a field here, and pydantic
    reserves that name.
    """

    #: Fast Downward alias, or a search string such as ``astar(hmax())``
    alias: str = "lama-first"
    #: seconds per Fast Downward call (household problems solve in ~0.1 s; a call that
    #: runs out is almost always a goal the pruned problem cannot reach)
    time_limit: float = 10.0
    #: MB per Fast Downward call
    memory_limit_mb: int = 2048
    #: Fast Downward calls run in parallel. Three on two cores: a thread grounds its
    #: problem (holding the GIL), then waits on its search process, so with two threads
    #: nobody grounds while both searches run; a third keeps grounding meanwhile (32 robots
    #: x 96 conditions: 0.68 -> 0.64 s, docs/planning.md section 3)
    workers: int = 3
    #: also cache plans on disk here
    cache_dir: str | None = None
    #: plan per subtask (False: one joint problem)
    decompose: bool = True
    #: check the merged plan in the simulator
    validate: bool = True
    #: "formal" (causal links, conflicts, sync points) or "concatenate" (no-HP ablation)
    merge: TypingLiteral["formal", "concatenate"] = "formal"
    #: most conditions one planning unit takes
    unit_conditions: int = 8
    #: what Fast Downward reads: "sas" (our own grounding, the search binary alone) or
    #: "pddl" (the driver: translator, then search); see pddl/runner.py
    planner_input: TypingLiteral["sas", "pddl"] = "sas"
    #: SAS input: operators cost their durations in seconds (a configuration that reads
    #: costs then minimises seconds, not actions; lama-first counts every action as 1)
    action_costs: bool = False
    #: plan a second time with the clusters re-allocated from their measured seconds when
    #: that promises a shorter busiest robot (:mod:`emboteam.hp.rebalance`): "off", "lpt"
    #: (all clusters again, longest first) or "cp-sat" (at most two clusters move, chosen
    #: by OR-Tools CP-SAT with the greedy best move as hint and fallback; repeated while
    #: the plans get shorter)
    rebalance: TypingLiteral["off", "lpt", "cp-sat"] = "cp-sat"
    #: with ``action_costs``: a plan of at least this cost (half seconds) gets a second,
    #: cost-bounded search (``pddl/runner.py``: REFINE_SEARCH); None: never
    refine_cost: int | None = None
    #: drop the steps the goals do not need (action elimination, :mod:`emboteam.hp.eliminate`):
    #: "units" from each unit's plan before it is accepted, "whole" also from the whole
    #: accepted sequence before the merge (across units and rounds: two robots' plans made
    #: apart each run the microwave, one run does), "off" never
    eliminate: TypingLiteral["off", "units", "whole"] = "whole"
    #: when one robot's cluster is longer than the resource-aware bound allows, plan it
    #: again in two parts, the first for a lightly loaded helper, the second for the robot
    #: from the state the first leaves, and keep the plan when the simulated makespan is
    #: shorter (:mod:`emboteam.hp.cluster_split`; at most ``SPLIT_CALLS`` Fast Downward calls)
    split_clusters: bool = False
    #: when one robot's cluster is longer than the resource-aware bound allows and has at
    #: least three blocks (``cluster_split.blocks``: a pencil, a book and a statue put in a
    #: box, the box put on a table), plan it again in one part per block (at most
    #: ``cluster_split.MAX_PARTS``): the part that moves the container first, for the
    #: robot, then the helpers' parts for the able robots that end earliest, each from the
    #: state the previous one leaves; kept when the simulated makespan is shorter (one
    #: Fast Downward call a part). Tried after ``split_clusters`` and ``spot_order``
    split_containers: bool = True
    #: move blocks of steps that waited at a shared spot (the microwave) before the other
    #: robots' steps there that started after their robot was free, and keep the plan
    #: when the simulated makespan is shorter (:mod:`emboteam.hp.spot_order`; replays and
    #: simulations only, no planner call)
    spot_order: bool = True
    #: move a step the robot drove to do to its other visit to the same object, when that
    #: saves seconds (:mod:`emboteam.hp.visits`; replays only, no planner call)
    merge_visits: bool = True

    def __post_init__(self) -> None:
        if self.time_limit <= 0 or self.memory_limit_mb <= 0:
            raise PlanningError("planner time and memory limits must be positive")
        if self.workers < 1 or self.unit_conditions < 1:
            raise PlanningError("planner workers and unit_conditions must be at least 1")
        if self.merge not in ("formal", "concatenate"):
            raise PlanningError(f"merge must be 'formal' or 'concatenate', not {self.merge!r}")
        if self.rebalance not in ("off", "lpt", "cp-sat"):
            raise PlanningError(f"rebalance must be 'off', 'lpt' or 'cp-sat', not {self.rebalance!r}")
        if self.planner_input not in ("sas", "pddl"):
            raise PlanningError(f"planner_input must be 'sas' or 'pddl', not {self.planner_input!r}")


@dataclass
class _Record:
    """What a decomposed planning pass allocated: subtask -> cluster id, subtask -> robots,
    cluster id -> robots able to do it alone (empty: it stays where it is)."""

    cluster: dict[str, str] = field(default_factory=dict)
    assigned: dict[str, tuple[str, ...]] = field(default_factory=dict)
    candidates: dict[str, tuple[str, ...]] = field(default_factory=dict)
    #: the grounded sequence the plan was merged from (its steps in the plan's order)
    sequence: list[GroundedStep] = field(default_factory=list)


#: elimination over the whole accepted sequence gives up a removal whose replay has not
#: rejoined the original within this many steps (docs/planning.md)
ELIMINATE_WINDOW = 40
#: at most this many re-allocation passes (each a whole planning pass, kept when shorter;
#: the robots whose clusters stay get their plans from the cache), counting the proposals
#: that did not pay off
REBALANCE_PASSES = 8
#: no further pass once the passes have asked for this many problems not asked before in
#: this planning call (a pass of the 32-robot x 96-condition cell asks 10-20 new ones, of a
#: 2-4 robot cell 3-5: the robots that keep their clusters ask the same problems again, so
#: the budget buys more passes where the team is small). Counted in problems, not Fast
#: Downward processes, so that a warm or disk cache gives the same plan as a cold one
REBALANCE_CALLS = 32
#: a proposal that does not shorten the plan is not the end: the next best one without its
#: moves is tried from the same plan (measured seconds transfer only roughly: a robot's
#: other clusters change with its order of clusters; docs/planning.md)
REBALANCE_RETRY = True
#: Fast Downward calls one cluster split may make (two per order of its two parts)
SPLIT_CALLS = 4


def _rounded(xs: Mapping[str, float]) -> dict[str, float]:
    return {k: round(v, 1) for k, v in xs.items()}


class _Fallback(Exception):
    """Decomposition cannot work here; the reason goes into the plan's notes."""


class _Invalid(Exception):
    """The merged plan failed in the simulator; ``index`` is the position of the failed
    step in the merged sequence (None: no step failed, e.g. the goal did not hold)."""

    def __init__(self, why: str, index: int | None = None) -> None:
        super().__init__(why)
        self.index = index


class HybridPlanner:
    """Plans TaskSpecs (and bare goals) for the robots of a state. Reusable: its plan
    cache persists across calls."""

    def __init__(self, config: PlannerConfig | None = None) -> None:
        self.config = config or PlannerConfig()
        self.cache = PlanCache(self.config.cache_dir)
        #: texts of the problems asked for in the current :meth:`plan` call (cache hits
        #: too): the re-allocation's budget counts these, so that a warm cache, a disk
        #: cache or a planner reused for a second task does not change the plan
        self.asked: set[str] = set()
        self.fd = FastDownward(self.config.alias, time_limit=self.config.time_limit,
                               memory_limit_mb=self.config.memory_limit_mb, cache=self.cache,
                               planner_input=self.config.planner_input,
                               action_costs=self.config.action_costs,
                               refine_cost=self.config.refine_cost)

    # ---- public API ---------------------------------------------------------------------
    def plan(self, spec: TaskSpec, state: WorldState) -> MergedPlan:
        """A validated multi-robot plan for ``spec`` from ``state`` (not modified)."""
        t0 = time.perf_counter()
        calls0 = self.fd.calls
        self.asked = set()
        team = [r for r, rs in state.robots.items() if not rs.down]
        if not team:
            raise PlanningError("no working robot in the team")
        start = planning_state(state)
        needs = {t.id: [need_of(c, start, team) for c in t.goal] for t in spec.subtasks}
        check_team([n for ns in needs.values() for n in ns], [start.robots[r].profile for r in team])
        notes: list[str] = []
        if self.config.merge == "concatenate":
            plan = self._concatenated(spec, start, team, needs, notes)
        elif self.config.decompose:
            try:
                plan = self._decomposed(spec, start, team, notes, record=(record := _Record()))
                plan = self._rebalanced(plan, spec, start, team, notes, record)
                plan = self._split(plan, spec, start, team, notes, record, needs)
                plan = self._reorder(plan, spec, start, team, notes, record)
                split = self._split(plan, spec, start, team, notes, record, needs, containers=True)
                if split is not plan:
                    plan = self._reorder(split, spec, start, team, notes, record)
            except _Fallback as fb:
                notes.append(f"decomposition failed ({fb}): planned as one joint problem")
                plan = self._joint(spec, start, team, notes)
        else:
            plan = self._joint(spec, start, team, notes)
        return plan.model_copy(update={"planner_calls": self.fd.calls - calls0,
                                       "plan_seconds": round(time.perf_counter() - t0, 4),
                                       "notes": tuple(notes)})

    def plan_goal(self, goal: Goal, state: WorldState) -> MergedPlan:
        """Plan a bare goal from ``state`` (e.g. mid-run, robots holding things): related
        conditions become subtasks, the allocator spreads them over the working robots."""
        return self.plan(decompose_goal(goal, state), state)

    # ---- Fast Downward ------------------------------------------------------------------
    def _solve(self, problems: Sequence[Problem]) -> list[SolveResult]:
        results = self._solve_all(problems)
        for r in results:
            if isinstance(r, PlanningError):
                raise r
        return [r for r in results if isinstance(r, SolveResult)]

    def _solve_all(self, problems: Sequence[Problem], workers: int | None = None
                   ) -> list[SolveResult | PlanningError]:
        """Fast Downward on ``problems`` (in parallel), each slot the result or its typed
        error; a time-out is raised, not returned: the time limit is a safety net, and no
        plan may depend on where a search was cut off (issue 28)."""
        self.asked.update(p.text for p in problems)
        results = self.fd.solve_problems(problems, self.config.workers if workers is None else workers)
        for r in results:
            if isinstance(r, PlannerTimeoutError):
                raise r
        return results

    def _unsolvable(self, what: str, conditions: Sequence[Condition], state: WorldState,
                    robots: Sequence[str]) -> UnsolvableSubtaskError:
        """Name the conditions that cannot be reached (each tried alone, a few calls)."""
        unmet = [c for c in conditions if not check_condition(c, state).holds]
        culprits: list[Condition] = []
        if 1 < len(unmet) <= 4:
            problems = [build_problem(state, [c], robots, name="why", narrow=False, release=False)
                        for c in unmet]
            culprits = [c for c, r in zip(unmet, self._solve(problems), strict=True) if not r.solved]
        shown = culprits or unmet
        return UnsolvableSubtaskError(
            f"subtask {what} has no plan: {', '.join(str(c) for c in shown)} cannot be reached by "
            f"{', '.join(robots)}", subtask=what, unmet=tuple(str(c) for c in shown))

    # ---- decomposed planning ------------------------------------------------------------
    def _decomposed(self, spec: TaskSpec, start: WorldState, team: list[str], notes: list[str],
                    prefer: Mapping[str, str] | None = None, record: _Record | None = None) -> MergedPlan:
        """Plan in rounds, merge, validate. ``prefer``: a robot per cluster id (from
        :func:`emboteam.hp.rebalance.rebalance`); ``record`` is filled with the clusters,
        their robots and the robots able to do each alone."""
        forward = start.copy()
        universe = Universe(forward)
        accepted: list[GroundedStep] = []
        done: set[str] = set()
        unit_of: dict[str, str] = {}
        protected: dict[str, tuple[Condition, frozenset[str]]] = {}
        assigned: dict[str, tuple[str, ...]] = {}
        cluster: dict[str, str] = {}
        attempts = {t.id: Attempt() for t in spec.subtasks}
        pending = [t for t in spec.subtasks]
        counter = itertools.count(1)
        rounds = 0
        while pending:
            rounds += 1
            if rounds > 3 * len(spec.subtasks) + 3:
                raise _Fallback("subtasks keep undoing each other")
            ready = [t for t in pending if all(d in done for d in t.depends_on)]
            load = {r: sum(g.seconds for g in accepted if g.robot == r) for r in team}
            fresh = [t for t in ready if t.id not in assigned]
            if fresh:
                groups = clusters(fresh, forward, team)
                needs = {g.id: [need_of(c, forward, team) for c in g.goal] for g in groups}
                for a in allocate(groups, needs, forward, team, load, prefer):
                    members = a.subtask.split("+")
                    for m in members:
                        assigned[m] = a.robots
                        cluster[m] = a.subtask
                    if record is not None:
                        record.candidates[a.subtask] = () if a.note == "as specified" else tuple(
                            r for r in team if all(covers([forward.robots[r].profile], n) for n in needs[a.subtask]))
                    if a.note != "as specified":
                        notes.append(f"{', '.join(members)}: {a.note} -> {', '.join(a.robots)}")
            units = make_units(ready, assigned, attempts, counter, cluster, self.config.unit_conditions)
            base = forward.copy()
            todo: list[tuple[Unit, Problem]] = []
            # units already satisfied are accepted first, so their goals are protected in
            # the problems of the others
            for u in [u for u in units if self._nothing_to_do(u, base)]:
                self._accept(u, [], forward, accepted, done, unit_of, protected)
            units = [u for u in units if u.subtasks[0].id not in done]
            pending = [t for t in pending if t.id not in done]
            for u in units:
                problem = build_problem(base, u.conditions, u.robots, name=u.id, narrow=u.narrow)
                overlap = [c for c, objs in protected.values() if objs & set(problem.objects)]
                extra = [c for c in overlap if str(c) not in {str(p) for p in u.protect}]
                if u.protect or extra:
                    u.protect = [*u.protect, *extra]
                    problem = build_problem(base, u.conditions, u.robots, name=u.id, narrow=u.narrow,
                                            protect=u.protect)
                todo.append((u, problem))
            round_start = len(accepted)
            round_plans: list[tuple[Unit, list[SeqStep]]] = []
            results = self._solve_all([p for _, p in todo])
            # users of the round's most contended spot are accepted (so ordered) first
            uses = [spot_seconds(base, p.decode(r.plan)) if isinstance(r, SolveResult) and r.solved else None
                    for (_, p), r in zip(todo, results, strict=True)]
            for (u, problem), result in bottleneck_first(list(zip(todo, results, strict=True)), uses):
                if isinstance(result, PlannerMemoryError) and len(u.subtasks) > 1:
                    for t in u.subtasks:  # too big to solve at once: one subtask at a time
                        attempts[t.id].solo = True
                    notes.append(f"{u.describe()}: {result}; planned one subtask at a time")
                    continue
                if isinstance(result, PlanningError):
                    raise result
                if not result.solved:
                    self._retry_unsolvable(u, attempts, accepted, start, forward, team)
                    continue
                actions = polish(problem.decode(result.plan))
                options = [actions]
                if self.config.eliminate != "off" and all(t.final for t in u.subtasks):
                    # u.protect holds every accepted goal on the problem's objects; goals on
                    # others are checked when the unit is replayed below. The shorter plan
                    # is tried first, the planner's own if it does not pass. Not with an
                    # intermediate goal: it need not hold at the end, so nothing would keep
                    # the steps that reach it.
                    shorter = eliminate(base, actions, [*u.conditions, *u.protect])
                    if len(shorter) < len(actions):
                        options.insert(0, shorter)
                    if self.config.merge_visits and not any(t.depends_on for t in u.subtasks):
                        # the steps of the plan tried first, moved to other visits. Not
                        # where the unit waits for another subtask: what its robot does
                        # before the wait is free (opening the fridge while a slice is
                        # cut), and fewer seconds of work can end later
                        fewer = merge_visits(base, options[0], [*u.conditions, *u.protect])
                        if fewer != options[0]:
                            options.insert(0, fewer)
                for actions in options:
                    steps = [SeqStep(r, a, t, u.id)
                             for (r, a), t in zip(actions, attribute(actions, u, base), strict=True)]
                    trial = forward.copy()
                    grounded, why = self._replay(trial, steps, universe)
                    missing: list[Condition] = []
                    broken: list[Condition] = []
                    if why is None:
                        missing = [c for c in u.conditions if not check_condition(c, trial).holds]
                        broken = [c for c, _ in protected.values() if not check_condition(c, trial).holds]
                    if why is None and not missing and not broken:
                        break
                if why is None:
                    if missing:
                        why = "misses " + ", ".join(str(c) for c in missing)
                    elif broken:
                        why = "undoes " + ", ".join(str(c) for c in broken)
                        for t in u.subtasks:
                            attempts[t.id].protect.update({str(c): c for c in broken})
                if why is not None:
                    for t in u.subtasks:
                        assigned.pop(t.id, None)  # re-allocate from the state it now faces
                        cluster.pop(t.id, None)
                        attempts[t.id].tries += 1
                        if attempts[t.id].tries > 3:
                            raise _Fallback(f"subtask {t.id} {why} whatever the order")
                    notes.append(f"{u.describe()}: replanned ({why})")
                    continue
                self._accept(u, grounded, forward, accepted, done, unit_of, protected, after=trial)
                round_plans.append((u, steps))
            if len(round_plans) > 1:
                self._interleave(base, round_plans, round_start, forward, accepted, protected, universe)
            pending = [t for t in pending if t.id not in done]
        if record is not None:
            record.cluster.update(cluster)
            record.assigned.update(assigned)
        trimmed = (self._eliminated(accepted, spec, start, universe) if self.config.eliminate == "whole"
                   else None)
        if trimmed is not None:
            tried: list[str] = []
            try:
                plan = self._merge_causal(trimmed, spec, unit_of, team, start, tried)
            except _Invalid:
                pass  # the whole sequence as accepted, below
            else:
                notes.extend(tried)
                if record is not None:
                    record.sequence = trimmed
                return plan
        try:
            plan = self._merge_causal(accepted, spec, unit_of, team, start, notes)
        except _Invalid as exc:
            raise _Fallback(f"the merged plan failed in the simulator: {exc}") from None
        if record is not None:
            record.sequence = list(accepted)
        return plan

    @staticmethod
    def _eliminated(accepted: Sequence[GroundedStep], spec: TaskSpec, start: WorldState, universe: Universe
                    ) -> list[GroundedStep] | None:
        """The accepted sequence without the steps the goal does not need across units and
        rounds (:func:`emboteam.hp.eliminate.eliminate`): two robots heat things in one
        microwave run where their plans, made apart, each ran it; None when nothing goes,
        when some subtask's goal is intermediate (the elimination keeps only what holds at
        the end) or the shorter sequence fails a PDDL precondition."""
        if any(not t.final for t in spec.subtasks) or len(accepted) < 2:
            return None
        kept, moved = eliminate_steps(start, [(g.robot, g.action) for g in accepted], spec.goal().conditions,
                                      window=ELIMINATE_WINDOW)
        if len(kept) == len(accepted):
            return None
        state = start.copy()
        steps: list[GroundedStep] = []
        try:
            for k in kept:
                g = accepted[k]
                if k in moved:  # may start from another state now: grounded again
                    steps.append(advance(state, SeqStep(g.robot, g.action, g.subtask, g.group), len(steps),
                                         universe=universe))
                else:  # starts from the very state it was grounded in
                    apply_action(state, g.robot, g.action)
                    steps.append(g)
        except StepFailure:
            return None
        return steps

    def _rebalanced(self, plan: MergedPlan, spec: TaskSpec, start: WorldState, team: list[str],
                    notes: list[str], record: _Record) -> MergedPlan:
        """Plan again with the clusters re-allocated from their measured seconds
        (:mod:`emboteam.hp.rebalance`) when that promises the robot that ends last an
        earlier end, or, when nothing does, the robot with the most work less of it;
        keep the plan with the shorter makespan, and try again from it. A proposal that
        does not make the plan shorter is not the end: its moves are excluded and the next
        best proposal for the same plan is tried (at most ``REBALANCE_PASSES`` passes and
        ``REBALANCE_CALLS`` Fast Downward calls)."""
        if self.config.rebalance == "off" or not self.config.validate:
            return plan
        asked0 = len(self.asked)
        tabu: set[tuple[str, str]] = set()  # moves that did not pay off from this plan
        for _ in range(REBALANCE_PASSES):
            if len(self.asked) - asked0 >= REBALANCE_CALLS:
                log.debug("rebalance: call budget spent (%d problems)", len(self.asked) - asked0)
                return plan  # the passes so far cost enough Fast Downward calls
            jobs = measured_jobs(plan, record.cluster, record.assigned, record.candidates)
            # a robot's time is its work and its waits (for a spot, a tool, another robot):
            # the waits stay with it as a job that does not move, so the robot that ends
            # last is the one to relieve
            ends = finish_of(plan, team)
            work = work_of(plan)
            waits = [Job(f"wait:{r}", (r,), ends[r] - work.get(r, 0.0), ()) for r in team
                     if ends[r] - work.get(r, 0.0) > 1e-9]
            prefer = rebalance([*jobs, *waits], team, max(ends.values(), default=0.0), self.config.rebalance,
                               exclude=tabu)
            if prefer is None:
                # the robot that ends last cannot be relieved (it does one cluster and
                # waits): relieve the one with the most work, which may be what it waits for
                prefer = rebalance(jobs, team, max(work.values(), default=0.0), self.config.rebalance,
                                   exclude=tabu)
            if prefer is None:
                log.debug("rebalance: no proposal (ends %s, work %s)", _rounded(ends), _rounded(work))
                return plan
            moves = {(j.id, prefer[j.id]) for j in jobs if j.id in prefer and prefer[j.id] != j.robots[0]}
            if moves <= tabu:
                return plan  # nothing new to try ("lpt" proposes all again, ignoring the exclusions)
            again: list[str] = []
            try:
                other = self._decomposed(spec, start, team, again, prefer=prefer, record=(mine := _Record()))
            except (_Fallback, PlanningError):
                return plan
            if log.isEnabledFor(logging.DEBUG):
                log.debug("rebalance: moves %s, promised %s, makespan %.1f -> %.1f (work %s -> %s, %d calls)",
                          sorted(moves), _rounded(loads(jobs, team, prefer)), plan.makespan, other.makespan,
                          _rounded(work), _rounded(work_of(other)), len(self.asked) - asked0)
            if other.makespan >= plan.makespan:
                if not REBALANCE_RETRY:
                    return plan
                tabu |= moves
                continue
            notes[:] = [*again, f"re-allocated from the measured plans: makespan {plan.makespan:.1f} -> "
                        f"{other.makespan:.1f} s"]
            plan = other
            tabu = set()
            record.cluster, record.assigned, record.candidates = mine.cluster, mine.assigned, mine.candidates
            record.sequence = mine.sequence
        return plan

    def _split(self, plan: MergedPlan, spec: TaskSpec, start: WorldState, team: list[str], notes: list[str],
               record: _Record, needs: Mapping[str, Sequence[Need]], containers: bool = False) -> MergedPlan:
        """Two robots on the longest cluster one robot does
        (:mod:`emboteam.hp.cluster_split`): its subtasks in two parts, the first planned
        for a helper from where the cluster started, the second for the robot from where
        the first leaves it; spliced in place of the robot's steps, replayed, merged and
        simulated. The plan with the shorter makespan is kept. Only for specs whose
        subtasks are final and independent (the splice keeps no dependency waits).
        ``containers``: one part per block, among several robots instead
        (:meth:`_split_parts`, ``PlannerConfig.split_containers``)."""
        if not (self.config.split_containers if containers else self.config.split_clusters) or not self.config.validate:
            return plan
        if any(t.depends_on or not t.final for t in spec.subtasks):
            return plan
        goal_of = {t.id: t.goal for t in spec.subtasks}

        def able(robot: str, members: Sequence[str]) -> bool:
            profile = start.robots[robot].profile
            return all(covers([profile], n) for m in members for n in needs.get(m, ()))

        target = cluster_split.find_target(plan, record.cluster, able)
        if target is None:
            return plan
        if len(record.sequence) != len(plan.steps):
            return plan
        before, gone, rest = cluster_split.splice(record.sequence, target)
        log.debug("split %s (makespan %.1f, bound %.1f)", target, plan.makespan, plan.resource_bound)
        universe = Universe(start.copy())
        here = start.copy()
        for g in before:
            apply_action(here, g.robot, g.action)
        members = set(target.members)
        kept = [c for t in spec.subtasks if t.id not in members for c in t.goal if check_condition(c, here).holds]
        subjects = {t.id: frozenset(_kind(c.subject, start) for c in t.goal) for t in spec.subtasks
                    if t.id in members}

        def conds(part: Sequence[str]) -> list[Condition]:
            return [c for m in part for c in goal_of[m]]

        def steps_of(problem: Problem, result: SolveResult, part: Sequence[str], state: WorldState) -> list[SeqStep]:
            actions = polish(problem.decode(result.plan))
            unit = Unit("split", [spec.subtask(m) for m in part], ())
            return [SeqStep(r, a, t, t) for (r, a), t in zip(actions, attribute(actions, unit, state), strict=True)]

        if containers:
            receptacles = {t.id: frozenset(_kind(c.receptacle, start) for c in t.goal if c.receptacle is not None)
                           for t in spec.subtasks if t.id in members}
            parts = cluster_split.container_parts(target, subjects, receptacles,
                                                  min(cluster_split.MAX_PARTS, len(target.helpers) + 1))
            if parts:
                helpers = list(target.helpers[:len(parts) - 1])
                found: tuple[MergedPlan, list[GroundedStep]] | None = None
                for order in cluster_split.CONTAINER_ORDERS:
                    if order == "last":
                        robots, ordered = [*helpers, target.robot], list(parts)
                    else:
                        robots = [target.robot, *helpers]
                        ordered = cluster_split.container_first(parts, target.members, subjects, receptacles)
                    tried = self._split_parts(found[0] if found else plan, spec, start, team, robots, ordered,
                                              (before, gone, rest), here, kept, universe, conds, steps_of)
                    if tried is not None:
                        found = tried
                if found is not None:
                    best, sequence = found
                    record.sequence = sequence
                    notes.append(f"{', '.join(target.members)}: parted among {', '.join(helpers)} and "
                                 f"{target.robot}: makespan {plan.makespan:.1f} -> {best.makespan:.1f} s")
                    return best
            return plan
        orders = [o for a, b in cluster_split.partitions(target, subjects) for o in ((a, b), (b, a))]
        orders = orders[:SPLIT_CALLS // 2]

        built = [(o, self._split_problem(here, conds(o[0]), target.helper, kept)) for o in orders]
        firsts = [(o, p) for o, p in built if p is not None]
        staged: list[tuple[list[GroundedStep], WorldState, Sequence[str], Problem]] = []
        results = self._solve_all([p for _, p in firsts])
        for ((a, b), problem), result in zip(firsts, results, strict=True):
            if not isinstance(result, SolveResult) or not result.solved:
                continue
            after = here.copy()
            grounded, why = self._replay(after, steps_of(problem, result, a, here), universe)
            if why is not None or not all(check_condition(c, after).holds for c in conds(a)):
                continue
            second_problem = self._split_problem(after, conds(b), target.robot, [*kept, *conds(a)])
            if second_problem is not None:
                staged.append((grounded, after, b, second_problem))
        seconds = self._solve_all([p for *_, p in staged]) if staged else []
        best = plan
        for (grounded, after, part, problem), result in zip(staged, seconds, strict=True):
            if not isinstance(result, SolveResult) or not result.solved:
                continue
            trial = after.copy()
            second, why = self._replay(trial, steps_of(problem, result, part, after), universe)
            if why is not None:
                continue
            tail, why = self._replay_reusing(trial, rest, set(), universe, [*gone, *grounded, *second])
            if why is not None or not all(check_condition(c, trial).holds for c in spec.goal().conditions):
                continue
            try:
                other = self._finish([*before, *grounded, *second, *tail], {}, team, start,
                                     spec.goal(), "formal")
            except _Invalid as exc:
                log.debug("split %s fails in the simulator: %s", part, exc)
                continue
            log.debug("split, second part %s: makespan %.1f", part, other.makespan)
            if other.makespan < best.makespan - 1e-6:
                best, sequence = other, [*before, *grounded, *second, *tail]
        if best is not plan:
            record.sequence = sequence
            notes.append(f"{', '.join(target.members)}: split between {target.helper} and {target.robot}: "
                         f"makespan {plan.makespan:.1f} -> {best.makespan:.1f} s")
        return best

    def _split_parts(self, plan: MergedPlan, spec: TaskSpec, start: WorldState, team: list[str],
                     robots: Sequence[str], parts: Sequence[Sequence[str]],
                     cut: tuple[list[GroundedStep], list[GroundedStep], list[GroundedStep]], here: WorldState,
                     kept: Sequence[Condition], universe: Universe,
                     conds: Callable[[Sequence[str]], list[Condition]],
                     steps_of: Callable[[Problem, SolveResult, Sequence[str], WorldState], list[SeqStep]],
                     ) -> tuple[MergedPlan, list[GroundedStep]] | None:
        """The cluster in ``parts`` (:func:`cluster_split.container_parts`), one robot each:
        the helpers' parts for the able robots that end earliest, the last for the
        cluster's robot, each planned from the state the previous one leaves with the
        goals reached so far protected (one Fast Downward call a part, one after the
        other); spliced in place of the robot's steps, replayed, merged and simulated. The
        plan and its sequence when its makespan is shorter, else None."""
        before, gone, rest = cut
        state, reached = here, list(kept)
        new: list[GroundedStep] = []
        for robot, part in zip(robots, parts, strict=True):
            problem = self._split_problem(state, conds(part), robot, reached)
            if problem is None:
                return None
            result = self._solve_all([problem], 1)[0]
            if not isinstance(result, SolveResult) or not result.solved:
                return None
            after = state.copy()
            grounded, why = self._replay(after, steps_of(problem, result, part, state), universe)
            if why is not None or not all(check_condition(c, after).holds for c in conds(part)):
                log.debug("part %s of %s fails: %s", part, robot, why or "misses its goal")
                return None
            new.extend(grounded)
            reached.extend(conds(part))
            state = after
        trial = state.copy()
        tail, why = self._replay_reusing(trial, rest, set(), universe, [*gone, *new])
        if why is not None or not all(check_condition(c, trial).holds for c in spec.goal().conditions):
            return None
        sequence = [*before, *new, *tail]
        try:
            other = self._finish(sequence, {}, team, start, spec.goal(), "formal")
        except _Invalid as exc:
            log.debug("split into %s fails in the simulator: %s", parts, exc)
            return None
        log.debug("split into %s: makespan %.1f -> %.1f", parts, plan.makespan, other.makespan)
        if other.makespan < plan.makespan - 1e-6:
            return other, sequence
        return None

    def _reorder(self, plan: MergedPlan, spec: TaskSpec, start: WorldState, team: list[str], notes: list[str],
                 record: _Record) -> MergedPlan:
        """Move blocks that waited at a shared spot ahead of the steps that made them wait
        (:mod:`emboteam.hp.spot_order`), one at a time, each replayed, merged and
        simulated; a move is kept when the makespan is shorter, and the search goes on
        from it (at most ``spot_order.TRIES`` moves tried in all). Only for specs whose
        subtasks are final and independent, as :meth:`_split`."""
        if not self.config.spot_order or not self.config.validate:
            return plan
        if any(t.depends_on or not t.final for t in spec.subtasks):
            return plan
        seq = record.sequence
        if len(seq) != len(plan.steps):
            return plan
        universe = Universe(start.copy())
        goal = spec.goal()
        tried = 0
        while tried < spot_order.TRIES:
            options = spot_order.candidates(plan, spot_order.TRIES - tried)
            if not options:
                break
            for block, new_order in options:
                tried += 1
                p = next(i for i, k in enumerate(new_order) if i != k)
                state = start.copy()
                for g in seq[:p]:
                    apply_action(state, g.robot, g.action)
                grounded, why = self._replay_reusing(state, [seq[k] for k in new_order[p:]],
                                                     {i for i, k in enumerate(new_order[p:]) if seq[k].robot == block.robot},
                                                     universe)
                if why is None and not all(check_condition(c, state).holds for c in goal.conditions):
                    why = "misses the goal"
                if why is not None:
                    log.debug("moving %s fails: %s", block, why)
                    continue
                candidate = [*seq[:p], *grounded]
                try:
                    other = self._finish(candidate, {}, team, start, goal, "formal")
                except _Invalid as exc:
                    log.debug("moving %s fails in the simulator: %s", block, exc)
                    continue
                log.debug("moving %s: makespan %.1f -> %.1f", block, plan.makespan, other.makespan)
                if other.makespan < plan.makespan - 1e-6:
                    notes.append(f"{block.robot}'s steps at {block.spot} moved ahead ({block.wait:.1f} s of waiting): "
                                 f"makespan {plan.makespan:.1f} -> {other.makespan:.1f} s")
                    plan, seq = other, candidate
                    break
            else:
                break
        record.sequence = seq
        return plan

    @staticmethod
    def _split_problem(state: WorldState, conditions: Sequence[Condition], robot: str,
                       kept: Sequence[Condition]) -> Problem | None:
        """One part of a split cluster for one robot, keeping the goals already reached
        that its problem's objects take part in (None: the goal compiler finds it out of
        that robot's reach, and the split is not tried that way)."""
        try:
            return HybridPlanner._protected_problem(state, conditions, robot, kept)
        except PlanningError:
            return None

    @staticmethod
    def _protected_problem(state: WorldState, conditions: Sequence[Condition], robot: str,
                           kept: Sequence[Condition]) -> Problem:
        problem = build_problem(state, conditions, [robot], name="split")
        objects = set(problem.objects)
        overlap = []
        for c in kept:
            result = check_condition(c, state)
            objs = set(result.witnesses)
            for w in result.witnesses:
                if w in state.objects:
                    objs.update(state.ancestors(w))
            if objs & objects:
                overlap.append(c)
        if not overlap:
            return problem
        return build_problem(state, conditions, [robot], name="split", protect=overlap)

    def _merge_causal(self, accepted: Sequence[GroundedStep], spec: TaskSpec, unit_of: Mapping[str, str],
                      team: Sequence[str], start: WorldState, notes: list[str]) -> MergedPlan:
        """Merge with the subtask dependencies as causal orderings
        (:mod:`emboteam.hp.subtask_order`) and validate. When that plan fails in the
        simulator, the dependencies involving the unit whose step failed (all remaining
        ones if no step failed or none of those is still causal) become strict (every
        step of the later subtask after the earlier one), noted, until the plan validates
        or every dependency is strict (then :class:`_Invalid` propagates: the joint
        fallback). Never returns an unvalidated plan (unless validation is off)."""
        deps = subtask_dependencies(spec, unit_of)
        groups = _group_dependencies(spec, unit_of)
        strict: set[Dependency] = set()
        while True:
            waits = dependency_waits(start, accepted, deps, strict)
            try:
                return self._finish(accepted, groups, team, start, spec.goal(), "formal", waits)
            except _Invalid as exc:
                relaxed = [d for d in deps if d not in strict]
                if not relaxed:
                    raise
                failed = accepted[exc.index].group if exc.index is not None else None
                culprits = [d for d in relaxed if failed in (d.later_group, d.earlier_group)] or relaxed
                strict.update(culprits)
                notes.append(f"the causal ordering of {', '.join(str(d) for d in culprits)} failed in the "
                             f"simulator ({exc}): strict ordering there (every step of the later subtask "
                             "waits for the earlier one)")

    @staticmethod
    def _nothing_to_do(u: Unit, state: WorldState) -> bool:
        if not all(check_condition(c, state).holds for c in u.conditions):
            return False
        return all(state.robots[r].holding is None or not (
            state.robots[r].profile.can(Skill.PutObject) or state.robots[r].profile.can(Skill.DropHandObject))
            for r in u.robots)

    def _retry_unsolvable(self, u: Unit, attempts: Mapping[str, Attempt], accepted: Sequence[GroundedStep],
                          start: WorldState, forward: WorldState, team: Sequence[str]) -> None:
        """Fast Downward found no plan for a unit: retry once with every candidate object
        and more robots (those able to fill its roles, least loaded first), then give up
        (a typed error if nothing was planned yet, else the joint fallback)."""
        a = [attempts[t.id] for t in u.subtasks]
        if any(not x.wide for x in a):
            wide = helpers(u, forward, team, accepted)
            for x in a:
                x.narrow, x.wide = False, wide
                x.tries += 1
            return
        if not accepted and not u.protect:
            raise self._unsolvable(u.describe(), u.conditions, start, list(u.robots))
        raise _Fallback(f"subtask {u.describe()} has no plan from the state the others leave")

    @classmethod
    def _interleave(cls, base: WorldState, plans: Sequence[tuple[Unit, list[SeqStep]]], round_start: int,
                    forward: WorldState, accepted: list[GroundedStep],
                    protected: dict[str, tuple[Condition, frozenset[str]]], universe: Universe) -> None:
        """Replace the round's unit-by-unit sequence by its time-interleaved replay
        (:mod:`emboteam.hp.interleave`) when that reaches every goal too."""
        if not worth_it(accepted[round_start:]):
            return
        goals = [*(c for u, _ in plans for c in u.conditions), *(c for c, _ in protected.values())]
        mixed = interleave(base, [steps for _, steps in plans], goals, universe)
        if mixed is None:
            return
        del accepted[round_start:]
        accepted.extend(mixed[0])
        forward.objects, forward.robots = mixed[1].objects, mixed[1].robots
        for u, _ in plans:
            cls._protect(u, forward, protected)

    @staticmethod
    def _protect(u: Unit, forward: WorldState, protected: dict[str, tuple[Condition, frozenset[str]]]) -> None:
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

    @staticmethod
    def _replay(trial: WorldState, steps: Sequence[SeqStep], universe: Universe,
                repair: Callable[[WorldState, SeqStep], list[Action]] | None = None
                ) -> tuple[list[GroundedStep], str | None]:
        """Run a unit's steps on ``trial`` (in place): grounded steps, or why they fail.
        ``repair``: more preparations, after :func:`preparations` (a reordering's)."""
        grounded: list[GroundedStep] = []
        try:
            for i, st in enumerate(steps):
                if already_done(trial, st.action):
                    continue  # another unit opened (switched, ...) it first: nothing to do
                for prep in preparations(trial, st):
                    # planned for a world another unit has changed since (the robot or the
                    # object moved, the microwave was left running): a step first puts it right
                    grounded.append(advance(trial, SeqStep(st.robot, prep, st.subtask, st.group), i,
                                            universe=universe))
                for prep in repair(trial, st) if repair is not None else ():
                    grounded.append(advance(trial, SeqStep(st.robot, prep, st.subtask, st.group), i,
                                            universe=universe))
                grounded.append(advance(trial, st, i, universe=universe))
        except StepFailure as exc:
            return [], f"no longer runs: {exc}"
        return grounded, None

    def _replay_reusing(self, state: WorldState, steps: Sequence[GroundedStep], fresh: set[int],
                        universe: Universe, changed: Sequence[GroundedStep] = ()
                        ) -> tuple[list[GroundedStep], str | None]:
        """Replay grounded steps in a new order on ``state`` (in place). The steps at
        ``fresh`` positions (those moved) are grounded again, with the repairs of
        :meth:`_replay` and :func:`emboteam.hp.spot_order.reopen`; so is every step that
        reads or writes a state variable a step grounded *differently* may have set (or
        updates one it wrote: two updates of a set commute). The others see the values
        they saw when they were grounded, so their grounding is kept and only applied;
        a step grounded again exactly as before sets the same values, so it sets nothing
        apart. A reordering of a 200-step plan grounds tens of steps, not all. ``changed``:
        steps taken out or put in before these (their variables are set apart too)."""
        written = {v for x in changed for v in x.footprint.writes}
        updated = {v for x in changed for v in x.footprint.updates}
        out: list[GroundedStep] = []
        for i, g in enumerate(steps):
            fp = g.footprint
            if i not in fresh:
                seen = fp.reads | fp.writes | {f"loc:{x}" for x in (g.action.target, g.action.receptacle) if x}
                if not seen & (written | updated) and not fp.updates & written:
                    apply_action(state, g.robot, g.action)
                    out.append(g)
                    continue
            again, why = self._replay(state, [SeqStep(g.robot, g.action, g.subtask, g.group)], universe,
                                      spot_order.reopen)
            if why is not None:
                return [], why
            if again != [g]:
                for x in [g, *again]:
                    written |= x.footprint.writes
                    updated |= x.footprint.updates
            out += again
        return out, None

    @staticmethod
    def _accept(u: Unit, grounded: list[GroundedStep], forward: WorldState, accepted: list[GroundedStep],
                done: set[str], unit_of: dict[str, str],
                protected: dict[str, tuple[Condition, frozenset[str]]],
                after: WorldState | None = None) -> None:
        if after is not None:
            forward.objects, forward.robots = after.objects, after.robots
        accepted.extend(grounded)
        for t in u.subtasks:
            done.add(t.id)
            unit_of[t.id] = u.id
        HybridPlanner._protect(u, forward, protected)

    # ---- joint planning -----------------------------------------------------------------
    def _joint(self, spec: TaskSpec, start: WorldState, team: list[str], notes: list[str]) -> MergedPlan:
        goal = spec.goal()
        if any(not t.final for t in spec.subtasks):
            notes.append("joint problem: intermediate (non-final) subtask goals are not planned")
        problem = build_problem(start, goal.conditions, team, name="joint")
        result = self._solve([problem])[0]
        if not result.solved:
            problem = build_problem(start, goal.conditions, team, name="joint", narrow=False)
            result = self._solve([problem])[0]
        if not result.solved:
            raise self._unsolvable("joint (the whole goal)", goal.conditions, start, team)
        actions = polish(problem.decode(result.plan))
        unit = Unit("joint", list(spec.subtasks), tuple(team))
        steps = [SeqStep(r, a, t, "joint") for (r, a), t in zip(actions, attribute(actions, unit, start),
                                                                strict=True)]
        try:
            grounded, _ = ground_sequence(start, steps)
        except StepFailure as exc:
            raise PlanValidationError(f"Fast Downward's joint plan does not run in the simulator: {exc}") from None
        try:
            plan = self._finish(grounded, {}, team, start, goal, "formal")
        except _Invalid as exc:
            notes.append(f"joint plan's partial order failed ({exc}): robots take turns")
            try:
                plan = self._finish(grounded, {}, team, start, goal, "sequential")
            except _Invalid as again:
                raise PlanValidationError(f"the joint plan fails in the simulator: {again}") from None
        return plan.model_copy(update={"joint": True})

    # ---- no-HP: concatenation -----------------------------------------------------------
    def _concatenated(self, spec: TaskSpec, start: WorldState, team: list[str],
                      needs: Mapping[str, list[Need]], notes: list[str]) -> MergedPlan:
        load: dict[str, float] = {r: 0.0 for r in team}
        assigned = {a.subtask: a.robots for a in allocate(list(spec.subtasks), needs, start, team, load)}
        levels = _levels(spec)
        plans: dict[str, list[SeqStep]] = {}
        bases: dict[str, WorldState] = {}
        used: set[str] = set()  # robots with an earlier subtask: they start elsewhere
        for level in levels:
            problems = []
            for t in level:
                bases[t.id] = _lenient_state(start, [s for d in ancestors(spec, t.id) for s in plans.get(d, [])])
                away = [r for r in assigned[t.id] if r in used]
                used.update(assigned[t.id])
                problems.append(build_problem(bases[t.id], t.goal, assigned[t.id], name=t.id, elsewhere=away))
            results = self._solve(problems)
            for t, problem, result in zip(level, problems, results, strict=True):
                if not result.solved:
                    problem = build_problem(bases[t.id], t.goal, team, name=t.id, narrow=False, elsewhere=team)
                    result = self._solve([problem])[0]
                    if not result.solved:
                        raise self._unsolvable(t.id, t.goal, bases[t.id], team)
                plans[t.id] = [SeqStep(r, a, t.id, t.id) for r, a in polish(problem.decode(result.plan))]
        grounded: list[GroundedStep] = []
        for t in (t for level in levels for t in level):
            try:
                g, _ = ground_sequence(bases[t.id], plans[t.id])
            except StepFailure as exc:
                raise PlanValidationError(f"subtask {t.id}'s plan does not run: {exc}") from None
            grounded.extend(g)
        deps = {t.id: tuple(ancestors(spec, t.id)) for t in spec.subtasks}
        if not self.config.validate:
            waits = order(grounded, deps, "concatenate")
            plan = assemble(grounded, waits, team, deps)
            return estimate(plan, {s.id: g.seconds for s, g in zip(plan.steps, grounded, strict=True)})
        try:
            return self._finish(grounded, deps, team, start, spec.goal(), "concatenate")
        except _Invalid as exc:
            notes.append(f"the concatenated plan failed in the simulator ({exc}): planned as one joint problem")
            return self._joint(spec, start, team, notes)

    # ---- merge + validate ---------------------------------------------------------------
    def _finish(self, grounded: Sequence[GroundedStep], deps: Mapping[str, Sequence[str]], team: Sequence[str],
                start: WorldState, goal: Goal, mode: MergeMode, dependencies: DependencyWaits | None = None
                ) -> MergedPlan:
        """Order, assemble and validate. ``dependencies`` replaces the whole-unit waits
        ``deps`` implies (the causal subtask dependencies)."""
        waits = order(grounded, deps, mode, dependency_waits=None if dependencies is None else dependencies.preds)
        plan = assemble(grounded, waits, team, deps, None if dependencies is None else dependencies.reasons)
        if not self.config.validate:
            return estimate(plan, {s.id: g.seconds for s, g in zip(plan.steps, grounded, strict=True)})
        timing = simulate(plan, start, goal)
        if not timing.ok:
            index = next((k for k, s in enumerate(plan.steps) if s.id == timing.failed_step), None)
            raise _Invalid(timing.failure, index)
        return with_times(plan, timing)


# ---- helpers ------------------------------------------------------------------------------

def _group_dependencies(spec: TaskSpec, unit_of: Mapping[str, str]) -> dict[str, tuple[str, ...]]:
    """Planning unit -> the units holding its subtasks' (transitive) dependencies."""
    out: dict[str, set[str]] = {}
    for t in spec.subtasks:
        u = unit_of.get(t.id)
        if u is None:
            continue
        out.setdefault(u, set()).update(unit_of[d] for d in ancestors(spec, t.id) if d in unit_of)
    return {u: tuple(sorted(d - {u})) for u, d in out.items()}


def _kind(ref: ObjectRef, state: WorldState) -> str:
    """What an object reference is about, as a type (``Egg_1`` and ``Egg`` alike)."""
    if ref.id is not None:
        o = state.objects.get(ref.id)
        return o.type if o is not None else ref.id
    return "|".join(sorted(ref.types))


def _levels(spec: TaskSpec) -> list[list[Subtask]]:
    """Subtasks by dependency depth (each level only depends on earlier ones)."""
    depth: dict[str, int] = {}

    def d(sid: str) -> int:
        if sid not in depth:
            deps = spec.subtask(sid).depends_on
            depth[sid] = 1 + max((d(x) for x in deps), default=-1)
        return depth[sid]

    levels: dict[int, list[Subtask]] = {}
    for t in spec.subtasks:
        levels.setdefault(d(t.id), []).append(t)
    return [levels[k] for k in sorted(levels)]


def _lenient_state(start: WorldState, steps: Sequence[SeqStep]) -> WorldState:
    """The state after ``steps``, skipping those that cannot run (no validation: the
    no-HP ablation plans each subtask from what its dependencies *probably* leave)."""
    s = start.copy()
    for st in steps:
        if check_action(s, st.robot, st.action) is None:
            apply_action(s, st.robot, st.action)
    return s

