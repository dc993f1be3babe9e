"""Assembling one self-contained HTML page from the packaged template, CSS and JS.

The page must open from a ``file://`` URL with no network, so styles and scripts are
inlined and the data travels as JSON inside ``<script type="application/json">``. A
browser ends a script element at the first ``</script`` whatever the JSON means, so
:func:`json_for_script` escapes ``<`` (and ``>``, ``&``, U+2028/2029) as ``\\uXXXX``
escapes, which JSON.parse turns back into the same characters.
"""

from __future__ import annotations

import html
import json
import re
from importlib import resources

_SCRIPT_UNSAFE = {"<": "\\u003c", ">": "\\u003e", "&": "\\u0026", "\u2028": "\\u2028", "\u2029": "\\u2029"}
_PLACEHOLDER = re.compile(r"\{\{(title|style|data|script|body)\}\}")


def json_for_script(data: object) -> str:
    """JSON text that can sit inside a ``<script>`` element without ending it."""
    text = json.dumps(data, ensure_ascii=False, separators=(",", ":"), allow_nan=False)
    return re.sub("[<>&\u2028\u2029]", lambda m: _SCRIPT_UNSAFE[m.group(0)], text)


def asset(name: str) -> str:
    """A file of ``emboteam/report/assets`` (package data)."""
    return resources.files("emboteam.report").joinpath("assets", name).read_text(encoding="utf-8")


def render_page(template: str, *, title: str, styles: list[str], scripts: list[str], data: object,
                body: str = "") -> str:
    """Fill ``template`` (an asset name) in one pass, so text substituted for one
    placeholder is never scanned for another."""
    script = "\n".join(asset(s) for s in scripts)
    if "</script" in script.lower():
        raise AssertionError("a packaged script contains '</script': it would end the element")
    values = {
        "title": html.escape(title),
        "style": "\n".join(asset(s) for s in styles),
        "data": json_for_script(data),
        "script": script,
        "body": body,
    }
    return _PLACEHOLDER.sub(lambda m: values[m.group(1)], asset(template))
