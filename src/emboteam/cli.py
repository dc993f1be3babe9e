"""The ``emboteam`` command (typer + rich). The contract is in docs/DESIGN.md:
``--json`` prints exactly one JSON object on stdout, logs go to stderr, and bad input
exits non-zero with a one-line error, never a traceback."""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from functools import wraps
from pathlib import Path
from typing import Any, TypeVar

import typer
from rich.console import Console
from rich.table import Table

from emboteam.errors import EmboTeamError
from emboteam.world.actions import Skill
from emboteam.world.robots import robot_profiles
from emboteam.world.scene import load_scene, scene_ids

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="EmboTeam: household instructions -> PDDL -> multi-robot plan -> reactive behavior trees.",
)
out = Console()
err = Console(stderr=True)

F = TypeVar("F", bound=Callable[..., Any])


def cli_errors(fn: F) -> F:
    """Turn expected errors into one line on stderr and a non-zero exit."""

    @wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except EmboTeamError as exc:
            err.print(f"[red]error:[/red] {exc}", highlight=False, soft_wrap=True)
            raise typer.Exit(exc.exit_code) from None

    return wrapper  # type: ignore[return-value]


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
    if as_json:
        print_json({
            "id": s.floor_plan, "room": s.room,
            "objects": [
                {"id": o.id, "type": o.type, "thor_id": o.thor_id, "parent": o.parent,
                 "properties": sorted(o.properties), "mass": o.mass, "position": o.position,
                 "state": o.state.model_dump(exclude_defaults=True), "controls": list(o.controls)}
                for o in s.objects
            ],
        })
        return
    table = Table(title=f"{s.floor_plan} ({s.room}, {len(s.objects)} objects)")
    for col in ("id", "in/on", "properties", "mass", "state"):
        table.add_column(col)
    for o in s.objects:
        state = ", ".join(f"{k}={v}" for k, v in o.state.model_dump(exclude_defaults=True).items())
        if o.controls:
            state = (state + ", " if state else "") + "controls " + " ".join(o.controls)
        table.add_row(o.id, o.parent or "", " ".join(sorted(o.properties)),
                      f"{o.mass:g}" if o.mass else "", state)
    out.print(table)


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
    from emboteam.bench.suites import load_suite

    loaded = load_suite(suite)
    for problem in loaded.problems:
        err.print(f"[yellow]skipped:[/yellow] {problem}", highlight=False, soft_wrap=True)
    if as_json:
        print_json({"tasks": [
            {"id": t.key, "scene": t.floor_plan, "category": t.category, "instruction": t.instruction,
             "robots": list(t.robots), "goal": [str(c) for c in t.goal.conditions]}
            for t in loaded.tasks
        ]})
        return
    counts = ", ".join(f"{n} {cat}" for cat, n in loaded.categories().items())
    table = Table(title=f"{loaded.name}: {len(loaded.tasks)} tasks ({counts})")
    for col in ("task", "scene", "category", "robots"):
        table.add_column(col, no_wrap=True)
    table.add_column("instruction", overflow="fold")
    for t in loaded.tasks:
        table.add_row(t.key, t.floor_plan, t.category, ",".join(t.robots), t.instruction)
    out.print(table)


@app.command()
@cli_errors
def report(directory: Path = typer.Argument(..., help="a run's or a benchmark's --out DIR")) -> None:
    """(Re)build the HTML report of a run (report.html) or a benchmark (index.html)."""
    from emboteam.report import write_report

    for path in write_report(directory):
        out.print(f"wrote {path}")


def main() -> None:
    """Entry point of the ``emboteam`` console script."""
    app()


if __name__ == "__main__":
    main()
