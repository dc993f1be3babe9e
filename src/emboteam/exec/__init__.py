"""EXEC: the reactive executor, blackboard protocol, replanning, dynamic team, trace.

``Executor(env, plan, goal, ...).run()`` ticks the compiled tree against an Environment;
``run_linear`` / ``run_sequences`` are the no-BTC ablation and SMART-LLM's execution on the
same environment and trace format.
"""

from emboteam.exec.executor import ExecutionConfigError, Executor, Join, UnsavableTaskError, parse_joins
from emboteam.exec.linear import run_linear, run_sequences, sequences_plan
from emboteam.exec.replan import Replanner, planner_replanner, restrict_team
from emboteam.exec.result import ExecutionResult

__all__ = [
    "ExecutionConfigError", "ExecutionResult", "Executor", "Join", "Replanner", "UnsavableTaskError",
    "parse_joins", "planner_replanner", "restrict_team", "run_linear", "run_sequences", "sequences_plan",
]
