"""Importers of other benchmarks' task formats into :class:`~emboteam.bench.task.BenchTask`."""
