"""``--executor ray``: the same episodes as the local executor, as Ray tasks.

Each job is one Ray task (``num_cpus=1``) running :func:`emboteam.bench.jobs.execute_job`,
so an exception inside an episode comes back as a failed episode exactly as locally. A
task whose worker process dies is retried once by Ray (``max_retries=1``); if it dies
again, the job is recorded as a failed episode and the run goes on.

Connecting: an already initialised Ray (a test, a notebook) is used as is and left
running; otherwise ``ray.init(address=...)`` joins a cluster (``"auto"``, ``HOST:6379``,
or ``ray://HOST:10001`` for Ray Client) or, with no address, whatever Ray finds
(``RAY_ADDRESS``, a ``ray start`` instance on this machine) or a new local instance; the
runner disconnects at the end. Every node must be able to import EmboTeam and the
episode function (install the package on the nodes, or pass a ``runtime_env``).
"""

from __future__ import annotations

import logging
import socket
from typing import Any

from emboteam.bench.jobs import BenchConfigError, EpisodeFn, Job, JobResult, execute_job, failed_episode
from emboteam.errors import ServiceUnavailableError

log = logging.getLogger(__name__)


def _import_ray() -> Any:
    try:
        import ray
    except ImportError:
        raise BenchConfigError("--executor ray needs Ray: pip install 'emboteam[ray]'") from None
    return ray


#: seconds to wait for a TCP answer from --ray-address before handing it to Ray (which
#: would retry for minutes, printing its own C++ log lines on the terminal)
PROBE_TIMEOUT = 3.0


def _host_port(address: str) -> tuple[str, int] | None:
    """``HOST:PORT`` or ``ray://HOST:PORT`` -> (host, port); None for what Ray resolves
    itself (``auto``, ``local``) or a form without a port."""
    text = address.strip()
    rest = text.split("://", 1)[1] if "://" in text else text
    host, sep, port = rest.rstrip("/").rpartition(":")
    if not sep or not port.isdigit():
        return None
    return host.strip("[]") or "127.0.0.1", int(port)


def probe_address(address: str | None, timeout: float = PROBE_TIMEOUT) -> None:
    """Fail fast (:class:`ServiceUnavailableError`, exit 3) when nothing answers at the
    cluster address: one TCP connection with a short timeout, before Ray is started."""
    if not address:
        return
    target = _host_port(address)
    if target is None:
        return
    host, port = target
    if not 0 < port < 65536:
        raise BenchConfigError(f"--ray-address {address}: port {port} is not a TCP port (1-65535)")
    try:
        with socket.create_connection((host, port), timeout=timeout):
            pass
    except OSError as exc:
        why = f"no answer within {timeout:g} s" if isinstance(exc, TimeoutError) else (exc.strerror or str(exc))
        raise ServiceUnavailableError(f"cannot reach the Ray cluster at {address}: {why}") from None


class RayExecutor:
    """Keeps at most ``workers`` Ray tasks in flight (the runner records each as it ends)."""

    def __init__(self, episode_fn: EpisodeFn, workers: int, *, address: str | None = None,
                 num_cpus_per_job: float = 1.0) -> None:
        self._ray = ray = _import_ray()
        self._owns_ray = not ray.is_initialized()
        if self._owns_ray:
            try:
                ray.init(address=address, include_dashboard=False, log_to_driver=False)
            except (ConnectionError, RuntimeError, ValueError) as exc:
                if address:  # a cluster that does not answer is a service problem (exit 3)
                    raise ServiceUnavailableError(f"cannot reach the Ray cluster at {address}: {exc}") from None
                raise BenchConfigError(f"cannot start a local Ray instance: {exc}") from None
        self._workers = workers
        self._fn_ref = ray.put(episode_fn)
        self._remote = ray.remote(execute_job).options(num_cpus=num_cpus_per_job, max_retries=1)
        self._running: dict[Any, Job] = {}

    def has_capacity(self) -> bool:
        return len(self._running) < self._workers

    def busy(self) -> bool:
        return bool(self._running)

    def submit(self, job: Job) -> None:
        self._running[self._remote.remote(self._fn_ref, job)] = job

    def wait(self) -> list[tuple[Job, JobResult]]:
        ray = self._ray
        ready, _ = ray.wait(list(self._running), num_returns=1)
        results: list[tuple[Job, JobResult]] = []
        for ref in ready:
            job = self._running.pop(ref)
            try:
                results.append((job, ray.get(ref)))
            except ray.exceptions.RayError as exc:
                # execute_job catches the episode's own exceptions, so this is Ray's: the
                # worker died twice, the node was lost, the object could not be fetched
                detail = f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"
                log.warning("Ray lost job %s: %s", job.key, detail)
                results.append((job, JobResult(key=job.key, traceback=str(exc),
                                               episode=failed_episode(job, f"WorkerDied: {detail}"))))
        return results

    def close(self) -> None:
        for ref in self._running:
            self._ray.cancel(ref, force=True)
        self._running.clear()
        if self._owns_ray:
            self._ray.shutdown()
