"""The console script's entry point.

Importing the CLI loads typer, rich, pydantic and the stages: about a second in which a
Ctrl-C would end in an import traceback. Caught here, it ends as the command-line contract
says: one line on stderr, with ``--json`` one JSON object on stdout, exit 130. Only the
standard library is used before the CLI has loaded, so this module loads at once."""

from __future__ import annotations

import json
import sys

EXIT_INTERRUPTED = 130  # emboteam.errors.EXIT_INTERRUPTED, not imported: it is not loaded yet


def main() -> None:
    """``emboteam``: load the CLI, then run it."""
    try:
        from emboteam.cli import main as run_cli
    except KeyboardInterrupt:
        if "--json" in sys.argv[1:]:
            print(json.dumps({"success": False, "error": "interrupted", "error_type": "KeyboardInterrupt",
                              "exit_code": EXIT_INTERRUPTED}))
        print("error: interrupted", file=sys.stderr)
        raise SystemExit(EXIT_INTERRUPTED) from None
    run_cli()
