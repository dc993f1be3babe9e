"""Importers of other benchmarks' task formats into :class:`~emboteam.task.BenchTask`."""
