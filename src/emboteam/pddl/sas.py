"""A problem as Fast Downward's finite-domain input (the translator's ``output.sas``,
file version 3), written from our own grounding (:mod:`emboteam.pddl.grounding`).

Format (https://www.fast-downward.org/latest/documentation/translator-output-format/):
version, metric, variables (name, axiom layer or -1, values), mutex groups, initial
state, goal, operators (prevail conditions, effects ``conditions var pre post``, cost),
axioms (``begin_rule``: conditions, ``var old new``).

Every fact is one binary variable, value 1 = true, 0 = false. A derived variable's default
is false (value 0); its rules set it to 1, and the search evaluates them layer by layer
with negation as failure (a condition ``var = 0`` on a derived variable reads "not
derivable", which the layering makes sound). We write no mutex groups: they only inform
heuristics, and finding them is what the translator's invariant synthesis spends its time
on. All preconditions are prevail conditions (the search merges prevail conditions and
effect ``pre`` values into one precondition list).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache

from emboteam.pddl.domain import DERIVED, SCHEMAS
from emboteam.pddl.grounding import Fact, GroundTask, compile_domain, ground_task
from emboteam.pddl.problem import Problem
from emboteam.sim.durations import ACTION_SECONDS
from emboteam.world.actions import Skill

#: bump when the emitted task changes for the same problem (it is part of cache keys)
EMITTER_VERSION = "sas-2"

#: operator costs with ``costs=True``: an action's duration in half seconds
#: (:data:`emboteam.sim.durations.ACTION_SECONDS`); a ``goto``, whose duration depends on where
#: the robot comes from (not a parameter of the operator), counts :data:`GOTO_SECONDS`
#: (a typical drive across a kitchen), so a plan that drives less and toggles less costs less
GOTO_SECONDS = 3.0
COST_UNIT = 0.5


@cache
def _schema_costs() -> dict[str, int]:
    out = {}
    for s in SCHEMAS:
        seconds = GOTO_SECONDS if s.skill is Skill.GoToObject else ACTION_SECONDS.get(s.skill, 1.0)
        out[s.name] = max(1, round(seconds / COST_UNIT))
    return out


def operator_cost(name: str) -> int:
    """The cost of a ground operator (``put robot1 apple_1 fridge_1``) with ``costs=True``."""
    return _schema_costs().get(name.split(" ", 1)[0], 1)


@dataclass(frozen=True)
class SasTask:
    """The emitted text, or a verdict that needs no search (``trivial``: the goal holds
    whatever happens; ``unreachable``: relaxed reachability proves it unsolvable)."""

    verdict: str
    text: str = ""
    variables: int = 0
    operators: int = 0
    axioms: int = 0


def _name(f: Fact) -> str:
    return f"{f[0]}({', '.join(f[1:])})"


def plan_cost(plan: Sequence[str]) -> int:
    """The cost of a plan (lines as Fast Downward writes them: ``(put robot1 apple_1 fridge_1)``)."""
    return sum(operator_cost(line.strip("() ")) for line in plan)


def render(task: GroundTask, costs: bool = False) -> str:
    """The task as text; ``costs``: operators cost their durations (:func:`operator_cost`),
    else 1 each (metric 0)."""
    index: dict[Fact, int] = {}
    lines = ["begin_version", "3", "end_version", "begin_metric", "1" if costs else "0", "end_metric"]
    variables: list[tuple[Fact, int]] = [(f, -1) for f in task.fluents] + list(task.derived.items())
    lines.append(str(len(variables)))
    for i, (f, layer) in enumerate(variables):
        index[f] = i
        name = _name(f)
        lines += ["begin_variable", f"var{i}", str(layer), "2", f"NegatedAtom {name}", f"Atom {name}",
                  "end_variable"]
    lines.append("0")
    lines.append("begin_state")
    lines += ["1" if layer == -1 and f in task.init else "0" for f, layer in variables]
    lines.append("end_state")
    lines += ["begin_goal", str(len(task.goal))]
    lines += [f"{index[f]} {int(v)}" for f, v in task.goal]
    lines.append("end_goal")
    lines.append(str(len(task.operators)))
    for op in task.operators:
        lines += ["begin_operator", op.name, str(len(op.pre))]
        lines += [f"{index[f]} {int(v)}" for f, v in op.pre]
        lines.append(str(len(op.effects)))
        for e in op.effects:
            conds = " ".join(f"{index[f]} {int(v)}" for f, v in e.conditions)
            head = f"{len(e.conditions)} {conds} " if e.conditions else "0 "
            lines.append(f"{head}{index[e.fact]} -1 {int(e.value)}")
        lines += [str(operator_cost(op.name)) if costs else "1", "end_operator"]
    lines.append(str(len(task.axioms)))
    for ax in task.axioms:
        lines += ["begin_rule", str(len(ax.body))]
        lines += [f"{index[f]} {int(v)}" for f, v in ax.body]
        lines += [f"{index[ax.head]} 0 1", "end_rule"]
    return "\n".join(lines) + "\n"


def _parse_fact(text: str) -> Fact:
    return tuple(text.strip().strip("()").split())


def emit(problem: Problem, goals: Sequence[str] | None = None, costs: bool = False) -> SasTask:
    """The SAS task of a rendered problem (its objects, initial facts and goal formulas);
    ``costs``: with action costs (:func:`render`)."""
    domain = compile_domain(SCHEMAS, tuple(DERIVED.values()))
    init = [_parse_fact(f) for f in problem.facts]
    task = ground_task(domain, problem.robots, problem.objects, init,
                       list(goals) if goals is not None else list(problem.goals))
    if task.verdict != "search":
        return SasTask(task.verdict)
    return SasTask("search", render(task, costs), len(task.fluents) + len(task.derived), len(task.operators),
                   len(task.axioms))
