"""Rich renderings of the stages' outputs for the terminal, and their JSON shapes.

Kept apart from :mod:`emboteam.cli` so the command module only parses options and
dispatches; the JSON shapes here are the ``--json`` contract of ``plan`` and ``run``.
"""

from __future__ import annotations

from rich.console import Group
from rich.markup import escape
from rich.panel import Panel
from rich.table import Table
from rich.text import Text

from emboteam.exec.episode import Episode
from emboteam.hp.plan import MergedPlan
from emboteam.pfg.taskspec import TaskSpec
from emboteam.terminal import one_line, printable, user_message


def spec_json(spec: TaskSpec) -> list[dict[str, object]]:
    return [
        {"id": s.id, "description": s.description, "robot": s.robot,
         "goal": [str(c) for c in s.goal], "depends_on": list(s.depends_on), "final": s.final}
        for s in spec.subtasks
    ]


def plan_json(plan: MergedPlan) -> dict[str, object]:
    return {
        "robots": {r: [{"id": s.id, "action": str(s.action), "subtask": s.subtask, "after": list(s.after)}
                       for s in plan.for_robot(r)] for r in plan.robots},
        "sync": [{"producer": p.producer, "consumer": p.consumer, "reason": p.reason} for p in plan.sync],
        "makespan": round(plan.makespan, 2), "lower_bound": round(plan.lower_bound, 2),
        "joint": plan.joint, "planner_calls": plan.planner_calls,
    }


def spec_table(spec: TaskSpec) -> Table:
    table = Table(title="subtasks (PFG)", title_justify="left", expand=False)
    for col in ("id", "robot", "goal", "after"):
        table.add_column(col)
    for s in spec.subtasks:
        goal = "\n".join(str(c) for c in s.goal) + ("" if s.final else "  (intermediate)")
        table.add_row(escape(printable(s.id)), escape(s.robot) if s.robot else "[dim]any[/dim]", escape(printable(goal)),
                      escape(", ".join(s.depends_on)))
    return table


def plan_table(plan: MergedPlan) -> Table:
    how = "joint problem (fallback)" if plan.joint else "per subtask, merged"
    if plan.planner_calls == 0 and plan.makespan == 0:
        # action lists taken as written (smart-llm, no-pfg-hp): nothing was planned or scheduled
        title = f"plan ({len(plan.steps)} actions as written, not planned: no Fast Downward call, no makespan estimate)"
    else:
        title = (f"plan (HP, {how}): makespan {plan.makespan:.1f} s, lower bound {plan.lower_bound:.1f} s, "
                 f"{plan.planner_calls} Fast Downward call(s)")
    table = Table(title=escape(title), title_justify="left")
    table.add_column("robot", no_wrap=True)
    table.add_column("actions  (⏳ waits for another robot's step)")
    for robot in plan.robots:
        parts = []
        for s in plan.for_robot(robot):
            wait = f"⏳{','.join(s.after)} " if s.after else ""
            parts.append(f"{wait}{s.action}")
        table.add_row(robot, Text(" → ".join(parts)))
    return table


def episode_panel(episode: Episode, *, out_dir: str | None = None) -> Panel:
    verdict = "[bold green]SUCCESS[/bold green]" if episode.success else "[bold red]FAILED[/bold red]"
    metrics = Table.grid(padding=(0, 2))
    for _ in range(4):
        metrics.add_column()
    metrics.add_row("GCR", f"{episode.gcr:.2f}", "Exec", f"{episode.exec:.2f}")
    metrics.add_row("makespan", f"{episode.makespan:.1f} s", "actions",
                    f"{episode.actions} ({episode.failed_actions} failed)")
    metrics.add_row("recoveries", str(episode.recoveries), "replans", str(episode.replans))
    metrics.add_row("LLM calls", str(episode.llm_calls), "tokens", str(episode.tokens))
    metrics.add_row("planning", f"{episode.plan_seconds:.2f} s", "mode",
                    f"{episode.mode} / {episode.frontend}")
    conds = Table.grid(padding=(0, 1))
    conds.add_column()
    conds.add_column()
    for c in episode.conditions:
        conds.add_row("[green]✓[/green]" if c.holds else "[red]✗[/red]", Text(c.condition))
    body: list[object] = [metrics, Text(""), conds]
    if episode.notes:      # what the front end could not read, or read with doubt
        body += [Text("")] + [Text(f"note: {one_line(n)}", style="yellow") for n in episode.notes]
    if episode.unexplained:     # things named that ended in no goal, with nothing to explain them
        body += [Text(f"unexplained: {', '.join(repr(w) for w in episode.unexplained)} (named, but in no goal)",
                      style="yellow")]
    if len(episode.candidates) > 1:     # the readings considered, best first
        body += [Text(""), Text("readings considered (score = log prior):")]
        body += [Text(f"{'→' if k == 0 else ' '} {c['score']:6.2f}  {c['sentence']}"
                      + (f"  [{'; '.join(r['how'] for r in c['resolves'])}]" if c["resolves"] else ""),
                      style="bold" if k == 0 else "dim")
                 for k, c in enumerate(episode.candidates)]
    if episode.not_attempted:    # requested, but the planner could not plan it: left out of the run
        body += [Text(""), Text("not attempted (the planner could not plan it):", style="red")]
        body += [Text(f"  ✗ {one_line(str(n))}", style="red") for n in episode.not_attempted]
    if episode.error:
        body += [Text(""), Text(f"error: {one_line(user_message(episode.error))}", style="red")]
    if out_dir:
        body += [Text(""), Text(f"report: {out_dir}/report.html", style="cyan")]
    return Panel(Group(*body), title=f"{escape(printable(episode.task))} {verdict}",  # type: ignore[arg-type]
                 subtitle=escape(f"{episode.floor_plan} · {', '.join(episode.robots)}"))

