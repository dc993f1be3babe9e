"""The mode table: every mode of the paper's Tables 1 and 2 as a choice of parts.

=============  ======================  ======================  ===========================
mode           decomposition / goals   planning                execution
=============  ======================  ======================  ===========================
full           front end (PFG)         HP: FD + formal merge,  behavior trees: checks,
                                       validated by simulation  recovery, sync, replanning
no-hp          front end (PFG)         FD per subtask, no      behavior trees
                                       validation, concatenated
no-btc         front end (PFG)         HP                      linear per robot, no checks
no-pfg-hp      LLM action lists        none                    behavior trees (no sync)
no-avoidance   front end (PFG)         HP                      behavior trees; robots drive
                                                               through each other on the grid
smart-llm      LLM action lists        none                    concurrent lists, no checks
lamma-p        front end (PFG)         FD per subtask + merge, linear per robot, no checks
                                       no validation
=============  ======================  ======================  ===========================

:data:`MODE_TABLE` is the only place that knows what a mode is made of; :mod:`emboteam.modes`
wires the parts by reading it and never compares mode names. Without an LLM, "LLM action
lists" come from :mod:`emboteam.pfg.scripted` (the results say so).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cache
from typing import Literal

from emboteam.config import MODES, Mode
from emboteam.errors import EmboTeamError
from emboteam.hp.planner import HybridPlanner, PlannerConfig
from emboteam.pddl.runner import PlannerInput

#: how a mode executes: the compiled behavior tree, one linear list per robot after a
#: plan, or the action lists run concurrently as written
Execution = Literal["tree", "linear", "sequences"]


@dataclass(frozen=True)
class ModeWiring:
    """The parts of one mode. ``planner`` None: no PDDL planning, the robots get action
    lists written directly; ``replan``: the executor replans when a subtask fails;
    ``llm_review``: with the LLM front end, the paper's LLM validation stage reviews the
    TaskSpec before planning."""

    planner: PlannerConfig | None
    execution: Execution
    replan: bool = False
    llm_review: bool = False
    #: robots avoid each other on the navigation grid (reservations, waits, yields)
    avoidance: bool = True
    #: the team closes what it opens (pfg/close_after_use.py); LaMMA-P plans the goals as read
    close_after_use: bool = True


#: LaMMA-P: optimal Fast Downward calls per subtask, one at a time, no cache, sub-plans
#: concatenated without validation and executed linearly. LaMMA-P's ``seq-opt-lmcut``
#: rejects this domain (LM-cut supports neither axioms nor conditional effects: Fast
#: Downward exit 34), so it runs ``astar(hmax())``, the admissible search that does
#: (docs/planning.md).
MODE_TABLE: dict[Mode, ModeWiring] = {
    "full": ModeWiring(PlannerConfig(), "tree", replan=True, llm_review=True),
    "no-pfg-hp": ModeWiring(None, "tree"),
    "no-hp": ModeWiring(PlannerConfig(validate=False, merge="concatenate"), "tree"),
    "no-btc": ModeWiring(PlannerConfig(), "linear"),
    "no-avoidance": ModeWiring(PlannerConfig(), "tree", replan=True, llm_review=True, avoidance=False),
    "smart-llm": ModeWiring(None, "sequences"),
    "lamma-p": ModeWiring(PlannerConfig(alias="astar(hmax())", workers=1, validate=False, merge="concatenate"),
                          "linear", close_after_use=False),
}
assert tuple(MODE_TABLE) == MODES, "the mode table lists every mode, in table order"


class ModeConfigError(EmboTeamError):
    """A mode/front-end combination that cannot run (e.g. ``--frontend llm`` without ``--llm``)."""


def wiring(mode: Mode) -> ModeWiring:
    return MODE_TABLE[mode]


@cache
def planner_for(mode: Mode, planner_input: PlannerInput = "sas", schedule: str = "fast") -> HybridPlanner:
    """One planner per mode and process (and input, schedule), so its plan cache serves
    every episode."""
    config = MODE_TABLE[mode].planner
    if config is None:
        raise ModeConfigError(f"mode {mode} does not plan")
    return HybridPlanner(replace(config, planner_input=planner_input,
                                 schedule="optimal" if schedule == "optimal" else "fast"))


__all__ = ["MODE_TABLE", "Execution", "ModeConfigError", "ModeWiring", "planner_for", "wiring"]
