"""Sphinx extension: the validation and benchmark tables, rendered at build time from checked-in JSON.

Two directives, each taking the artefact's path (relative to the page, or to the source folder with a
leading ``/``):

``sunwind-validation``
    The output of ``sunwind validate --quick --json``: a summary by reference (the family of closed
    forms or tracers a case is checked against), then one section per reference with a row per measure:
    case, where it was evaluated, measure, error, tolerance, pass.
``sunwind-bench``
    The output of ``sunwind bench --json``: one row per timed setting (time per attitude and the error
    of that setting against the reference), then the one-off costs and the model's size.

Both start with the provenance the regenerating script (``docs/_data/regenerate.py``) adds: the command,
date, machine and version. An artefact that is missing, unreadable, or lacks a field the tables need
is a build warning (an error under ``-W``), never a silently empty table.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any, ClassVar

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.application import Sphinx
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)


def cell(content: str | nodes.Node) -> nodes.entry:
    entry = nodes.entry()
    if isinstance(content, nodes.Node):
        entry += nodes.paragraph("", "", content)
    else:
        entry += nodes.paragraph(text=content)
    return entry


def table(headers: Sequence[str], rows: Sequence[Sequence[str | nodes.Node]], classes=()) -> nodes.table:
    """A docutils table with a header row (cells are text or inline nodes)."""
    node = nodes.table(classes=["sunwind-artefact", *classes])
    group = nodes.tgroup(cols=len(headers))
    node += group
    group.extend(nodes.colspec(colwidth=1) for _ in headers)
    head, body = nodes.thead(), nodes.tbody()
    head += nodes.row("", *(cell(text) for text in headers))
    body.extend(nodes.row("", *(cell(text) for text in row)) for row in rows)
    group += [head, body]
    return node


def number(value: Any, digits: int = 2) -> str:
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return f"{value:,}"
    if isinstance(value, float):
        if value == 0:
            return "0"
        return f"{value:.{digits}e}" if abs(value) < 1e-2 or abs(value) >= 1e5 else f"{value:.{digits + 1}g}"
    return str(value)


def verdict(passed: bool) -> nodes.Node:
    return nodes.strong(text="pass") if passed else nodes.emphasis(text="FAIL")


class ArtefactDirective(SphinxDirective):
    """Reads one JSON artefact; subclasses turn it into nodes."""

    required_arguments = 1
    has_content = False
    option_spec: ClassVar[dict] = {"command": directives.unchanged}

    def run(self) -> list[nodes.Node]:
        relative, path = self.env.relfn2path(self.arguments[0], self.env.docname)
        self.env.note_dependency(relative)
        try:
            data = json.loads(Path(path).read_text(encoding="utf-8"))
        except (OSError, ValueError) as error:
            logger.warning(f"cannot read the artefact {relative}: {error}", location=self.get_location())
            return []
        try:
            return [*self.provenance(data, relative), *self.render(data)]
        except (KeyError, TypeError, ValueError) as error:
            logger.warning(
                f"the artefact {relative} lacks what its tables need ({error!r}): regenerate it "
                "(docs/_data/README.md) or update docs/_ext/sunwind_artefacts.py",
                location=self.get_location(),
            )
            return []

    def provenance(self, data: dict, relative: str) -> list[nodes.Node]:
        """Where the numbers come from: the command, its date and machine."""
        given = data.get("provenance", {})
        command = given.get("command") or self.options.get("command")
        if not command:
            raise KeyError("provenance.command (or the directive's :command: option)")
        items = nodes.bullet_list()
        facts = [
            ("Regenerate with", nodes.literal(text=f"python docs/_data/regenerate.py {Path(relative).stem}")),
            ("Command", nodes.literal(text=command)),
            ("Artefact", nodes.literal(text=f"docs/{relative}")),
            ("Run on", nodes.Text(given.get("date", "date not recorded"))),
            ("Machine", nodes.Text(given.get("machine") or data.get("machine") or "not recorded")),
        ]
        if "sunwind" in given:
            facts.append(("Versions", nodes.Text(f"sunwind {given['sunwind']}, Python {given['python']}")))
        if "wall_s" in given:
            facts.append(("Wall time", nodes.Text(f"{given['wall_s']:.0f} s")))
        if "note" in given:
            facts.append(("Note", nodes.Text(given["note"])))
        for label, value in facts:
            item = nodes.list_item()
            item += nodes.paragraph("", "", nodes.strong(text=f"{label}: "), value)
            items += item
        return [items]

    def render(self, data: dict) -> list[nodes.Node]:
        raise NotImplementedError

    def section(self, title: str, *children: nodes.Node) -> nodes.section:
        node = nodes.section()
        node += nodes.title(text=title)
        node["names"].append(nodes.fully_normalize_name(title))
        self.state.document.note_implicit_target(node, node)
        node.extend(children)
        return node


class ValidationDirective(ArtefactDirective):
    """``sunwind validate --json``: checks grouped by reference, one row per measure."""

    def render(self, data: dict) -> list[nodes.Node]:
        checks = data["checks"]
        families: dict[str, list[dict]] = {}
        for check in checks:
            families.setdefault(check["family"], []).append(check)
        scope = "the quick subset" if data.get("quick") else "every case"
        failed = data["failed"]
        outcome = nodes.paragraph(
            "",
            "",
            nodes.Text(f"{scope[:1].upper()}{scope[1:]}: "),
            nodes.strong(text=f"{data['passed']} passed, {failed} failed"),
            nodes.Text(
                ". The error of each measure is its distance from the reference, on the scale the "
                "tolerance is given in (relative, or in standard errors of a tracer where the measure "
                "says so)."
            ),
        )
        summary = []
        for family, group in families.items():
            worst = max(
                (m["value"] / m["limit"] for c in group for m in c["measures"] if m["limit"]), default=0.0
            )
            passed = sum(c["passed"] for c in group)
            summary.append([family, str(len(group)), f"{passed} / {len(group)}", number(worst)])
        out: list[nodes.Node] = [
            outcome,
            table(["Reference", "Checks", "Passed", "Worst error / tolerance"], summary),
        ]
        for family, group in families.items():
            rows = [
                [c["case"], c["at"], m["name"], number(m["value"]), number(m["limit"]), verdict(c["passed"])]
                for c in group
                for m in c["measures"]
            ]
            headers = ["Case", "At", "Measure", "Error", "Tolerance", "Pass"]
            out.append(self.section(family, table(headers, rows, ["sunwind-validation"])))
        return out


#: The benchmark's timed settings: label, key of the mean and of the median time per attitude [ms] (None:
#: not measured), key of the setting's error (a LoadError; None: no loads). ``{fixed}``: the fixed sampling.
TIMED = (
    ("SRP direct, default shadow pass", "default_ms", "default_median_ms", "default_error"),
    ("SRP direct, {fixed}", "fixed_ms", "fixed_median_ms", "fixed_error"),
    ("SRP direct, {attitudes} attitudes as one batch, default pass", "default_batch_ms", None, None),
    ("SRP direct, {attitudes} attitudes as one batch, {fixed}", "fixed_batch_ms", None, None),
    ("Raw Embree on the rays of {fixed}", "raw_embree_ms", None, None),
    ("SRP full reflections, default pass", "full_ms", "full_median_ms", "full_error"),
    ("SRP full reflections, {fixed}", "fixed_full_ms", None, "fixed_full_error"),
    ("Drag, no re-emission, default", None, "drag_ms", "drag_error"),
    ("Drag, no re-emission, {fixed}", None, "fixed_drag_ms", "fixed_drag_error"),
    ("Drag, full re-emission", None, "drag_full_ms", "drag_full_error"),
)
#: One-off costs per model: label, key [s].
ONCE = (
    ("Load the mesh", "load_s"),
    ("Build the ray-tracing scene", "scene_build_s"),
    ("First call (compilation)", "first_call_s"),
    ("View factors (full reflections)", "view_factor_s"),
    ("Diffuse balance setup", "exchange_setup_s"),
    ("Open sky (drag)", "sky_s"),
)


class BenchDirective(ArtefactDirective):
    """``sunwind bench --json``: time per attitude of each setting with its error, then one-off costs."""

    def render(self, data: dict) -> list[nodes.Node]:
        fixed = f"{data['samples_per_side']} point(s) per side"
        rows = []
        for label, mean_key, median_key, error_key in TIMED:
            error = data[error_key] if error_key else None
            rows.append(
                [
                    label.format(fixed=fixed, attitudes=data["attitudes"]),
                    f"{data[mean_key]:.2f}" if mean_key else "—",
                    f"{data[median_key]:.2f}" if median_key else "—",
                    number(error["force_worst"]) if error else "—",
                    number(error["torque_worst"]) if error else "—",
                    number(error["force_median"]) if error else "—",
                ]
            )
        headers = ["Setting", "Mean [ms]", "Median [ms]", "Force error, worst", "Torque error, worst"]
        timed = table([*headers, "Force error, median"], rows, ["sunwind-bench"])
        once = table(["One-off cost per model", "Time [s]"], [[a, f"{data[k]:.2f}"] for a, k in ONCE])
        model = nodes.paragraph(
            text=(
                f"Model: {data.get('mesh', 'the generated sample spacecraft')}, {data['triangles']:,} "
                f"triangles, {data['sides']:,} sides; {data['attitudes']} attitudes timed on "
                f"{data['threads']} threads; peak memory {data['peak_memory_MB']:.0f} MB. The errors are "
                "relative, against a reference run of each attitude at a ten times tighter shadow "
                "tolerance (and finer gas sampling for drag); times are per attitude, a batch's divided by "
                "its size."
            )
        )
        return [model, timed, once]


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("sunwind-validation", ValidationDirective)
    app.add_directive("sunwind-bench", BenchDirective)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
