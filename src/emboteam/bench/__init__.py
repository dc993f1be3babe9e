"""BENCH: MACE-THOR, importers, metrics, modes, the evaluation runner and reports."""
