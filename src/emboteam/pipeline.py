"""One episode end to end: front end -> hybrid planner -> behavior trees -> execution.

The entry point of an episode, for ``emboteam run`` and a benchmark worker alike:
:func:`run_episode` takes an :class:`~emboteam.task.EpisodeTask` (a benchmark task or a
typed :class:`~emboteam.task.Instruction`) and a :class:`~emboteam.config.RunConfig`. The
mode table is :mod:`emboteam.mode_table`, the stage wiring :mod:`emboteam.modes`. Every
typed error becomes a recorded failed episode.
"""

from __future__ import annotations

import time

from emboteam.config import MODES, RunConfig
from emboteam.environments import check_thor_config
from emboteam.errors import EmboTeamError
from emboteam.exec.episode import Episode, episode_header, score
from emboteam.llm.client import LLMClient
from emboteam.modes import make_llm, run_mode
from emboteam.pfg.clarification import ClarificationNeeded
from emboteam.task import EpisodeTask


def check_config(cfg: RunConfig) -> None:
    """Raise the typed error of an unusable configuration (an LLM spec that names no
    provider, ``--frontend llm`` without ``--llm``, a missing API key) before any episode
    runs: such errors are the user's to fix, not failed episodes."""
    make_llm(cfg)
    if cfg.env == "ai2thor":
        check_thor_config(cfg)  # fails fast, in a second or so, when AI2-THOR cannot start here


def run_episode(task: EpisodeTask, cfg: RunConfig) -> Episode:
    """Plan and execute one task; a typed error ends it as a recorded failed episode."""
    started = time.perf_counter()
    llm: LLMClient | None = None
    try:
        llm = make_llm(cfg)
        episode = run_mode(task, cfg, llm)
    except EmboTeamError as exc:
        team = task.team()
        truth = task.ground_truth
        _, gcr, conds = score(truth, task.initial_state()) if truth is not None else (False, 0.0, ())
        # a failed episode still reports what its LLM calls cost
        usage = {"llm_calls": llm.usage.calls, "tokens": llm.usage.tokens} if llm is not None else {}
        asked = exc.clarification if isinstance(exc, ClarificationNeeded) else None
        episode = Episode.model_validate({
            **episode_header(task, cfg, [p.name for p in team]), "success": False, "gcr": gcr,
            "conditions": conds, "error": f"{type(exc).__name__}: {exc}", "clarification": asked, **usage,
            **(exc.read_so_far or {})})
    return episode.model_copy(update={"wall_seconds": round(time.perf_counter() - started, 4)})


__all__ = ["MODES", "RunConfig", "check_config", "run_episode"]
