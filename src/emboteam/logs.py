"""Where EmboTeam's log records go: nowhere by default, stderr with ``emboteam -v``.

The command-line contract (docs/cli.md) is one line on stderr per failure. Without a
handler, Python's last-resort handler would print every warning record (an LLM retry
notice, a worker that died) on stderr before that line, so the ``emboteam`` logger gets
one explicitly: silent by default, warnings and progress details at ``-v``, debug records
at ``-vv``. Benchmark workers are spawned processes that inherit the environment, not the
logging set-up, so the level travels in ``EMBOTEAM_LOG_VERBOSITY``.
"""

from __future__ import annotations

import logging
import os
import sys

ENV = "EMBOTEAM_LOG_VERBOSITY"
_HANDLER_NAME = "emboteam-cli"


def configure(verbosity: int | None = None) -> None:
    """Send the ``emboteam`` logger's records to stderr at ``-v`` (INFO) or ``-vv``
    (DEBUG); drop them at 0. ``None`` reads the level a parent process set."""
    if verbosity is None:
        try:
            verbosity = int(os.environ.get(ENV, "0"))
        except ValueError:
            verbosity = 0
    os.environ[ENV] = str(verbosity)
    logger = logging.getLogger("emboteam")
    for old in [h for h in logger.handlers if h.get_name() == _HANDLER_NAME]:
        logger.removeHandler(old)
    handler: logging.Handler
    if verbosity <= 0:
        handler = logging.NullHandler()
        logger.setLevel(logging.CRITICAL + 1)
    else:
        handler = logging.StreamHandler(sys.stderr)
        handler.setFormatter(logging.Formatter("%(levelname)s %(name)s: %(message)s"))
        logger.setLevel(logging.INFO if verbosity == 1 else logging.DEBUG)
    handler.set_name(_HANDLER_NAME)
    logger.addHandler(handler)
    logger.propagate = False
