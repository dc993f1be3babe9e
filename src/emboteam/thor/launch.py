"""Probe for a usable AI2-THOR build and start the controller, failing fast.

``ai2thor.controller.Controller`` downloads its Unity build (about 500 MB) from S3 on
first use, then starts it on an X display with GLX (platform Linux64) or headless through
Vulkan (``platform=CloudRendering``), and waits for it up to ``server_start_timeout``.
On a machine with neither, or without network access to the build, that ends in a long
hang or a multi-line traceback. :func:`probe` checks each prerequisite first, in well
under a second plus at most :data:`DOWNLOAD_PROBE_SECONDS` for the build's URL, and
raises one :class:`ThorUnavailableError` whose message says everything that is missing.

Environment variables: ``EMBOTEAM_THOR_PLATFORM`` (``Linux64``, ``CloudRendering``, ``OSXIntel64``)
forces a platform; ``EMBOTEAM_THOR_EXECUTABLE`` runs a local Unity build instead of the
downloaded one; ``EMBOTEAM_THOR_START_TIMEOUT`` bounds the wait for Unity (seconds).
"""

from __future__ import annotations

import contextlib
import importlib
import os
import platform as host
from dataclasses import dataclass
from typing import Any

from emboteam.thor.errors import ThorUnavailableError

#: seconds to wait for the build server to answer a HEAD request before calling it
#: unreachable (the download itself, when reachable, is not bounded: it is the user's opt-in)
DOWNLOAD_PROBE_SECONDS = 3.0
#: seconds to wait for the Unity process to connect once started
START_TIMEOUT = 120.0
PLATFORMS = ("Linux64", "CloudRendering", "OSXIntel64")
PREFIX = "no AI2-THOR build could be started"


@dataclass(frozen=True, slots=True)
class LaunchPlan:
    """How :func:`start_controller` will start AI2-THOR."""

    platform: str
    executable: str | None
    build: str | None
    cached: bool


def _ai2thor() -> Any:
    try:
        importlib.import_module("ai2thor.controller")
        return importlib.import_module("ai2thor")
    except ImportError as exc:
        raise ThorUnavailableError(f"{PREFIX}: the ai2thor package is not installed "
                                   f"({exc.name or exc}); pip install 'emboteam[ai2thor]'") from None


def _platform_problems(name: str, width: int, height: int) -> list[str]:
    """Why AI2-THOR's own platform check rejects ``name`` here (empty: usable)."""
    from ai2thor.platform import STR_PLATFORM_MAP, Request

    if host.system() not in ("Linux", "Darwin"):
        return [f"AI2-THOR runs on Linux and macOS, not {host.system()}"]
    display = os.environ.get("DISPLAY")
    if name == "Linux64" and host.system() == "Linux" and not display and not os.path.isdir("/tmp/.X11-unix"):
        return ["no X display (DISPLAY is not set and no X server runs)"]
    req = Request(host.system(), width, height, display, False)
    problems = [str(p) for p in STR_PLATFORM_MAP[name].validate(req)]
    if name == "Linux64" and problems:
        return [f"no X display with GLX ({'DISPLAY=' + display if display else 'DISPLAY is not set'}: "
                f"{'; '.join(problems)})"]
    if name == "CloudRendering" and problems:
        return ["no Vulkan driver for platform=CloudRendering (libvulkan not found; apt-get install libvulkan1)"]
    return problems


def _build_problem(ai2thor: Any, name: str) -> tuple[str | None, bool, str | None]:
    """(build name, cached?, problem): the build ``Controller`` would use for ``name``."""
    import ai2thor.build as build

    commit = build.COMMIT_ID
    if not commit:
        return None, False, "this ai2thor package names no build commit"
    releases = os.path.join(os.path.expanduser("~"), ".ai2thor", "releases")
    b = build.Build(name, commit, False, releases)
    if os.path.isdir(b.base_dir):
        return b.name, True, None
    try:
        import requests

        status = requests.head(b.url, timeout=DOWNLOAD_PROBE_SECONDS).status_code
    except Exception as exc:  # any network failure means: not downloadable from here
        reason = type(exc).__name__
        short = b.name.rsplit("-", 1)[0] + "-" + commit[:8]
        return b.name, False, (f"build {short} is not cached in ~/.ai2thor/releases and cannot be "
                               f"downloaded ({b.url.split('/')[2]} unreachable: {reason})")
    if status != 200:
        return b.name, False, f"build {b.name} is not cached and its download answers HTTP {status}"
    return b.name, False, None


def probe(platform: str | None = None, *, width: int = 300, height: int = 300) -> LaunchPlan:
    """The way AI2-THOR can start here, or a :class:`ThorUnavailableError` saying why not."""
    ai2thor = _ai2thor()
    wanted = platform or os.environ.get("EMBOTEAM_THOR_PLATFORM") or None
    if wanted is not None and wanted not in PLATFORMS:
        raise ThorUnavailableError(f"{PREFIX}: unknown AI2-THOR platform {wanted!r} ({' or '.join(PLATFORMS)})")
    candidates = [wanted] if wanted else ["OSXIntel64"] if host.system() == "Darwin" else ["Linux64", "CloudRendering"]
    problems: list[str] = []
    chosen: str | None = None
    for name in candidates:
        found = _platform_problems(name, width, height)
        if not found:
            chosen = name
            break
        problems.extend(found)
    executable = os.environ.get("EMBOTEAM_THOR_EXECUTABLE") or None
    if executable is not None:
        if not os.access(executable, os.X_OK):
            problems.append(f"EMBOTEAM_THOR_EXECUTABLE={executable} is not an executable file")
        elif chosen is not None:
            return LaunchPlan(chosen, executable, None, True)
        raise ThorUnavailableError(f"{PREFIX}: " + "; ".join(problems))
    build_name, cached, build_problem = _build_problem(ai2thor, chosen or candidates[-1])
    if build_problem:
        problems.append(build_problem)
    if chosen is None or build_problem:
        raise ThorUnavailableError(f"{PREFIX}: " + "; ".join(problems))
    return LaunchPlan(chosen, None, build_name, cached)


def start_controller(plan: LaunchPlan, floor_plan: str, agent_count: int, *, width: int = 300,
                     height: int = 300, **init: Any) -> Any:
    """Start ``ai2thor.controller.Controller`` as ``plan`` says, with a bounded wait for Unity.

    AI2-THOR's initialisation: ``agentCount`` agents on a 0.25 m grid with the 1.5 m
    visibility distance our reach uses; temperatures stay as actions leave them
    (``SetDecayTemperatureBool``), since our goals read a heated potato as hot.
    """
    from ai2thor.controller import Controller
    from ai2thor.platform import CloudRendering

    timeout = float(os.environ.get("EMBOTEAM_THOR_START_TIMEOUT", START_TIMEOUT))
    kwargs: dict[str, Any] = dict(
        scene=floor_plan, agentCount=agent_count, gridSize=0.25, visibilityDistance=1.5,
        # off: a drive ends facing the object at any yaw (thor/driving.py), between grid headings
        snapToGrid=False, width=width, height=height, server_start_timeout=timeout, **init,
    )
    if plan.platform == "CloudRendering":
        kwargs["platform"] = CloudRendering
    if plan.executable:
        kwargs["local_executable_path"] = plan.executable
    try:
        controller = Controller(**kwargs)
    except Exception as exc:  # Unity did not start or answer: one line, the cause first
        first = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
        raise ThorUnavailableError(f"{PREFIX}: {plan.platform} build did not start ({type(exc).__name__}: "
                                   f"{first})") from None
    keep_temperatures(controller)
    return controller


def keep_temperatures(controller: Any) -> None:
    """Ask AI2-THOR not to let heated and chilled objects drift back to room temperature
    (our goals read a potato taken out of the microwave as hot). A build without the
    action keeps its default; the episode then sees the drift."""
    with contextlib.suppress(ValueError):
        controller.step(dict(action="SetDecayTemperatureBool", allowDecayTemperature=False))
