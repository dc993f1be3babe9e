"""How the hybrid planner runs: :class:`PlannerConfig` (the ablations and the stages the
pipeline runs are configurations, not forks)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal as TypingLiteral

from emboteam.pddl.errors import PlanningError


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
    #: when ``split_clusters`` is off and the longest cluster one robot does is more than
    #: ``fork.LOAD_EXCESS`` x the team's mean load on a plan of at most ``fork.MAX_STEPS``
    #: steps, also run the improvements on the plan with that cluster split in two
    #: (``split_clusters``' split) and keep whichever plan simulates shorter
    #: (:mod:`emboteam.hp.stages.fork`; the plan without it is made first, unchanged)
    split_critical: bool = True
    #: when one robot's cluster is longer than the resource-aware bound allows and has at
    #: least three blocks (``cluster_split.blocks``: a pencil, a book and a statue put in a
    #: box, the box put on a table), plan it again in one part per block (at most
    #: ``cluster_split.MAX_PARTS``): the part that moves the container first, for the
    #: robot, then the helpers' parts for the able robots that could be at each part's
    #: first thing earliest, each from the state the previous one leaves, spliced in the
    #: cluster's place or after the helpers' own jobs; kept when the simulated makespan is shorter (one
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
    #: put the plan's jobs in a shorter order and on the robots able to do them, priced by
    #: walking the routes as the simulator drives, and rebuild the plan with its drives
    #: planned again; kept when the simulated makespan is shorter (:mod:`emboteam.hp.routes`,
    #: :mod:`emboteam.hp.stages.route`; no planner call). Tried after the container split
    route: bool = True
    #: jobs of the robot that ends last moved to capable robots that end early or never
    #: moved (their start as their route), one at a time or, when no single move helps, two
    #: at once (:mod:`emboteam.hp.stages.idle_chain`: a job of the last robot to any able
    #: robot, one of that robot's on to an early one), the plan rebuilt with its drives planned again;
    #: kept when the simulated makespan is shorter (:mod:`emboteam.hp.stages.idle`; no
    #: planner call). Tried after the route stage
    idle: bool = True
    #: drives that waited for another robot to bring their object (a box carried to a
    #: table, then a book put in it) go to the place it is brought to instead, so the
    #: robot waits there; kept when the simulated makespan is shorter
    #: (:mod:`emboteam.hp.drive_ahead`; no planner call). Tried after the route stage
    drive_ahead: bool = True
    #: a switch or a door other robots waited for (the faucet another robot turns on late
    #: in its own chain) is done by the waiting robot free earliest; kept when the
    #: simulated makespan is shorter (:mod:`emboteam.hp.take_over`; no planner call).
    #: Tried after the drives ahead
    take_over: bool = True
    #: "fast" (the default): the stages above; "optimal": then the plan's actions given to
    #: CP-SAT's exact model of the whole schedule (:mod:`emboteam.hp.optimal`: which robot
    #: does each job, in which order, when; a deterministic time limit), and the plan
    #: rebuilt from its answer when that simulates shorter (:mod:`emboteam.hp.stages.schedule`)
    schedule: TypingLiteral["fast", "optimal"] = "fast"

    def __post_init__(self) -> None:
        if self.time_limit <= 0 or self.memory_limit_mb <= 0:
            raise PlanningError("planner time and memory limits must be positive")
        if self.workers < 1 or self.unit_conditions < 1:
            raise PlanningError("planner workers and unit_conditions must be at least 1")
        if self.merge not in ("formal", "concatenate"):
            raise PlanningError(f"merge must be 'formal' or 'concatenate', not {self.merge!r}")
        if self.rebalance not in ("off", "lpt", "cp-sat"):
            raise PlanningError(f"rebalance must be 'off', 'lpt' or 'cp-sat', not {self.rebalance!r}")
        if self.schedule not in ("fast", "optimal"):
            raise PlanningError(f"schedule must be 'fast' or 'optimal', not {self.schedule!r}")
        if self.planner_input not in ("sas", "pddl"):
            raise PlanningError(f"planner_input must be 'sas' or 'pddl', not {self.planner_input!r}")
