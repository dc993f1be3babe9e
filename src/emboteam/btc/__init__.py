"""BTC (Behavior Tree Compiler): merged plan -> py_trees tree; exporters.

``compile_plan(plan, runtime)`` builds the tree the executor ticks
(``Parallel(T_R1..T_RN)``, each action ``Sequence(Fallback(Pre, Recover), Core, Post)``);
``to_btcpp_xml`` / ``to_dot`` / ``to_ascii`` / ``render`` export it. docs/behavior_trees.md
describes the node anatomy, the recovery table and the sync/lock protocol.
"""

from emboteam.btc.blueprint import PlanBlueprint, StepBlueprint, blueprint
from emboteam.btc.compiler import CompiledTree, compile_plan
from emboteam.btc.config import BTConfig
from emboteam.btc.errors import ExportError, PlanCompileError
from emboteam.btc.export import render, to_ascii, to_btcpp_xml, to_dot
from emboteam.btc.recovery import Diagnosis, Strategy
from emboteam.btc.runtime import Runtime

__all__ = [
    "BTConfig", "CompiledTree", "Diagnosis", "ExportError", "PlanBlueprint", "PlanCompileError", "Runtime",
    "StepBlueprint", "Strategy", "blueprint", "compile_plan", "render", "to_ascii", "to_btcpp_xml", "to_dot",
]
