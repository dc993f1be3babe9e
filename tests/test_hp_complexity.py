"""The planner stays one can read (issue 28): no function in src/emboteam/hp above
cyclomatic complexity 25, as radon counts it, and hp/planner.py (which only composes the
stages) under 300 lines.

Measured through radon's own API (``radon.complexity.cc_visit``, what ``radon cc`` prints),
not by counting keywords: radon is a test dependency (pyproject's ``test`` extra), so this
test runs wherever the suite does.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from pathlib import Path

from radon.complexity import cc_visit
from radon.visitors import Class, Function

import emboteam.hp

HP = Path(emboteam.hp.__file__).resolve().parent
MAX_COMPLEXITY = 25
MAX_PLANNER_LINES = 300


def _functions(blocks: Iterable[Function | Class], prefix: str = "") -> Iterator[tuple[str, int, int]]:
    """(qualified name, line, complexity) of every function, method and closure in
    ``blocks`` (``cc_visit`` lists the methods of a module's classes, not the closures nor
    the methods of inner classes: each is a function of its own here, measured alone)."""
    for b in blocks:
        if isinstance(b, Class):
            yield from _functions([*b.methods, *b.inner_classes], f"{prefix}{b.name}.")
            continue
        name = f"{prefix}{b.name}" if prefix else b.fullname
        yield name, b.lineno, b.complexity
        yield from _functions(b.closures, f"{name}.")


def too_complex(code: str, limit: int = MAX_COMPLEXITY) -> list[tuple[str, int]]:
    """The functions of ``code`` above ``limit``, with their complexity."""
    measured = {(name, line): cc for name, line, cc in _functions(cc_visit(code))}
    return [(name, cc) for (name, _), cc in sorted(measured.items(), key=lambda kv: kv[0][1]) if cc > limit]


def test_the_check_sees_a_complex_function() -> None:
    branches = [f"if x == {i}:\n    return {i}" for i in range(MAX_COMPLEXITY)]
    body = "\n".join(branches) + "\nreturn -1"

    def indented(text: str, level: int) -> str:
        return "".join(" " * 4 * level + line + "\n" for line in text.splitlines())

    assert too_complex(f"def f(x):\n{indented(body, 1)}") == [("f", MAX_COMPLEXITY + 1)]
    assert too_complex(f"class C:\n    def m(self, x):\n{indented(body, 2)}") == [("C.m", MAX_COMPLEXITY + 1)]
    assert too_complex(f"def g(x):\n    def h(x):\n{indented(body, 2)}    return h\n") == [("g.h", MAX_COMPLEXITY + 1)]
    inner = f"class C:\n    class D:\n        def n(self, x):\n{indented(body, 3)}"
    assert too_complex(inner) == [("C.D.n", MAX_COMPLEXITY + 1)]
    shorter = "\n".join(branches[1:]) + "\nreturn -1"
    assert too_complex(f"def f(x):\n{indented(shorter, 1)}") == []


def test_no_hp_function_above_the_limit() -> None:
    files = sorted(HP.rglob("*.py"))
    assert len(files) > 20  # the whole package is measured, stages included
    over = [f"{p.relative_to(HP)}: {name} {cc}" for p in files for name, cc in too_complex(p.read_text())]
    assert not over, f"cyclomatic complexity above {MAX_COMPLEXITY} (radon): {over}"


def test_planner_module_is_short() -> None:
    lines = len((HP / "planner.py").read_text().splitlines())
    assert lines < MAX_PLANNER_LINES, f"hp/planner.py has {lines} lines (limit: under {MAX_PLANNER_LINES})"
