"""The stage wiring of every mode of the paper's Tables 1 and 2 (see :mod:`emboteam.pipeline`).

Each mode is a choice of front end, planner configuration and executor; the parts are the
same packages everywhere, so an ablation differs from the full system only in the part it
ablates.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import replace
from functools import cache

from emboteam.bench.task import BenchTask
from emboteam.environments import ExecutionEnvironment, make_environment
from emboteam.errors import EmboTeamError
from emboteam.exec import Executor, parse_joins, planner_replanner, run_linear, run_sequences
from emboteam.exec.episode import Episode
from emboteam.exec.result import ExecutionResult
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.llm.client import LLMClient, make_client
from emboteam.pddl.domain import DomainError, step_literals
from emboteam.pddl.errors import PlanningError
from emboteam.pddl.literal import Literal
from emboteam.pddl.runner import PlannerInput
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.reading import Reading
from emboteam.pfg.scripted import scripted_action_lists
from emboteam.pfg.taskspec import TaskSpec
from emboteam.pipeline import RunConfig, initial_state, score
from emboteam.sim.rules import apply_action, check_action
from emboteam.sim.simulator import Simulator
from emboteam.world.actions import Action
from emboteam.world.goals import Goal
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene, load_scene
from emboteam.world.state import WorldState


class ModeConfigError(EmboTeamError):
    """A mode/front-end combination that cannot run (e.g. ``--frontend llm`` without ``--llm``)."""


#: the planner configuration of each mode. LaMMA-P: optimal Fast Downward calls per subtask,
#: one at a time, no cache, sub-plans concatenated without validation and executed
#: linearly. LaMMA-P's ``seq-opt-lmcut`` rejects this domain (LM-cut supports neither
#: axioms nor conditional effects: Fast Downward exit 34), so it runs ``astar(hmax())``,
#: the admissible search that does (docs/planning.md).
PLANNER_OF_MODE: dict[str, PlannerConfig] = {
    "full": PlannerConfig(),
    "no-btc": PlannerConfig(),
    "no-hp": PlannerConfig(validate=False, merge="concatenate"),
    "lamma-p": PlannerConfig(alias="astar(hmax())", workers=1, validate=False, merge="concatenate"),
}


@cache
def planner_for(mode: str, planner_input: PlannerInput = "sas") -> HybridPlanner:
    """One planner per mode and process, so its plan cache serves every episode."""
    return HybridPlanner(replace(PLANNER_OF_MODE[mode], planner_input=planner_input))


@cache
def offline_frontend() -> OfflineFrontend:
    """One parser per process: building its lexicon and spelling caches takes ~0.1 s."""
    return OfflineFrontend()


def make_llm(cfg: RunConfig) -> LLMClient | None:
    if cfg.llm is None:
        if cfg.frontend in ("llm", "hybrid"):
            raise ModeConfigError(f"--frontend {cfg.frontend} needs --llm PROVIDER:MODEL[@BASE_URL]")
        return None
    return make_client(cfg.llm, timeout=cfg.llm_timeout, record_dir=cfg.llm_record, seed=cfg.seed)


def understand(task: BenchTask, cfg: RunConfig, scene: Scene, state: WorldState,
               team: Sequence[RobotProfile], llm: LLMClient | None,
               notes: list[str] | None = None) -> TaskSpec:
    """The PFG: the instruction as a TaskSpec, by the configured front end. ``notes``, if
    given, receives what the front end could not read or read with doubt (for the user)."""
    if cfg.frontend == "oracle":
        from emboteam.pfg.oracle import OracleFrontend

        if not task.goal.conditions:
            raise ModeConfigError("the oracle front end needs a task with a ground-truth goal")
        return OracleFrontend(task.goal).decompose(task.instruction, scene, state, team)
    if cfg.frontend == "llm":
        from emboteam.pfg.llm_frontend import LLMFrontend

        assert llm is not None
        return LLMFrontend(llm).decompose(task.instruction, scene, state, team)
    if cfg.frontend == "hybrid":
        from emboteam.pfg.hybrid import HybridFrontend
        from emboteam.pfg.llm_frontend import LLMFrontend

        assert llm is not None
        planner = planner_for(cfg.mode)
        # one feedback round (at most two calls per doubtful task): the draft stands after
        # it, and a model that cannot fix its answer once rarely does twice. An LLM-written
        # or corrected spec must plan: the planner's error is fed back (its plan is cached
        # for plan_spec)
        hybrid = HybridFrontend(llm, offline_frontend().parse, when=cfg.llm_when,
                                llm=LLMFrontend(llm, repair_rounds=1), review_rounds=1)
        return hybrid.decompose(task.instruction, scene, state, team,
                                validate=lambda spec: _plans(planner, spec, state))
    reading = offline_frontend().parse(task.instruction, scene, state, team)
    if notes is not None:
        notes.extend(reading_notes(reading))
    return reading.spec


def reading_notes(reading: Reading) -> list[str]:
    """A reading's notes and unsure conditions, one line each, as the user sees them."""
    return [*(str(n) for n in reading.notes),
            *(f"unsure {c}: chosen with doubt" for c in reading.unsure)]


def _plans(planner: HybridPlanner, spec: TaskSpec, state: WorldState) -> None:
    planner.plan(spec, state)


def plan_spec(spec: TaskSpec, cfg: RunConfig, task: BenchTask, scene: Scene, state: WorldState,
              team: Sequence[RobotProfile], llm: LLMClient | None) -> tuple[TaskSpec, MergedPlan]:
    """The HP. With an LLM front end in the full system, the paper's LLM validation stage
    reviews the TaskSpec first, and one planner error goes back to the LLM for repair."""
    planner = planner_for(cfg.mode, cfg.planner_input)
    if llm is not None and cfg.frontend == "llm" and cfg.mode == "full":
        from emboteam.hp.llm_stages import review_spec

        spec = review_spec(llm, spec, task.instruction, scene, state, team).spec
    try:
        plan = planner.plan(spec, state)
    except PlanningError as exc:
        if llm is None or cfg.frontend != "llm":
            raise
        from emboteam.pfg.llm_frontend import LLMFrontend

        spec = LLMFrontend(llm).repair(spec, str(exc), scene, state, team)
        plan = planner.plan(spec, state)
    if llm is not None and cfg.llm_merge:
        # the paper's LLM merge: orderings it proposes become dependencies if they keep the
        # subtasks acyclic, and the formal merge plans and validates the result
        from emboteam.hp.llm_stages import apply_orderings, propose_orderings
        from emboteam.views import plan_summary

        ordered = apply_orderings(spec, propose_orderings(llm, spec, task.instruction, plan_summary(plan)))
        if ordered != spec:
            spec, plan = ordered, planner.plan(ordered, state)
    return spec, plan


def action_lists(task: BenchTask, cfg: RunConfig, scene: Scene, state: WorldState,
                 team: Sequence[RobotProfile], llm: LLMClient | None) -> dict[str, list[Action]]:
    """Per-robot action lists written directly (no PDDL): by the LLM, or without one by the
    scripted stand-in over the goal the front end understood."""
    if llm is not None and cfg.frontend == "llm":
        from emboteam.pfg.action_lists import LLMActionListFrontend

        return LLMActionListFrontend(llm).generate(task.instruction, scene, state, team)
    goal = understand(task, cfg, scene, state, team, None).goal()
    return scripted_action_lists(goal, state, team)


def literal_plan(lists: Mapping[str, Sequence[Action]], state: WorldState) -> MergedPlan:
    """Action lists as a plan whose steps carry their PDDL pre/post literals (for the
    no-pfg-hp ablation, which compiles LLM-written lists to behavior trees). Literals are
    grounded on a forward simulation of the lists in order; an action the forward state
    rejects keeps empty literals (its tree still runs the action with recovery)."""
    forward = state.copy()
    steps: list[PlanStep] = []
    queues = {r: list(a) for r, a in lists.items()}
    index = dict.fromkeys(lists, 0)
    while any(queues.values()):  # round-robin, the order concurrent robots would interleave
        for robot, queue in queues.items():
            if not queue:
                continue
            action = queue.pop(0)
            index[robot] += 1
            pre: tuple[Literal, ...] = ()
            post: tuple[Literal, ...] = ()
            if check_action(forward, robot, action) is None:
                try:
                    pre, post = step_literals(robot, action, forward)
                except DomainError:
                    pre, post = (), ()
                apply_action(forward, robot, action)
            steps.append(PlanStep(id=f"{robot}.{index[robot]}", robot=robot, action=action, subtask="s1",
                                  pre=pre, post=post))
    return MergedPlan(robots=tuple(lists), steps=tuple(steps))


def execute(plan: MergedPlan, goal: Goal, cfg: RunConfig, scene: Scene, state: WorldState,
            team: Sequence[RobotProfile], *, reactive: bool, replan: bool,
            finish_plan: bool = False) -> tuple[ExecutionResult, ExecutionEnvironment]:
    sim = make_environment(cfg, scene, team, state)  # the simulator, or AI2-THOR (--env)
    joins = parse_joins(cfg.joins, [p.name for p in team])
    messages = cfg.fault_config().messages
    if not reactive:
        return run_linear(sim, plan, goal, time_limit=cfg.time_limit, joins=[(j.profile, j.at) for j in joins],
                          messages=messages, seed=cfg.seed), sim
    replanner = planner_replanner(planner_for("full", cfg.planner_input)) if replan else None
    executor = Executor(sim, plan, goal, replanner=replanner, joins=joins, seed=cfg.seed,
                        time_limit=cfg.time_limit, finish_plan=finish_plan, messages=messages)
    return executor.run(), sim


def run_mode(task: BenchTask, cfg: RunConfig, llm: LLMClient | None = None) -> Episode:
    """Plan and execute one task in ``cfg.mode``; typed errors propagate to the caller.
    ``llm``: the client to use (the caller keeps it to report the usage of a failed
    episode); made from ``cfg`` when None."""
    scene = load_scene(task.floor_plan)
    state, team = initial_state(task)
    prepared = None
    if cfg.disturbance.any:  # breakdowns, joins, moves, message faults placed in this task
        from emboteam.bench.ceiling import prepare

        prepared = prepare(task, cfg, state, team)
        cfg = prepared.cfg
    llm = llm if llm is not None else make_llm(cfg)
    t0 = time.perf_counter()
    spec: TaskSpec | None = None
    notes: list[str] = []
    if cfg.mode in ("no-pfg-hp", "smart-llm"):
        lists = action_lists(task, cfg, scene, state, team, llm)
        plan_seconds = time.perf_counter() - t0
        goal = task.goal if task.goal.conditions else Goal(conditions=())
        if cfg.mode == "smart-llm":
            sim = make_environment(cfg, scene, team, state)
            joins = [(j.profile, j.at) for j in parse_joins(cfg.joins, [p.name for p in team])]
            result = run_sequences(sim, lists, goal, time_limit=cfg.time_limit, joins=joins)
        else:
            result, sim = execute(literal_plan(lists, state), goal, cfg, scene, state, team,
                                  reactive=True, replan=False)
    else:
        spec = understand(task, cfg, scene, state, team, llm, notes)
        spec, plan = plan_spec(spec, cfg, task, scene, state, team, llm)
        plan_seconds = time.perf_counter() - t0
        reactive = cfg.mode in ("full", "no-hp")
        result, sim = execute(plan, spec.goal(), cfg, scene, state, team, reactive=reactive,
                              replan=cfg.mode == "full",
                              finish_plan=any(not s.final for s in spec.subtasks))
    truth = task.goal if task.goal.conditions else (spec.goal() if spec else Goal(conditions=()))
    success, gcr, conditions = score(truth, sim.state)
    fields = result.episode_fields()
    fields.update(success=success, gcr=gcr, conditions=conditions)
    error = result.error
    if prepared is not None:
        from emboteam.bench.ceiling import disturbance_outcome

        assert isinstance(sim, Simulator)  # disturbances are the simulator's (check_thor_config)
        outcome = disturbance_outcome(task, prepared, sim, result, success, state)
        fields["disturbance"] = outcome
        if not success and outcome.savable is False and error is None:
            error = outcome.ceiling  # the typed reason an unsavable episode ended with
    return Episode(
        task=task.key, instruction=task.instruction, floor_plan=task.floor_plan,
        robots=tuple(sorted(sim.state.robots)), category=task.category, mode=cfg.mode,
        frontend=cfg.frontend, llm=cfg.llm, seed=cfg.seed, faults=cfg.fault_config(),
        fault_level=cfg.fault_level, env=cfg.env,
        llm_calls=llm.usage.calls if llm else 0, tokens=llm.usage.tokens if llm else 0,
        plan_seconds=round(plan_seconds, 4), taskspec=spec, notes=tuple(notes),
        error=error, **fields,
    )


__all__ = ["PLANNER_OF_MODE", "ModeConfigError", "planner_for", "run_mode"]
