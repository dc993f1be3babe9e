"""The parts of an episode and their wiring by mode (the table is :mod:`emboteam.mode_table`).

Each stage takes one :class:`EpisodeContext` (task, configuration, scene, initial state,
team, LLM client) instead of loose parameters. An ablation differs from the full system
only in the part the mode table swaps.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Protocol, cast

from emboteam.config import RunConfig
from emboteam.environments import ExecutionEnvironment, make_environment
from emboteam.errors import EmboTeamError
from emboteam.exec import Executor, parse_joins, planner_replanner, run_linear, run_sequences
from emboteam.exec.ceiling import Prepared, disturbance_outcome, prepare
from emboteam.exec.episode import Episode, episode_header, score
from emboteam.exec.executor import ExecutorSettings
from emboteam.exec.nav_check import check_motion
from emboteam.exec.result import ExecutionResult
from emboteam.exec.trace import TraceEvent
from emboteam.hp.feasible import Feasible, plan_feasible
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.hp.planner import HybridPlanner
from emboteam.llm.client import LLMClient, make_client
from emboteam.mode_table import ModeConfigError, planner_for, wiring
from emboteam.pddl.domain import DomainError, step_literals
from emboteam.pddl.errors import PlanningError
from emboteam.pddl.literal import Literal
from emboteam.pfg.clarification import Clarification, ClarifyHook
from emboteam.pfg.close_after_use import close_after_use
from emboteam.pfg.parser import offline_frontend
from emboteam.pfg.reading import Reading
from emboteam.pfg.scripted import scripted_action_lists
from emboteam.pfg.taskspec import TaskSpec
from emboteam.sim.rules import apply_action, check_action
from emboteam.sim.simulator import Simulator
from emboteam.sim.traffic import Traffic
from emboteam.task import EpisodeTask
from emboteam.world.actions import Action
from emboteam.world.checker import check_goal
from emboteam.world.goals import Goal
from emboteam.world.navfit import check_reachable
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene, load_scene
from emboteam.world.state import WorldState


@dataclass(frozen=True)
class EpisodeContext:
    """What every stage of one episode reads: built once, handed down."""

    task: EpisodeTask
    cfg: RunConfig
    scene: Scene
    state: WorldState
    team: tuple[RobotProfile, ...]
    llm: LLMClient | None
    #: settles an LLM front end's clarification (``--clarify``); None: it ends the episode
    clarify: ClarifyHook | None = None

    @classmethod
    def open(cls, task: EpisodeTask, cfg: RunConfig, llm: LLMClient | None = None) -> EpisodeContext:
        """The context of ``task``: its scene and initial state, the LLM made from ``cfg``
        unless given."""
        team = task.team()
        return cls(task=task, cfg=cfg, scene=load_scene(task.floor_plan), state=task.initial_state(),
                   team=team, llm=llm if llm is not None else make_llm(cfg),
                   clarify=_ask_on_terminal if cfg.clarify else None)


def _ask_on_terminal(clarification: Clarification) -> str | None:
    """``--clarify`` for the LLM front ends: the model's question goes to the person (one
    flag for both: the offline reader's close candidates are settled in :func:`understand`)."""
    import sys

    from emboteam.pfg.clarification import ask_terminal

    return ask_terminal(clarification, sys.stdin, sys.stderr)


def make_llm(cfg: RunConfig) -> LLMClient | None:
    if cfg.llm is None:
        if cfg.frontend in ("llm", "hybrid"):
            raise ModeConfigError(f"--frontend {cfg.frontend} needs --llm PROVIDER:MODEL[@BASE_URL]")
        return None
    return make_client(cfg.llm, timeout=cfg.llm_timeout, record_dir=cfg.llm_record, seed=cfg.seed)


def understand(ctx: EpisodeContext, notes: list[str] | None = None,
               readings: list[Reading] | None = None) -> TaskSpec:
    """The PFG: the instruction as a TaskSpec, by the configured front end. ``notes``, if
    given, receives what the front end could not read or read with doubt (for the user);
    ``readings`` the offline reading itself (its candidates and unexplained mentions)."""
    task, cfg, llm = ctx.task, ctx.cfg, ctx.llm
    args = (task.instruction, ctx.scene, ctx.state, ctx.team)
    if cfg.frontend == "oracle":
        from emboteam.pfg.oracle import OracleFrontend

        if task.ground_truth is None:
            raise ModeConfigError("the oracle front end needs a task with a ground-truth goal")
        return OracleFrontend(task.ground_truth).decompose(*args)
    if cfg.frontend == "llm":
        from emboteam.pfg.llm_frontend import LLMFrontend

        assert llm is not None
        return LLMFrontend(llm, avoid_set=example_set(task)).decompose(*args, clarify=ctx.clarify)
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
                                llm=LLMFrontend(llm, repair_rounds=1, avoid_set=example_set(task)), review_rounds=1,
                                clarify=ctx.clarify)
        reading = hybrid.read(*args, validate=lambda spec: _plans(planner, spec, ctx.state))
    else:
        reading = offline_frontend().parse(*args)
    if cfg.clarify and cfg.frontend != "hybrid":
        import sys

        from emboteam.pfg.clarify import settle
        from emboteam.pfg.offline.doubts.priors import load_priors

        reading = settle(reading, load_priors().close_margin, sys.stdin, sys.stdout)
    if readings is not None:
        readings.append(reading)
    if notes is not None:
        notes.extend(reading_notes(reading))
    return reading.spec


def example_set(task: EpisodeTask) -> str:
    """The set a task comes from, as the worked-example pool names it (``blind_r20``,
    ``mace-thor``): the LLM front ends never show an example of the task's own set."""
    suite = str(getattr(task, "suite", ""))
    if suite.startswith("smart-llm:"):
        parts = [p for p in suite.removeprefix("smart-llm:").replace("\\", "/").split("/") if p]
        named = [p for p in parts if p.startswith("blind_r")]
        return named[-1] if named else (parts[-1] if parts else "")
    return suite


def reading_notes(reading: Reading) -> list[str]:
    """A reading's notes and unsure conditions, one line each, as the user sees them."""
    return [*(str(n) for n in reading.notes),
            *(f"unsure {c}: chosen with doubt" for c in reading.unsure)]


def reading_fields(reading: Reading | None) -> dict[str, object]:
    """What an episode records of the offline reading: the mentions nothing explained and
    the candidates considered, with their scores and the doubts each settles."""
    if reading is None:
        return {}
    return {"unexplained": reading.unexplained, "candidates": tuple(c.to_json() for c in reading.candidates)}


def _plans(planner: HybridPlanner, spec: TaskSpec, state: WorldState) -> None:
    planner.plan(spec, state)


def plan_summary(plan: MergedPlan) -> str:
    """The plan as text for the LLM merge prompt: per robot, its actions with subtask and waits."""
    lines = []
    for robot in plan.robots:
        steps = [f"{s.action} [{s.subtask}{'; after ' + ','.join(s.after) if s.after else ''}]"
                 for s in plan.for_robot(robot)]
        lines.append(f"{robot}: " + " -> ".join(steps))
    return "\n".join(lines)


def plan_spec(ctx: EpisodeContext, spec: TaskSpec, reading: Reading | None = None,
              feasible: list[Feasible] | None = None) -> tuple[TaskSpec, MergedPlan]:
    """The HP. With an LLM front end in the full system, the paper's LLM validation stage
    reviews the TaskSpec first, and one planner error goes back to the LLM for repair.
    The offline or hybrid reading that cannot be planned gives way to its next candidate
    that plans, or to its largest part that does (:mod:`emboteam.hp.feasible`); what was
    taken and left out goes to ``feasible``."""
    cfg, llm = ctx.cfg, ctx.llm
    args = (ctx.scene, ctx.state, ctx.team)
    planner = planner_for(cfg.mode, cfg.planner_input, cfg.schedule)
    if llm is not None and cfg.frontend == "llm" and wiring(cfg.mode).llm_review:
        from emboteam.hp.llm_stages import review_spec

        spec = review_spec(llm, spec, ctx.task.instruction, *args, avoid_set=example_set(ctx.task)).spec
    try:
        if cfg.frontend in ("offline", "hybrid"):
            spec, plan = _plan_reading(ctx, planner, spec, reading, feasible)
        else:
            # a reading's fallback only: the LLM repairs its own spec instead (below), and
            # the oracle's ground-truth goal is planned whole (its errors measure the planner)
            check_reachable(spec.goal(), ctx.scene)  # an object beyond the grid's reach: exit 2
            plan = planner.plan(spec, ctx.state)
    except PlanningError as exc:
        if llm is None or cfg.frontend != "llm":
            raise
        from emboteam.pfg.llm_frontend import LLMFrontend

        spec = LLMFrontend(llm, avoid_set=example_set(ctx.task)).repair(spec, str(exc), *args)
        plan = planner.plan(spec, ctx.state)
    if llm is not None and cfg.llm_merge:
        # the paper's LLM merge: orderings it proposes become dependencies if they keep the
        # subtasks acyclic, and the formal merge plans and validates the result
        from emboteam.hp.llm_stages import apply_orderings, propose_orderings

        ordered = apply_orderings(spec, propose_orderings(llm, spec, ctx.task.instruction, plan_summary(plan)))
        if ordered != spec:
            spec, plan = ordered, planner.plan(ordered, ctx.state)
    return spec, plan


def _plan_reading(ctx: EpisodeContext, planner: HybridPlanner, spec: TaskSpec, reading: Reading | None,
                  feasible: list[Feasible] | None) -> tuple[TaskSpec, MergedPlan]:
    """A reading planned, or its next candidate or largest part that plans
    (:func:`~emboteam.hp.feasible.plan_feasible`); what was taken goes to ``feasible``."""
    def checked_plan(s: TaskSpec) -> MergedPlan:
        # an object beyond the grid's reach: exit 2; a condition true already ("the vase stays
        # where it is") needs no robot to reach anything
        check_reachable(Goal(conditions=tuple(check_goal(s.goal(), ctx.state).unmet())), ctx.scene)
        return planner.plan(s, ctx.state)

    found = plan_feasible(spec, checked_plan, reading.candidates if reading else (), reading.unsure if reading else ())
    if feasible is not None:
        feasible.append(found)
    return found.spec, found.plan


def plan_task(ctx: EpisodeContext, notes: list[str] | None = None, readings: list[Reading] | None = None,
              feasible: list[Feasible] | None = None) -> tuple[TaskSpec, MergedPlan]:
    """PFG then HP: what ``emboteam plan`` shows and a planning mode executes. A reading
    the planner refuses gives way to a candidate or a part that plans (``feasible`` gets
    what was taken and left out; ``notes`` says so)."""
    read: list[Reading] = [] if readings is None else readings
    spec = understand(ctx, notes, read)
    if ctx.cfg.close_after_use and ctx.cfg.frontend in ("offline", "hybrid") and wiring(ctx.cfg.mode).close_after_use:
        # the offline reader's reading gets the team's habit; the ground truth says what it
        # wants closed, and an LLM's spec is its own answer (its review and repair see it as
        # written, and recorded cassettes replay)
        spec, added = close_after_use(spec, ctx.state, ctx.team)
        if notes is not None:
            notes.extend(added)
    found: list[Feasible] = [] if feasible is None else feasible
    spec, plan = plan_spec(ctx, spec, read[-1] if read else None, found)
    if notes is not None and found:
        notes.extend(found[-1].notes)
    return spec, plan


def action_lists(ctx: EpisodeContext) -> dict[str, list[Action]]:
    """Per-robot action lists written directly (no PDDL): by the LLM, or without one by the
    scripted stand-in over the goal the front end understood."""
    if ctx.llm is not None and ctx.cfg.frontend == "llm":
        from emboteam.pfg.action_lists import LLMActionListFrontend

        return LLMActionListFrontend(ctx.llm).generate(ctx.task.instruction, ctx.scene, ctx.state, ctx.team)
    goal = understand(replace(ctx, llm=None)).goal()
    return scripted_action_lists(goal, ctx.state, ctx.team)


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


def execute(ctx: EpisodeContext, plan: MergedPlan, goal: Goal, *,
            finish_plan: bool = False) -> tuple[ExecutionResult, ExecutionEnvironment]:
    """Run ``plan`` the way the mode executes: the compiled tree (replanning if the mode
    does) or linear lists."""
    cfg, team = ctx.cfg, ctx.team
    how = wiring(cfg.mode)
    sim = make_environment(cfg, ctx.scene, team, ctx.state)  # the simulator, or AI2-THOR (--env)
    joins = parse_joins(cfg.joins, [p.name for p in team])
    messages = cfg.fault_config().messages
    if how.execution == "linear":
        return run_linear(sim, plan, goal, time_limit=cfg.time_limit, joins=[(j.profile, j.at) for j in joins],
                          messages=messages, seed=cfg.seed), sim
    replanner = planner_replanner(planner_for("full", cfg.planner_input, cfg.schedule)) if how.replan else None
    settings = ExecutorSettings(time_limit=cfg.time_limit, seed=cfg.seed, finish_plan=finish_plan, messages=messages)
    executor = Executor(sim, plan, goal, replanner=replanner, joins=joins, settings=settings)
    return executor.run(), sim


def _run_lists(ctx: EpisodeContext, lists: dict[str, list[Action]],
               goal: Goal) -> tuple[ExecutionResult, ExecutionEnvironment]:
    if wiring(ctx.cfg.mode).execution == "sequences":
        cfg, team = ctx.cfg, ctx.team
        sim = make_environment(cfg, ctx.scene, team, ctx.state)
        joins = [(j.profile, j.at) for j in parse_joins(cfg.joins, [p.name for p in team])]
        return run_sequences(sim, lists, goal, time_limit=cfg.time_limit, joins=joins), sim
    return execute(ctx, literal_plan(lists, ctx.state), goal)


def run_mode(task: EpisodeTask, cfg: RunConfig, llm: LLMClient | None = None) -> Episode:
    """Plan and execute one task in ``cfg.mode``; typed errors propagate to the caller.
    ``llm``: the client to use (the caller keeps it to report the usage of a failed
    episode); made from ``cfg`` when None."""
    ctx = EpisodeContext.open(task, cfg, llm)
    prepared: Prepared | None = None
    if cfg.disturbance.any:  # breakdowns, joins, moves, message faults placed in this task
        prepared = prepare(task, cfg, ctx.state, ctx.team, planner_for("full"))
        ctx = replace(ctx, cfg=prepared.cfg)
    cfg, llm = ctx.cfg, ctx.llm
    t0 = time.perf_counter()
    spec: TaskSpec | None = None
    notes: list[str] = []
    readings: list[Reading] = []
    feasible: list[Feasible] = []
    if wiring(cfg.mode).planner is None:
        lists = action_lists(ctx)
        plan_seconds = time.perf_counter() - t0
        result, sim = _run_lists(ctx, lists, task.ground_truth or Goal(conditions=()))
    else:
        try:
            spec, plan = plan_task(ctx, notes, readings, feasible)
        except EmboTeamError as exc:
            # a goal read and then refused by the planner is a reading's failure: keep what
            # was read (notes, candidates, the model's overturn) for the failed episode
            exc.read_so_far = {"notes": tuple(notes), **reading_fields(readings[-1] if readings else None)}
            raise
        plan_seconds = time.perf_counter() - t0
        result, sim = execute(ctx, plan, spec.goal(), finish_plan=any(not s.final for s in spec.subtasks))
    # an instruction without a ground truth is scored on all it asked, a part not attempted included
    requested = feasible[-1].requested if feasible else spec
    truth = task.ground_truth or (requested.goal() if requested else Goal(conditions=()))
    success, gcr, conditions = score(truth, sim.state)
    fields = result.episode_fields()
    fields.update(success=success, gcr=gcr, conditions=conditions)
    fields.update(_motion_fields(sim, fields))
    error = result.error
    if prepared is not None:
        assert isinstance(sim, Simulator)  # disturbances are the simulator's (check_thor_config)
        outcome = disturbance_outcome(task, prepared, sim, result, success, ctx.state, planner_for("full"))
        fields["disturbance"] = outcome
        if not success and outcome.savable is False and error is None:
            error = outcome.ceiling  # the typed reason an unsavable episode ended with
    header = episode_header(task, cfg, sorted(sim.state.robots))
    return Episode.model_validate({
        **header, "llm_calls": llm.usage.calls if llm else 0, "tokens": llm.usage.tokens if llm else 0,
        "plan_seconds": round(plan_seconds, 4), "taskspec": spec, "notes": tuple(notes), "error": error,
        "not_attempted": feasible[-1].not_attempted if feasible else (),
        **reading_fields(readings[-1] if readings else None), **fields,
    })


class _OnGrid(Protocol):
    """An environment whose robots drive on the navigation grid."""

    traffic: Traffic

    def nav_record(self) -> dict[str, object]: ...


def _motion_fields(env: object, fields: dict[str, object]) -> dict[str, object]:
    """The robots' recorded motion, checked by the independent trace checker, and the
    trace with its ``nav`` event (environments without a grid record nothing)."""
    if not isinstance(getattr(env, "traffic", None), Traffic):  # the simulator and AI2-THOR's have one
        return {}
    grid_env = cast(_OnGrid, env)
    record = grid_env.nav_record()
    check = check_motion(record)
    old = fields.get("trace", ())
    trace: tuple[TraceEvent, ...] = tuple(old) if isinstance(old, tuple) else ()
    end = max([ev.t for ev in trace], default=0.0)
    event = TraceEvent(t=end, kind="nav", data={**record, "vertex_conflicts": len(check.vertex),
                                                "edge_conflicts": len(check.edge)})
    tr = grid_env.traffic
    return {"collisions": check.collisions, "nav_waits": tr.waits, "nav_replans": tr.replans,
            "path_seconds": round(tr.search_seconds, 4), "trace": (*trace, event)}


__all__ = ["EpisodeContext", "ModeConfigError", "action_lists", "execute", "make_llm",
           "plan_spec", "plan_task", "run_mode", "understand"]
