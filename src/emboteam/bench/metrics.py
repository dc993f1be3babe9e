"""Benchmark metrics, implemented from their definitions in docs/metrics.md.

Per episode (computed once, when the episode is built, and stored in it):

- **SR** (success): every goal condition holds in the final state.
- **GCR**: required instances that hold / required instances; a condition over ``N of``
  a type counts N (``GoalReport.gcr``): always in [0, 1].
- **Exec**: actions that succeeded / actions started in the environment. Every action
  counts: navigation (GoToObject), recovery actions, and actions the environment
  rejected at once (a rejected action is started and ends failed).
- makespan (simulated s), actions, LLM calls, tokens, planning s: as recorded.

Over episodes (:func:`summarize`): means overall and per task category, with a seeded
percentile-bootstrap 95% CI for SR that resamples *tasks* (all seeds of a task together).
Aggregates read the episodes' stored fields only, so a summary built from a result store
(traces not loaded) equals one built from the episodes in memory.
"""

from __future__ import annotations

import random
import re
import statistics
from collections.abc import Iterable, Sequence
from typing import Protocol

from pydantic import BaseModel, ConfigDict, Field

from emboteam.bench.disturbance_metrics import DisturbanceSummary, disturbance_by_mode, summarize_disturbance
from emboteam.exec.episode import Episode
from emboteam.exec.trace import TraceEvent
from emboteam.world.actions import ActionOutcome, Skill

#: bootstrap resamples for the SR confidence interval
RESAMPLES = 2000
#: its seed (fixed: the same episodes always give the same interval)
CI_SEED = 0


class _Counted(Protocol):
    """A condition's outcome: ``ConditionOutcome`` (episode) or ``ConditionResult`` (checker)."""

    @property
    def holds(self) -> bool: ...
    @property
    def satisfied(self) -> int: ...
    @property
    def required(self) -> int: ...


# ---- one episode --------------------------------------------------------------------------


def success_rate(conditions: Sequence[_Counted]) -> float:
    """1.0 if every condition holds, else 0.0 (an episode without conditions fails)."""
    return 1.0 if conditions and all(c.holds for c in conditions) else 0.0


def goal_condition_rate(conditions: Sequence[_Counted]) -> float:
    """Held required instances over required instances; a condition over N instances
    contributes at most N (extra witnesses never push it above 1)."""
    required = sum(c.required for c in conditions)
    if required == 0:
        return 0.0
    return sum(min(c.satisfied, c.required) for c in conditions) / required


_SKILL = re.compile(r"^\s*([A-Za-z]+)\s*\(")


def _skill_of(data: dict[str, object]) -> str | None:
    skill = data.get("skill")
    if isinstance(skill, str):
        return skill
    action = data.get("action")
    if isinstance(action, dict):
        value = action.get("skill")
        return value if isinstance(value, str) else None
    if isinstance(action, str):
        m = _SKILL.match(action)
        return m.group(1) if m else None
    return None


def exec_rate(trace: Iterable[TraceEvent], *, navigation: bool = True) -> float | None:
    """Exec from a trace: successful ``action_end`` events over actions started.

    Started = ``action_start`` events (an action cut off by the time limit never ends and
    counts as failed); a recorder that logs only ends is counted by its ends.
    ``navigation=False`` leaves GoToObject out, as SMART-LLM's count does (docs/metrics.md).
    None when no action was started (Exec is undefined, not 0).
    """
    starts = ends = ok = 0
    for ev in trace:
        if ev.kind not in ("action_start", "action_end"):
            continue
        if not navigation and _skill_of(ev.data) == Skill.GoToObject.value:
            continue
        if ev.kind == "action_start":
            starts += 1
        else:
            ends += 1
            ok += bool(ev.data.get("success"))
    started = max(starts, ends)
    return ok / started if started else None


def exec_from_outcomes(outcomes: Sequence[ActionOutcome], *, unfinished: int = 0,
                       navigation: bool = True) -> float | None:
    """Exec from the environment's outcomes (every started action that ended, rejected
    ones included) plus ``unfinished`` actions still running when the episode stopped."""
    counted = [o for o in outcomes if navigation or o.action.skill is not Skill.GoToObject]
    started = len(counted) + unfinished
    return sum(o.success for o in counted) / started if started else None


# ---- many episodes ------------------------------------------------------------------------


class GroupSummary(BaseModel):
    """SR, GCR, Exec of a group of episodes (fractions in [0, 1])."""

    model_config = ConfigDict(frozen=True)

    n: int
    sr: float
    gcr: float
    exec: float = Field(description="mean over episodes that started an action; 0 if none did")
    sr_ci: tuple[float, float] = Field(description="95% bootstrap CI of SR (tasks resampled)")


class BenchSummary(BaseModel):
    """``emboteam bench --json``: the fields of the command-line contract (docs/architecture.md) in its order, plus ``sr_ci``."""

    model_config = ConfigDict(frozen=True)

    suite: str = ""
    n: int
    sr: float
    gcr: float
    exec: float = Field(description="mean over episodes that started an action; 0 if none did")
    sr_ci: tuple[float, float] = Field(description="95% bootstrap CI of SR (tasks resampled)")
    by_category: dict[str, GroupSummary] = {}
    plan_seconds_p50: float = Field(0.0, description="median wall-clock planning seconds")
    makespan_mean: float = Field(0.0, description="mean simulated seconds of the successful episodes; "
                                                  "0 if none succeeded")
    llm_calls_mean: float = 0.0
    tokens_mean: float = 0.0
    errors: int = Field(0, description="episodes ended by a typed error")
    partly_done: int = Field(0, description="episodes that ran only the part of their reading the planner "
                                            "could plan (their not_attempted conditions: hp/feasible.py)")
    collisions: int = Field(0, description="vertex and edge conflicts the independent trace checker "
                                           "found (exec/nav_check.py), over all episodes")
    nav_waits: int = Field(0, description="times a robot waited for another on the grid, over all episodes")
    nav_replans: int = Field(0, description="drives re-planned around other robots, over all episodes")
    disturbance: DisturbanceSummary | None = Field(
        None, description="breakdowns, joins, moves, message faults: SR of savable, savable share (None: "
                          "no episode was disturbed by options)")
    disturbance_by_mode: dict[str, DisturbanceSummary] = Field(
        default_factory=dict, description="the same per mode")
    not_applicable: tuple[str, ...] = Field(
        (), description="'TASK: why' of the tasks a named disturbance cannot happen in: not run, in no SR")

    def to_json(self) -> dict[str, object]:
        """The bench ``--json`` object (the disturbance fields only when a run was disturbed,
        so the contract of an undisturbed run is unchanged)."""
        data = self.model_dump(mode="json")
        if self.disturbance is None:
            del data["disturbance"], data["disturbance_by_mode"]
        if not self.not_applicable:
            del data["not_applicable"]
        return data


#: categories in the paper's order; others follow alphabetically
CATEGORY_ORDER = ("parallel", "temporal", "imported")


def _mean(values: Sequence[float]) -> float:
    return sum(values) / len(values) if values else 0.0


def bootstrap_ci(groups: Sequence[Sequence[float]], *, level: float = 0.95, resamples: int = RESAMPLES,
                 seed: int = CI_SEED) -> tuple[float, float]:
    """Percentile bootstrap CI of the mean of all values, resampling whole groups.

    Written here rather than taken from scipy.stats.bootstrap: SciPy is not a dependency,
    and the groups (a task's seeds) must be resampled together, since runs of one task
    are not independent.
    """
    totals = [(float(sum(g)), float(len(g))) for g in groups if g]
    if not totals:
        return (0.0, 0.0)
    rng = random.Random(seed)
    k = len(totals)
    means: list[float] = []
    for _ in range(resamples):
        picks = rng.choices(totals, k=k)
        means.append(sum(t for t, _ in picks) / sum(n for _, n in picks))
    means.sort()
    alpha = (1 - level) / 2
    lo = means[int(alpha * (resamples - 1))]
    hi = means[round((1 - alpha) * (resamples - 1))]
    return (round(lo, 6), round(hi, 6))


def _group(episodes: Sequence[Episode], seed: int) -> GroupSummary:
    by_task: dict[str, list[float]] = {}
    for e in episodes:
        by_task.setdefault(e.task, []).append(1.0 if e.success else 0.0)
    ran = [e.exec for e in episodes if e.actions > 0]
    return GroupSummary(
        n=len(episodes),
        sr=_mean([1.0 if e.success else 0.0 for e in episodes]),
        gcr=_mean([e.gcr for e in episodes]),
        exec=_mean(ran),
        # tasks in key order: the interval must not depend on the order episodes finished in
        sr_ci=bootstrap_ci([by_task[task] for task in sorted(by_task)], seed=seed),
    )


def summarize(episodes: Iterable[Episode], *, suite: str = "", seed: int = CI_SEED) -> BenchSummary:
    """Aggregate episodes overall and per category (docs/metrics.md)."""
    eps = list(episodes)
    overall = _group(eps, seed)
    cats: dict[str, list[Episode]] = {}
    for e in eps:
        cats.setdefault(e.category or "uncategorised", []).append(e)
    order = [c for c in CATEGORY_ORDER if c in cats] + sorted(set(cats) - set(CATEGORY_ORDER))
    if not suite:
        names = {e.task.rpartition("/")[0] for e in eps}
        suite = names.pop() if len(names) == 1 else ""
    return BenchSummary(
        suite=suite, **overall.model_dump(),
        by_category={c: _group(cats[c], seed) for c in order},
        plan_seconds_p50=statistics.median([e.plan_seconds for e in eps]) if eps else 0.0,
        makespan_mean=_mean([e.makespan for e in eps if e.success]),
        llm_calls_mean=_mean([float(e.llm_calls) for e in eps]),
        tokens_mean=_mean([float(e.tokens) for e in eps]),
        errors=sum(1 for e in eps if e.error), partly_done=sum(1 for e in eps if e.not_attempted),
        collisions=sum(e.collisions for e in eps), nav_waits=sum(e.nav_waits for e in eps),
        nav_replans=sum(e.nav_replans for e in eps),
        disturbance=summarize_disturbance(eps), disturbance_by_mode=disturbance_by_mode(eps),
    )
