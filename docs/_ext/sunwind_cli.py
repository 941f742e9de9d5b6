"""Sphinx extension: the command line's help texts read as plain text in the sphinx-click pages.

sphinx-click passes click's help strings to reST, where ``|v_rel|`` is a substitution reference (an
error) rather than the magnitude the terminal shows. Every ``|`` outside an inline literal is escaped,
except the marker of a line block, which sphinx-click writes itself for click's ``\\b`` paragraphs.
"""

from __future__ import annotations

import re
from typing import Any

from sphinx.application import Sphinx

LITERAL = re.compile(r"(``.+?``)")
EVENTS = ("description", "options", "arguments", "epilog")


def escape_bars(line: str) -> str:
    """``line`` with ``|`` escaped outside inline literals and line-block markers."""
    body = line.lstrip()
    indent = line[: len(line) - len(body)]
    marker = ""
    if body == "|" or body.startswith("| "):
        marker, body = body[:1], body[1:]
    parts = LITERAL.split(body)
    parts[::2] = [part.replace("|", r"\|") for part in parts[::2]]
    return indent + marker + "".join(parts)


def plain_help(app: Sphinx, ctx: Any, lines: list[str]) -> None:
    lines[:] = [escape_bars(line) for line in lines]


def setup(app: Sphinx) -> dict[str, Any]:
    app.setup_extension("sphinx_click")
    for event in EVENTS:
        app.connect(f"sphinx-click-process-{event}", plain_help)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
