"""BTC (Behavior Tree Compiler): merged plan -> py_trees tree; exporters."""
