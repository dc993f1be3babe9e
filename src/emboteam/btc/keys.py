"""Names of the shared blackboard entries: the cross-robot protocol of a compiled tree.

One module so the compiler, the executor, the trace and the BehaviorTree.CPP export agree
on them. Keys are identifiers (``done_robot1_3``): py_trees reads ``.`` in a key as
attribute access and BehaviorTree.CPP port names must be identifiers too.

- ``done_<step>``   the producer step ended and its effects were observed (sync flag)
- ``lock_<spot>``   the robot currently holding an interaction spot (``None``: free)
- ``failed_<robot>`` why that robot's branch gave up (unset while it is working)
"""

from __future__ import annotations

import re

_NOT_IDENT = re.compile(r"[^A-Za-z0-9_]")


def ident(text: str) -> str:
    """``robot1.3`` -> ``robot1_3``: a name usable as a blackboard key or XML port."""
    return _NOT_IDENT.sub("_", text)


def flag_key(step_id: str) -> str:
    return f"done_{ident(step_id)}"


def lock_key(spot: str) -> str:
    return f"lock_{ident(spot)}"


def failed_key(robot: str) -> str:
    return f"failed_{ident(robot)}"
