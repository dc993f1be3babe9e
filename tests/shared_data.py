"""Where the tests find ``../shared`` (AI2-THOR metadata dumps, the peers' task files).

A user's clone has nothing beside it, so every test that reads this folder skips *at test
level* with its reason when the data is missing; nothing here may skip or fail at import
(``pytest.skip`` at collection aborts the whole run). ``EMBOTEAM_SHARED_DIR`` points the
lookup elsewhere: CI sets it to an empty folder to prove the suite collects without the data.
"""

from __future__ import annotations

import os
from pathlib import Path


def shared_dir() -> Path:
    """``$EMBOTEAM_SHARED_DIR``, else the ``shared`` folder beside the repository."""
    env = os.environ.get("EMBOTEAM_SHARED_DIR")
    return Path(env) if env else Path(__file__).resolve().parents[2] / "shared"


SHARED = shared_dir()
AI2THOR = SHARED / "data" / "ai2thor"
SMART_LLM = SHARED / "data" / "peers" / "smart-llm"
