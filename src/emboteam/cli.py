"""The ``emboteam`` command (typer + rich). The contract is in docs/DESIGN.md:
``--json`` prints exactly one JSON object on stdout, logs go to stderr, and bad input
exits non-zero with a one-line error, never a traceback."""

from __future__ import annotations

import json
import os
import sys
from collections.abc import Callable, Sequence
from dataclasses import replace
from functools import wraps
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar, cast

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table
from rich.text import Text

from emboteam.errors import (
    EXIT_BAD_INPUT,
    EXIT_FAILED,
    EXIT_INTERNAL,
    EXIT_INTERRUPTED,
    EXIT_OK,
    EmboTeamError,
    exit_code_of,
)
from emboteam.pfg.clarification import ClarificationNeeded
from emboteam.terminal import error_object, one_line, printable, split_error
from emboteam.world.actions import Skill
from emboteam.world.navfit import nav_fit
from emboteam.world.robots import robot_profiles
from emboteam.world.scene import load_scene, scene_ids

if TYPE_CHECKING:
    from emboteam.config import EnvName, RunConfig
    from emboteam.task import EpisodeTask

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="EmboTeam: household instructions -> PDDL -> multi-robot plan -> reactive behavior trees.",
)
out = Console()
err = Console(stderr=True)


def _version(value: bool) -> None:
    if value:
        from importlib.metadata import PackageNotFoundError, version

        try:
            text = version("emboteam")
        except PackageNotFoundError:  # run from a source tree that was never installed
            text = "unknown (not installed)"
        sys.stdout.write(f"emboteam {text}\n")
        raise typer.Exit(EXIT_OK)


@app.callback()
def _options(
    _show_version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                       help="print the version and exit"),
    verbose: int = typer.Option(0, "--verbose", "-v", count=True,
                                help="log details on stderr: retries, import problems, progress (-vv: debug)"),
) -> None:
    """EmboTeam: household instructions -> PDDL -> multi-robot plan -> reactive behavior trees.

    Exit codes: 0 goal reached (run) / job done; 1 the episode ran and did not reach its
    goal; 2 bad input or configuration; 3 a service (the LLM endpoint) could not be used;
    70 internal error; 130 interrupted."""
    if verbose:
        from emboteam.logs import configure

        configure(verbose)

F = TypeVar("F", bound=Callable[..., Any])


def fail(message: str, code: int, *, as_json: bool = False, label: str = "error",
         error_type: str | None = None, extra: dict[str, Any] | None = None) -> typer.Exit:
    """Report a failure as the contract says (one line on stderr; with ``--json`` also one
    JSON object on stdout) and return the exit to raise. The message is escaped: it
    often holds brackets ('emboteam[ray]', the '[pfg]' stage tag) that Rich would eat as
    markup."""
    line = one_line(message)  # one line, control characters escaped, whatever the message holds
    if as_json:
        print_json({**error_object(message, code, error_type), **(extra or {})})
    err.print(f"[red]{label}:[/red] {escape(line)}", highlight=False, soft_wrap=True)
    return typer.Exit(code)


def cli_errors(fn: F) -> F:
    """Turn expected errors into one line on stderr and the exit code of their family
    (emboteam.errors.EXIT_CODES); every command has it, so new options inherit it."""

    @wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        as_json = bool(kwargs.get("as_json"))
        try:
            return fn(*args, **kwargs)
        except ClarificationNeeded as exc:  # the front end asked instead of guessing
            raise fail(str(exc), exc.exit_code, as_json=as_json,
                       error_type=type(exc).__name__, extra={"clarification": exc.clarification.to_json()}) from None
        except EmboTeamError as exc:
            raise fail(str(exc), exc.exit_code, as_json=as_json, error_type=type(exc).__name__) from None
        except (typer.Exit, typer.Abort):
            raise
        except KeyboardInterrupt:
            raise fail("interrupted", EXIT_INTERRUPTED, as_json=as_json, error_type="KeyboardInterrupt") from None
        except OSError as exc:  # the machine, not EmboTeam: a full disk, a file that vanished
            if os.environ.get("EMBOTEAM_DEBUG"):
                raise
            where = f" ({exc.filename})" if exc.filename else ""
            raise fail(f"{exc.strerror or exc}{where}", EXIT_BAD_INPUT, as_json=as_json,
                       error_type=type(exc).__name__) from None
        except Exception as exc:  # a bug: one line for the user, the traceback on request
            if os.environ.get("EMBOTEAM_DEBUG"):
                raise
            raise fail(f"{type(exc).__name__}: {exc} (set EMBOTEAM_DEBUG=1 for the traceback; please "
                       "report it)", EXIT_INTERNAL, as_json=as_json, label="internal error",
                       error_type=type(exc).__name__) from None

    return wrapper  # type: ignore[return-value]


def episode_exit_code(success: bool, error: str | None, not_attempted: int = 0) -> int:
    """``run``'s exit code: 0 goal reached; else the code of the error that ended the
    episode (recorded as ``"ClassName: message"``: 2 bad input, 3 a service), and 1 for an
    episode that ran and did not reach its goal, or did only part of it (``not_attempted``
    requested conditions the planner could not plan: never 0, whatever the truth says)."""
    if success and not not_attempted:
        return EXIT_OK
    if error:
        code = exit_code_of(error.split(":", 1)[0].strip())
        if code is not None and code != EXIT_OK:
            return code
    return EXIT_FAILED


def partly_done_message(left: Sequence[Any]) -> str:
    """What a partly done job says: the conditions the planner could not plan."""
    return (f"only the part of the goal that could be planned was done; {len(left)} requested "
            f"condition(s) not attempted: {'; '.join(str(n.condition) for n in left)}")


def partly_done(episode: Any) -> str | None:
    """The failure message of an episode that ran the part of its goal the planner could
    plan (None when nothing was left out)."""
    return partly_done_message(episode.not_attempted) if episode.not_attempted else None


def print_json(payload: Any) -> None:
    sys.stdout.write(json.dumps(payload, indent=None, default=str) + "\n")


@app.command()
@cli_errors
def scenes(as_json: bool = typer.Option(False, "--json", help="one JSON object on stdout")) -> None:
    """List the floor plans: id, room type, object count."""
    rows = []
    for fp in scene_ids():
        s = load_scene(fp)
        rows.append({"id": fp, "room": s.room, "objects": len(s.objects)})
    if as_json:
        print_json({"scenes": rows})
        return
    table = Table(title=f"{len(rows)} iTHOR floor plans")
    for col in ("id", "room", "objects"):
        table.add_column(col, justify="right" if col == "objects" else "left")
    for r in rows:
        table.add_row(str(r["id"]), str(r["room"]), str(r["objects"]))
    out.print(table)


@app.command()
@cli_errors
def scene(
    floor_plan: str = typer.Argument(..., help="FloorPlan6, 6 or FP6"),
    as_json: bool = typer.Option(False, "--json", help="one JSON object on stdout"),
) -> None:
    """List the objects of one floor plan."""
    s = load_scene(floor_plan)
    fit = nav_fit(s.floor_plan)
    if as_json:
        print_json({
            "id": s.floor_plan, "room": s.room, "navigation": fit.as_dict(),
            "objects": [
                {"id": o.id, "type": o.type, "thor_id": o.thor_id, "parent": o.parent,
                 "properties": sorted(o.properties), "mass": o.mass, "position": o.position,
                 "state": o.state.model_dump(exclude_defaults=True), "controls": list(o.controls)}
                for o in s.objects
            ],
        })
        return
    rows = []
    for o in s.objects:
        state = ", ".join(f"{k}={v}" for k, v in o.state.model_dump(exclude_defaults=True).items())
        if o.controls:
            state = (state + ", " if state else "") + "controls " + " ".join(o.controls)
        rows.append((o.id, o.parent or "", " ".join(sorted(o.properties)), f"{o.mass:g}" if o.mass else "", state))
    out.print(scene_table(f"{s.floor_plan} ({s.room}, {len(s.objects)} objects)", rows, out.width))
    out.print(Text(fit.summary()))  # wrapped at the terminal's width, as the table


#: below this terminal width ``scene`` folds properties, mass and state into one column
SCENE_WIDE = 140


def scene_table(title: str, rows: list[tuple[str, str, str, str, str]], width: int) -> Table:
    """The objects of a floor plan: five columns on a wide terminal; on a narrow one the
    ids and parents whole and one wrapped column of details, so nothing is cut."""
    if width >= SCENE_WIDE:
        table = Table(title=title)
        for col in ("id", "in/on", "properties", "mass", "state"):
            table.add_column(col, no_wrap=col in ("id", "in/on", "mass"), overflow="fold")
        for row in rows:
            table.add_row(*(Text(x) for x in row))
        return table
    table = Table(title=title, show_lines=False)
    table.add_column("id", no_wrap=True)
    table.add_column("in/on", no_wrap=True)
    table.add_column("properties · mass · state", overflow="fold")
    for oid, parent, props, mass, state in rows:
        details = " · ".join(x for x in (props, f"{mass} kg" if mass else "", state) if x)
        table.add_row(Text(oid), Text(parent), Text(details))
    return table


@app.command()
@cli_errors
def robots(as_json: bool = typer.Option(False, "--json", help="one JSON object on stdout")) -> None:
    """List the 28 robot profiles (SMART-LLM numbering): skills, mass capacity, speed."""
    profiles = robot_profiles()
    if as_json:
        print_json({"robots": [
            {"number": p.number, "name": p.name, "skills": [s.value for s in Skill if s in p.skills],
             "mass_capacity": p.mass_capacity, "speed": p.speed}
            for p in profiles
        ]})
        return
    table = Table(title="robot profiles (SMART-LLM numbering)")
    for col in ("#", "name", "max kg", "m/s", "skills"):
        table.add_column(col)
    for p in profiles:
        skills = " ".join(s.value.replace("Object", "") for s in Skill if s in p.skills)
        table.add_row(str(p.number), p.name, f"{p.mass_capacity:g}", f"{p.speed:g}", skills)
    out.print(table)


@app.command()
@cli_errors
def tasks(
    suite: str = typer.Option("mace-thor", "--suite", help="mace-thor | smart-llm:PATH"),
    as_json: bool = typer.Option(False, "--json", help="one JSON object on stdout"),
) -> None:
    """List a suite's tasks: id, floor plan, category, instruction."""
    from rich.padding import Padding

    loaded = _load_suite_quietly(suite)
    if as_json:
        print_json({"tasks": [
            {"id": t.key, "scene": t.floor_plan, "category": t.category, "instruction": t.instruction,
             "robots": list(t.robots), "goal": [str(c) for c in t.goal.conditions]}
            for t in loaded.tasks
        ]})
        return
    counts = ", ".join(f"{n} {cat}" for cat, n in loaded.categories().items())
    # ids, not SUITE/ID keys: a smart-llm key holds the whole path and would crowd out the
    # instruction (the title says how to name a task). A table while the short columns fit
    # whole with 30 columns left for the instruction; on a narrower terminal one entry per
    # task, the instruction on its own lines: nothing is cut either way.
    rows = [(printable(t.id), t.floor_plan, t.category, ",".join(t.robots), printable(t.instruction))
            for t in loaded.tasks]
    heads = ("id", "scene", "category", "robots")
    fixed = sum(max([len(h), *(len(r[i]) for r in rows)]) + 3 for i, h in enumerate(heads)) + 1
    title = Text(f"{loaded.name}: {len(loaded.tasks)} tasks ({counts}); a task is named {loaded.name}/ID")
    if fixed + 30 > out.width:
        out.print(title, style="bold")
        for task_id, fp, category, team, instruction in rows:
            out.print(Text(f"{task_id}  {fp}  {category}  robots {team}", style="bold"))
            out.print(Padding(Text(instruction), (0, 0, 0, 2)), overflow="fold")
        return
    table = Table(title=title)
    for col in heads:
        table.add_column(col, no_wrap=True)
    table.add_column("instruction", overflow="fold")
    for row in rows:
        table.add_row(*(Text(x) for x in row))
    out.print(table)


@app.command()
@cli_errors
def report(directory: Path = typer.Argument(..., help="a run's or a benchmark's --out DIR")) -> None:
    """(Re)build the HTML report of a run (report.html) or a benchmark (index.html)."""
    from emboteam.bench.runner import store_path, write_reports
    from emboteam.report import write_report

    if not directory.exists():
        raise EmboTeamError(f"{printable(str(directory))} does not exist: give the --out DIR of a run or a benchmark")
    if not directory.is_dir():
        raise EmboTeamError(f"{printable(str(directory))} is a file, not a folder: give the --out DIR of a run or a "
                            "benchmark")
    if store_path(directory).exists():  # a benchmark: tables and plots from its results store
        for path in write_reports(directory):
            out.print(f"wrote {path}", markup=False, highlight=False)
    skipped: list[str] = []
    pages = write_report(directory, problems=skipped)
    for problem in skipped:  # what was broken is listed, the rest is built
        err.print(f"[yellow]skipped:[/yellow] {escape(one_line(problem))}", highlight=False, soft_wrap=True)
    out.print(f"wrote {pages[-1]}" + (f" and {len(pages) - 1} episode report(s)" if len(pages) > 1 else ""),
              markup=False, highlight=False)


# ---- tasks, planning and runs ------------------------------------------------------
#: what --llm selects without --frontend and --llm-when, and what --llm-when is for hybrid
#: when not given: the mode of highest SR ceiling on the development rounds, measured with a
#: perfect-model stand-in (benchmarks/frontend_routing.py, docs/llm.md "Routing")
LLM_DEFAULT_FRONTEND = "llm"
HYBRID_DEFAULT_WHEN = "doubt"
FRONTEND_HELP = ("oracle (ground-truth goals) | offline (embedded parser; the default without --llm) | "
                 "llm (the LLM writes the goals, then reviews them: 2 calls a task, the highest SR ceiling, "
                 "0.981 on 2162 development tasks; the default with --llm) | hybrid (the parser reads, the "
                 "LLM reviews its reading: see --llm-when)")
LLM_WHEN_HELP = ("selects the hybrid front end. always: the LLM reviews every reading (1 call a task, SR "
                 "ceiling 0.968) | doubt: only readings the doubt detector flags (about 0.2 calls a task, "
                 "ceiling 0.964; a wrong reading it misses stands) | close: the model only scores the offline "
                 "reader's close readings (PMI, needs log-probabilities: llamacpp, openai completions), "
                 "never reviews; for a small local model whose review says ok to everything. Ceilings: "
                 "docs/llm.md")
FRONTENDS_CLI = ("oracle", "offline", "hybrid", "llm")


def _front_end(frontend: str | None, llm: str | None, llm_when: str | None) -> tuple[str, str]:
    """(front end, --llm-when). No --frontend: offline without --llm; with --llm,
    ``--llm-when W`` picks hybrid, and --llm alone :data:`LLM_DEFAULT_FRONTEND`."""
    if frontend is None and llm is None:
        frontend = "offline"
    elif frontend is None:
        frontend = "hybrid" if llm_when is not None else LLM_DEFAULT_FRONTEND
    return frontend, llm_when if llm_when is not None else HYBRID_DEFAULT_WHEN
LLM_HELP = "PROVIDER:MODEL[@BASE_URL]: openai, anthropic, llamacpp (MODEL = .gguf path), replay (MODEL = cassette dir)"


def probability(value: float) -> float:
    """``--faults P``: a probability in [0, 1]; click's range check lets ``nan`` through and
    would tell ``inf`` it "should be <= 1"."""
    import math

    if not math.isfinite(value) or not 0.0 <= value <= 1.0:
        raise typer.BadParameter(f"{value:g} is not a probability: give a number in [0, 1], e.g. 0.2")
    return value


def _resolve_task(target: str, scene_fp: str | None, robots_list: str | None) -> EpisodeTask:
    """TASK (SUITE/ID) or an instruction with --scene and --robots."""
    from emboteam.bench.suites import get_task
    from emboteam.task import Instruction

    if scene_fp is not None or robots_list is not None:
        if scene_fp is None or robots_list is None:
            raise EmboTeamError("an instruction needs both --scene FLOORPLAN and --robots LIST")
        if printable(target) != target:  # a terminal escape pasted in says nothing to the parser
            raise EmboTeamError(f"the instruction '{printable(target)}' holds control characters: remove them")
        return Instruction.typed(target, scene_fp, robots_list)
    if len(target.split()) > 1:  # task ids have no spaces: this is an instruction
        raise EmboTeamError(f"the instruction '{printable(target)}' needs --scene FLOORPLAN and --robots LIST "
                            "(or give a task SUITE/ID, e.g. mace-thor/fp1-toast)")
    return get_task(target)


PLANNER_INPUT_HELP = ("what Fast Downward reads: sas (our own grounded task, search binary only; default) "
                      "| pddl (its driver and translator)")


def _with_planner_input(cfg: Any, planner_input: str, schedule: str = "fast", leave_open: bool = False) -> Any:
    """A RunConfig or BenchConfig with ``--planner-input``, ``--schedule`` and
    ``--leave-open`` set (checked here: one line)."""
    if planner_input not in ("sas", "pddl"):
        raise EmboTeamError(f"--planner-input takes sas or pddl, not {planner_input!r}")
    if schedule not in ("fast", "optimal"):
        raise EmboTeamError(f"--schedule takes fast or optimal, not {schedule!r}")
    return cfg.model_copy(update={"planner_input": planner_input, "schedule": schedule,
                                  "close_after_use": not leave_open})


LEAVE_OPEN_HELP = ("do not add the closing of a closed fridge, drawer or box the reading puts things into "
                   "(by default the team closes what it opens unless asked to leave it open)")
SCHEDULE_HELP = ("fast (default) | optimal: then CP-SAT over the whole schedule (who does what, in which order), "
                 "kept when shorter; up to ~10 s more per plan (docs/planning.md)")


# the backslash keeps rich from reading [ai2thor] as markup in --help
ENV_HELP = ("sim (the symbolic simulator) | ai2thor (a live AI2-THOR 5.x: pip install 'emboteam\\[ai2thor]', "
            "a display or Vulkan; docs/ai2thor.md)")


def _env(value: str) -> EnvName:
    if value == "sim":
        return "sim"
    if value == "ai2thor":
        return "ai2thor"
    raise EmboTeamError(f"unknown environment {value!r}: sim or ai2thor")


def _run_config(mode: str, frontend: str, llm: str | None, **kw: Any) -> RunConfig:
    from emboteam.config import MODES, RunConfig

    if mode not in MODES:
        raise EmboTeamError(f"unknown mode {mode!r}; modes: {', '.join(MODES)}")
    if frontend not in FRONTENDS_CLI:
        raise EmboTeamError(f"unknown front end {frontend!r}: {', '.join(FRONTENDS_CLI)}")
    if kw.get("llm_when", "doubt") not in ("doubt", "always", "close"):
        raise EmboTeamError(f"--llm-when takes doubt, always or close, not {kw['llm_when']!r}")
    return RunConfig(mode=mode, frontend=frontend, llm=llm, **kw)


def _load_suite_quietly(suite: str) -> Any:
    """A suite, its import problems summed up in one line on stderr (each is logged:
    ``emboteam -v`` lists them); a suite left with no task is bad input, one line too."""
    import logging

    from emboteam.bench.suites import load_suite

    loaded = load_suite(suite)
    log = logging.getLogger("emboteam.bench.import")
    for problem in loaded.problems:
        log.warning("%s", printable(problem))
    if loaded.problems:
        first = one_line(loaded.problems[0])
        count = len(loaded.problems)
        if not loaded.tasks:
            raise EmboTeamError(f"{printable(suite)}: no usable task; {count} problem(s) in its files, the first: "
                                f"{first} (emboteam -v lists them all)")
        err.print(f"[yellow]import:[/yellow] {escape(f'{count} problem(s) in the suite files left entries out, the first: {first} (emboteam -v lists them all)')}",
                  highlight=False, soft_wrap=True)
    return loaded


def _echo_task(task: EpisodeTask) -> None:
    """The header of ``plan`` and ``run``: the task and its instruction, as typed (control
    characters escaped, brackets kept)."""
    out.print(f"[bold]{escape(printable(task.key))}[/bold] {escape(task.floor_plan)}: "
              f"{escape(printable(task.instruction))}", highlight=False)


@app.command()
@cli_errors
def plan(
    target: str = typer.Argument(..., metavar="TASK|INSTRUCTION", help="SUITE/ID, or an instruction"),
    scene_fp: str | None = typer.Option(None, "--scene", help="floor plan of an instruction"),
    robots_list: str | None = typer.Option(None, "--robots", help="team of an instruction: 1,2,3"),
    frontend: str | None = typer.Option(None, "--frontend", help=FRONTEND_HELP),
    llm: str | None = typer.Option(None, "--llm", help=LLM_HELP),
    llm_when: str | None = typer.Option(None, "--llm-when", help=LLM_WHEN_HELP),
    llm_timeout: float = typer.Option(60.0, "--llm-timeout", help="seconds per LLM request"),
    as_json: bool = typer.Option(False, "--json", help="one JSON object on stdout"),
    planner_input: str = typer.Option("sas", "--planner-input", help=PLANNER_INPUT_HELP),
    schedule: str = typer.Option("fast", "--schedule", help=SCHEDULE_HELP),
    leave_open: bool = typer.Option(False, "--leave-open", help=LEAVE_OPEN_HELP),
) -> None:
    """Decompose and plan a task (PFG + HP) without executing it."""
    import time

    from emboteam.hp.feasible import Feasible
    from emboteam.modes import EpisodeContext, plan_task
    from emboteam.views import plan_json, plan_table, spec_json, spec_table

    task = _resolve_task(target, scene_fp, robots_list)
    fe, when = _front_end(frontend, llm, llm_when)
    cfg = _run_config("full", fe, llm, llm_timeout=llm_timeout, llm_when=when)
    ctx = EpisodeContext.open(task, cfg)
    ctx = replace(ctx, cfg=_with_planner_input(cfg, planner_input, schedule, leave_open))
    client = ctx.llm
    t0 = time.perf_counter()
    notes: list[str] = []        # what the front end could not read, or read with doubt
    feasible: list[Feasible] = []    # the reading taken, what of it could not be planned
    spec, merged = plan_task(ctx, notes, feasible=feasible)
    seconds = time.perf_counter() - t0
    left = feasible[-1].not_attempted if feasible else ()
    code = EXIT_FAILED if left else EXIT_OK     # a plan of part of the goal is a partly done job
    if as_json:
        partial = error_object(partly_done_message(left), code, None) if left else {}
        print_json({"task": task.key, "instruction": task.instruction, "scene": task.floor_plan,
                    "subtasks": spec_json(spec), **plan_json(merged), "plan_seconds": round(seconds, 4),
                    "llm_calls": client.usage.calls if client else 0, "notes": notes,
                    "not_attempted": [n.model_dump() for n in left],
                    **{k: v for k, v in partial.items() if k != "success"}})
        raise typer.Exit(code)
    _echo_task(task)
    out.print(spec_table(spec))
    for note in notes:
        out.print(f"[yellow]note:[/yellow] {escape(one_line(note))}", highlight=False)
    for n in left:
        out.print(f"[red]not attempted:[/red] {escape(one_line(str(n)))}", highlight=False)
    out.print(plan_table(merged))
    out.print(f"planned in {seconds:.2f} s")
    raise typer.Exit(code)


@app.command()
@cli_errors
def run(
    target: str = typer.Argument(..., metavar="TASK|INSTRUCTION", help="SUITE/ID, or an instruction"),
    scene_fp: str | None = typer.Option(None, "--scene", help="floor plan of an instruction"),
    robots_list: str | None = typer.Option(None, "--robots", help="team of an instruction: 1,2,3"),
    frontend: str | None = typer.Option(None, "--frontend", help=FRONTEND_HELP),
    mode: str = typer.Option("full", "--mode", help="full | no-pfg-hp | no-hp | no-btc | no-avoidance | smart-llm | lamma-p"),
    llm: str | None = typer.Option(None, "--llm", help=LLM_HELP),
    llm_timeout: float = typer.Option(60.0, "--llm-timeout", help="seconds per LLM request"),
    llm_record: str | None = typer.Option(None, "--llm-record", help="record LLM calls into this cassette dir"),
    llm_merge: bool = typer.Option(False, "--llm-merge", help="the paper's LLM merge stage (one more call)"),
    llm_when: str | None = typer.Option(None, "--llm-when", help=LLM_WHEN_HELP),
    faults: float = typer.Option(0.0, "--faults", callback=probability, help="per-action failure probability"),
    seed: int = typer.Option(0, "--seed", help="seed of the fault injection"),
    join: list[str] = typer.Option([], "--join", help="PROFILE@SECONDS: a robot joins mid-run (repeatable)"),
    env: str = typer.Option("sim", "--env", help=ENV_HELP),
    out_dir: Path | None = typer.Option(None, "--out", help="write episode.json, trace.jsonl, report.html here"),
    as_json: bool = typer.Option(False, "--json", help="one JSON object on stdout"),
    planner_input: str = typer.Option("sas", "--planner-input", help=PLANNER_INPUT_HELP),
    clarify: bool = typer.Option(False, "--clarify", help="when the offline reading is close, or the LLM "
                                 "cannot tell, ask which end state was meant (numbered sentences; without a "
                                 "terminal the best reading)"),
    schedule: str = typer.Option("fast", "--schedule", help=SCHEDULE_HELP),
    leave_open: bool = typer.Option(False, "--leave-open", help=LEAVE_OPEN_HELP),
) -> None:
    """Plan and execute a task in the simulator; print the outcome and metrics."""
    from emboteam.exec import Join
    from emboteam.outputs import ensure_out_dir, write_error
    from emboteam.pipeline import check_config, run_episode
    from emboteam.views import episode_panel, plan_table, spec_table

    for flag, given in (("--llm-merge", llm_merge), ("--llm-record", llm_record is not None)):
        if given and llm is None:
            raise EmboTeamError(f"{flag} needs --llm PROVIDER:MODEL (without an LLM there is nothing to "
                                f"{'merge with' if flag == '--llm-merge' else 'record'})")
    task = _resolve_task(target, scene_fp, robots_list)
    fe, when = _front_end(frontend, llm, llm_when)
    cfg = _run_config(mode, fe, llm, llm_timeout=llm_timeout, llm_record=llm_record,
                      llm_merge=llm_merge, llm_when=when,
                      fault_level=faults, seed=seed, joins=tuple(join), env=_env(env),
                      clarify=clarify and not as_json)    # with --json the candidates are in the output
    cfg = _with_planner_input(cfg, planner_input, schedule, leave_open)
    for j in join:
        Join.parse(j)  # a typed error now rather than mid-run
    check_config(cfg)
    if out_dir is not None:
        ensure_out_dir(out_dir)  # before the run, not after it: a bad --out is bad input
    episode = run_episode(task, cfg)
    if out_dir is not None:
        from emboteam.report import save_episode_report

        try:
            episode.save(out_dir)
            save_episode_report(episode, out_dir)
        except OSError as exc:
            raise write_error(out_dir, exc) from None
    code = episode_exit_code(episode.success, episode.error, len(episode.not_attempted))
    error_type, message = split_error(episode.error) if episode.error else (None, None)
    if code not in (EXIT_OK, EXIT_FAILED) and message:  # bad input or a service: say it on stderr too
        err.print(f"[red]error:[/red] {escape(one_line(message))}", highlight=False, soft_wrap=True)
    if as_json:
        summary = episode.summary()
        if code != EXIT_OK:  # the error object every command prints (error, exit_code)
            failure = message or partly_done(episode) or "the episode ran and did not reach its goal"
            summary.update({k: v for k, v in error_object(failure, code, error_type).items() if k != "success"})
        print_json(summary)
        raise typer.Exit(code)
    _echo_task(task)
    if episode.taskspec is not None:
        out.print(spec_table(episode.taskspec))
    if episode.plan is not None:
        out.print(plan_table(episode.plan))
    out.print(episode_panel(episode, out_dir=str(out_dir) if out_dir else None))
    raise typer.Exit(code)


@app.command()
@cli_errors
def bench(
    suite: str = typer.Option(..., "--suite", help="mace-thor | smart-llm:PATH"),
    frontend: list[str] = typer.Option([], "--frontend", help=FRONTEND_HELP + " (repeatable)"),
    llm: str | None = typer.Option(None, "--llm", help=LLM_HELP),
    llm_when: str | None = typer.Option(None, "--llm-when", help=LLM_WHEN_HELP),
    llm_timeout: float = typer.Option(60.0, "--llm-timeout", help="seconds per LLM request"),
    ablation: list[str] = typer.Option([], "--ablation", help="full | no-pfg-hp | no-hp | no-btc | no-avoidance (repeatable)"),
    baseline: list[str] = typer.Option([], "--baseline", help="smart-llm | lamma-p (repeatable)"),
    faults: list[str] = typer.Option(["0"], "--faults", help="fault level(s): 0.2 or 0,0.1,0.2 (repeatable)"),
    seeds: int = typer.Option(1, "--seeds", min=1, help="seeds 0..N-1 per task"),
    breakdown: list[str] = typer.Option([], "--breakdown", help="WHO@WHEN: a robot stops for good, e.g. "
                                        "random@0.3 (drawn by the seed, at 30% of the nominal makespan), "
                                        "robot25@12s (that team member; a task whose team lacks it is "
                                        "not applicable) (repeatable)"),
    join: list[str] = typer.Option([], "--join", help="PROFILE@WHEN: a robot joins mid-run, e.g. 5@30 (at 30 s, "
                                   "as run has it), random@30% (a second unit of a team member's profile, at "
                                   "30% of the nominal makespan) (repeatable)"),
    moves: list[str] = typer.Option([], "--moves", help="WHAT@WHEN: someone moves an object the plan uses "
                                    "to a random valid place the team can get it back from (shut in a "
                                    "receptacle only when a working robot can open it), e.g. random@0.5, "
                                    "Apple_1@20s (a floor plan without it: not applicable) (repeatable)"),
    msg_loss: float = typer.Option(0.0, "--msg-loss", help="probability that a blackboard lock release is "
                                   "lost (the lock's lease then times out)"),
    msg_delay: float = typer.Option(0.0, "--msg-delay", help="up to this many simulated seconds late a robot "
                                    "reads another's sync flag"),
    workers: int = typer.Option(2, "--workers", min=1, help="parallel episodes"),
    executor: str = typer.Option("local", "--executor", help="local (process pool) | ray"),
    ray_address: str | None = typer.Option(None, "--ray-address", help="Ray cluster address (default: local)"),
    env: str = typer.Option("sim", "--env", help=ENV_HELP),
    out_dir: Path | None = typer.Option(None, "--out", help="results store, tables, plots, index.html "
                                        "(default: a new folder bench-out/SUITE_CONFIGURATION_TIME)"),
    resume: bool = typer.Option(False, "--resume", help="continue a killed run in --out DIR"),
    as_json: bool = typer.Option(False, "--json", help="one JSON summary object on stdout"),
    planner_input: str = typer.Option("sas", "--planner-input", help=PLANNER_INPUT_HELP),
    schedule: str = typer.Option("fast", "--schedule", help=SCHEDULE_HELP),
    leave_open: bool = typer.Option(False, "--leave-open", help=LEAVE_OPEN_HELP),
) -> None:
    """Run a suite in one or more modes, seeds and fault levels; tables, plots, an HTML index."""
    from emboteam.bench.disturbance_scope import split_applicable
    from emboteam.bench.jobs import BenchConfig, expand_jobs, modes_from_options, parse_fault_levels
    from emboteam.bench.runner import BenchInterrupted, run_bench
    from emboteam.bench.tables import bench_summary
    from emboteam.sim.disturbances import Disturbances

    loaded = _load_suite_quietly(suite)
    default_frontend, when = _front_end(None, llm, llm_when)
    frontends = frontend or [default_frontend]
    cfg = BenchConfig.build(
        suite=suite, modes=modes_from_options(ablation, baseline), frontends=frontends, llm=llm,
        seeds=seeds, fault_levels=parse_fault_levels(faults), workers=workers, executor=executor,
        disturbance=Disturbances.parse(breakdown=breakdown, join=join, moves=moves, msg_loss=msg_loss,
                                       msg_delay=msg_delay),
        ray_address=ray_address, out_dir=out_dir or BENCH_ROOT, resume=resume, env=_env(env), llm_timeout=llm_timeout,
        llm_when=when,
    )
    from emboteam.config import RunConfig
    from emboteam.pipeline import check_config

    if cfg.env != "sim":  # fails fast when AI2-THOR cannot start here, before any job
        check_config(RunConfig(env=cfg.env, fault_level=max(cfg.fault_levels), disturbance=cfg.disturbance))
    for f in cfg.frontends:
        check_config(RunConfig(frontend=f, llm=cfg.llm, llm_timeout=llm_timeout, llm_when=cfg.llm_when))
    cfg = _with_planner_input(cfg, planner_input, schedule, leave_open)
    tasks_run, not_applicable = split_applicable(cfg.disturbance, loaded.tasks)  # exit 2 if it fits none
    cfg = _bench_out(cfg, out_dir)
    out_dir = cfg.out_dir
    jobs = expand_jobs(cfg, tasks_run)
    try:
        episodes = run_bench(cfg, jobs, not_applicable=not_applicable)
    except BenchInterrupted as exc:
        raise fail(f"{exc}; continue with: {resume_command(exc.out_dir)}", exc.exit_code,
                   as_json=as_json, error_type=type(exc).__name__) from None
    from emboteam.report import write_report

    skipped: list[str] = []
    write_report(out_dir, refresh=False, problems=skipped)
    for problem in skipped:
        err.print(f"[yellow]skipped:[/yellow] {escape(one_line(problem))}", highlight=False, soft_wrap=True)
    summary = bench_summary(episodes, suite=suite, not_applicable=not_applicable)
    if as_json:
        print_json(summary.to_json())
        return
    tables = out_dir / "tables.md"
    if tables.exists():
        from emboteam.bench.tables import terminal_tables

        for renderable in terminal_tables(tables.read_text(), width=out.width):
            out.print(renderable)
    out.print(f"results: {out_dir}/results.sqlite · report: {out_dir}/index.html", markup=False,
              highlight=False)


BENCH_ROOT = Path("bench-out")
#: the arguments ``main()`` was called with (what a resume command repeats)
_invocation: list[str] | None = None


def _bench_out(cfg: Any, out_dir: Path | None) -> Any:
    """The run's folder: ``--out DIR`` as given (strict: it must not hold another run's
    results unless ``--resume``), or a new folder under bench-out/ named by suite,
    configuration and time."""
    from emboteam.bench.runner import default_out_dir, store_path
    from emboteam.outputs import ensure_out_dir

    if out_dir is None:
        if cfg.resume:
            raise EmboTeamError("--resume needs --out DIR, the folder of the run to continue")
        if BENCH_ROOT.exists() and not BENCH_ROOT.is_dir():
            raise EmboTeamError(f"{BENCH_ROOT} is a file: pass --out DIR")
        BENCH_ROOT.mkdir(exist_ok=True)
        cfg = cfg.model_copy(update={"out_dir": default_out_dir(cfg, root=BENCH_ROOT)})
    elif cfg.resume and not store_path(out_dir).exists():
        where = "does not exist" if not out_dir.exists() else f"holds no {store_path(out_dir).name}"
        raise EmboTeamError(f"nothing to resume: {printable(str(out_dir))} {where} (drop --resume to start a new run "
                            "there)")
    ensure_out_dir(cfg.out_dir)
    return cfg


def resume_command(out_dir: Path) -> str:
    """The command that continues an interrupted run: the same arguments, with
    ``--resume --out DIR`` (the default folder is new each run, so it must be named)."""
    import shlex

    args = list(_invocation) if _invocation is not None else ["bench"]
    kept: list[str] = []
    skip = False
    for arg in args:
        if skip:
            skip = False
            continue
        if arg == "--out":
            skip = True
            continue
        if arg.startswith("--out=") or arg == "--resume":
            continue
        kept.append(arg)
    return shlex.join(["emboteam", *kept, "--resume", "--out", str(out_dir)])


@app.command("export-bt")
@cli_errors
def export_bt(
    target: str = typer.Argument(..., metavar="TASK|INSTRUCTION", help="SUITE/ID, or an instruction"),
    fmt: str = typer.Option("btcpp", "--format", help="btcpp (BehaviorTree.CPP v4 XML) | dot | ascii"),
    scene_fp: str | None = typer.Option(None, "--scene", help="floor plan of an instruction"),
    robots_list: str | None = typer.Option(None, "--robots", help="team of an instruction: 1,2,3"),
    frontend: str | None = typer.Option(None, "--frontend", help=FRONTEND_HELP),
    llm: str | None = typer.Option(None, "--llm", help=LLM_HELP),
    llm_when: str | None = typer.Option(None, "--llm-when", help=LLM_WHEN_HELP),
    out_file: Path | None = typer.Option(None, "--out", help="write here (.png/.svg with --format dot: an image)"),
) -> None:
    """Export a task's behavior tree: BehaviorTree.CPP v4 XML (Groot2), Graphviz DOT or ASCII."""
    from emboteam.btc.export import render, to_ascii, to_btcpp_xml, to_dot
    from emboteam.modes import EpisodeContext, plan_task
    from emboteam.outputs import check_out_file, write_error

    if fmt not in ("btcpp", "dot", "ascii"):
        raise EmboTeamError(f"unknown format {fmt!r}: btcpp, dot or ascii")
    if out_file is not None:
        if out_file.suffix.lower() in (".png", ".svg") and fmt != "dot":
            raise EmboTeamError(f"--out {out_file} is an image, but --format {fmt} writes text: use "
                                f"--format dot for a {out_file.suffix.lower()}, or another file name")
        check_out_file(out_file)
    task = _resolve_task(target, scene_fp, robots_list)
    fe, when = _front_end(frontend, llm, llm_when)
    cfg = _run_config("full", fe, llm, llm_when=when)
    ctx = EpisodeContext.open(task, cfg)
    state = ctx.state
    _, merged = plan_task(ctx)
    if fmt == "dot" and out_file is not None and out_file.suffix.lower() in (".png", ".svg"):
        try:
            render(merged, out_file, state=state)
        except OSError as exc:
            raise write_error(out_file, exc) from None
        err.print(f"wrote {out_file}", markup=False, highlight=False)
        return
    text = {"btcpp": to_btcpp_xml, "dot": to_dot, "ascii": to_ascii}[fmt](merged, state=state)
    if out_file is None:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
    else:
        try:
            out_file.write_text(text)
        except OSError as exc:
            raise write_error(out_file, exc) from None
        err.print(f"wrote {out_file}", markup=False, highlight=False)


def _click_exceptions() -> Any:
    """Click's exception classes: recent typer releases ship their own copy of click (typer._click)
    and raise those; older typer raises click's."""
    try:
        from typer._click import exceptions
    except ImportError:  # an older typer on plain click
        from click import exceptions  # type: ignore[no-redef]
    return exceptions


def _abort_class(exceptions: Any) -> type[BaseException]:
    """Click's Abort (Ctrl-C at a prompt): in click's exceptions module, or in
    ``typer.exceptions`` for typer releases that ship their own click."""
    abort = getattr(exceptions, "Abort", None)
    if abort is None:
        from typer.exceptions import Abort as abort
    return cast(type[BaseException], abort)


def _usage_message(exc: Any) -> str:
    """Click's message, with where to look: ``--help`` of the command that was called."""
    message = str(exc.format_message())
    ctx = getattr(exc, "ctx", None)
    if isinstance(exc, _click_exceptions().UsageError) and ctx is not None:
        message += f" (see '{ctx.command_path} --help')"
    return message


def main(argv: list[str] | None = None) -> None:
    """Entry point of the ``emboteam`` console script.

    Click is run with ``standalone_mode=False`` so that its own errors (an unknown option,
    a value out of range, a missing argument) follow the same contract as ours: one line
    on stderr, exit 2, and with ``--json`` one JSON object on stdout, instead of the
    multi-line box typer draws."""
    global _invocation
    from emboteam.logs import configure

    configure(0)  # log records stay off stderr unless -v (one line per failure)
    args = sys.argv[1:] if argv is None else list(argv)
    _invocation = args
    as_json = "--json" in args
    ce = _click_exceptions()
    try:
        code = app(args=args, prog_name="emboteam", standalone_mode=False)
    except ce.UsageError as exc:
        if type(exc).__name__ == "NoArgsIsHelpError":  # bare `emboteam`: the help is the answer
            exc.show()
            code = EXIT_BAD_INPUT
        else:
            code = fail(_usage_message(exc), EXIT_BAD_INPUT, as_json=as_json, error_type="UsageError").exit_code
    except ce.ClickException as exc:
        code = fail(exc.format_message(), exc.exit_code or EXIT_BAD_INPUT, as_json=as_json,
                    error_type=type(exc).__name__).exit_code
    except (_abort_class(ce), KeyboardInterrupt):
        code = fail("interrupted", EXIT_INTERRUPTED, as_json=as_json, error_type="KeyboardInterrupt").exit_code
    sys.exit(code if isinstance(code, int) else EXIT_OK)


if __name__ == "__main__":
    main()
