"""One offline parser per process, shared by every caller (the pipeline's front ends, the
LLM front end's draft reading): building its lexicon and spelling caches takes ~0.1 s."""

from __future__ import annotations

from functools import cache

from emboteam.pfg.offline import OfflineFrontend


@cache
def offline_frontend() -> OfflineFrontend:
    return OfflineFrontend()


__all__ = ["offline_frontend"]
