"""Sphinx extension: the API reference pages, written from the package itself before the sources are read.

``import sunwind as sw`` exposes the names of ``sunwind._PUBLIC`` (imported on first use through the
package's ``__getattr__``), so the list of public objects is read from that mapping at build time rather
than copied here. Its comments (``# the model``, ``# results``, ...) become the page's sections. A name
whose target does not import (a module being written) is left out with an info line, not a warning.

Written under ``docs/api/generated/`` (ignored by git, rewritten only where the text changes so an
incremental build stays incremental):

- ``public.rst``: the ``sunwind`` module docstring, one autosummary table per section, a hidden toctree;
- ``sunwind.<name>.rst``: one autodoc stub per public object (autoclass, autofunction, ...);
- ``<subpackage>.rst`` for each of ``sunwind_api_subpackages``: the module docstring and a table of its
  ``__all__``; a name that is also a public ``sw.`` name links to that page, the rest get stubs
  ``<subpackage>.<name>.rst``.
"""

from __future__ import annotations

import importlib
import inspect
import re
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

from sphinx.application import Sphinx
from sphinx.util import logging

logger = logging.getLogger(__name__)

GENERATED = "generated"
SUBPACKAGES = (
    "sunwind.forces.orbit",
    "sunwind.meshes",
    "sunwind.forces.export",
    "sunwind.forces.fit",
    "sunwind.forces.sensing",
    "sunwind.forces.sight",
)


@dataclass(frozen=True)
class Entry:
    """One documented object: its full dotted name, the object, and the directive that documents it."""

    name: str
    value: Any

    @property
    def short(self) -> str:
        return self.name.rpartition(".")[2]

    @property
    def owner(self) -> str:
        return self.name.rpartition(".")[0]

    @property
    def directive(self) -> str:
        if inspect.ismodule(self.value):
            return "automodule"
        if inspect.isclass(self.value):
            return "autoexception" if issubclass(self.value, BaseException) else "autoclass"
        if inspect.isroutine(self.value):
            return "autofunction"
        return "autodata"


def resolve(target: str) -> Any:
    """The object a ``_PUBLIC`` target names: ``package.module:attribute`` or a module alone."""
    module_name, _, attribute = target.partition(":")
    module = importlib.import_module(module_name)
    return getattr(module, attribute) if attribute else module


def public_sections(package: ModuleType) -> list[tuple[str, list[str]]]:
    """``_PUBLIC``'s names in its order, grouped under its comments; names outside any comment (or a
    mapping whose source cannot be read) go under "Other"."""
    names = list(package._PUBLIC)
    sections: list[tuple[str, list[str]]] = []
    try:
        source = Path(inspect.getsourcefile(package) or "").read_text(encoding="utf-8")
    except (OSError, TypeError):
        source = ""
    block = re.search(r"^_PUBLIC\b.*?=\s*\{(.*?)^\}", source, flags=re.S | re.M)
    for line in block.group(1).splitlines() if block else ():
        comment = re.match(r"\s*#\s*(.+?)\s*$", line)
        key = re.match(r"\s*[\"'](\w+)[\"']\s*:", line)
        if comment:
            sections.append((comment.group(1), []))
        elif key and key.group(1) in names:
            if not sections:
                sections.append(("Other", []))
            sections[-1][1].append(key.group(1))
    placed = {name for _, group in sections for name in group}
    rest = [name for name in names if name not in placed]
    if rest:
        sections.append(("Other", rest))
    return [(title[:1].upper() + title[1:], group) for title, group in sections if group]


def heading(text: str, mark: str = "=") -> list[str]:
    return [text, mark * len(text), ""]


def stub(entry: Entry) -> str:
    """The autodoc page of one object."""
    lines = [*heading(entry.name), f".. currentmodule:: {entry.owner}", ""]
    lines.append(f".. {entry.directive}:: {entry.short}")
    if entry.directive in ("autoclass", "autoexception"):
        lines += ["   :members:", "   :show-inheritance:"]
    elif entry.directive == "autodata" and not isinstance(entry.value, (int, float, str, bool)):
        lines.append("   :no-value:")
    return "\n".join(lines) + "\n"


def table(module: str, items: list[str], caption: str | None = None) -> list[str]:
    """An autosummary table (no ``:toctree:``: the stubs are this extension's, not autosummary's)."""
    lines = heading(caption, "-") if caption else []
    lines += [f".. currentmodule:: {module}", "", ".. autosummary::", "   :nosignatures:", ""]
    return lines + [f"   {item}" for item in items] + [""]


def hidden_toctree(pages: list[str]) -> list[str]:
    if not pages:
        return []
    return [".. toctree::", "   :hidden:", "", *(f"   {page}" for page in pages), ""]


class Writer:
    """Collects the generated pages, then writes those whose text changed and removes stale ones."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self.pages: dict[str, str] = {}

    def add(self, name: str, text: str) -> None:
        self.pages[name] = text

    def flush(self) -> None:
        self.folder.mkdir(parents=True, exist_ok=True)
        for old in self.folder.glob("*.rst"):
            if old.stem not in self.pages:
                old.unlink()
        for name, text in self.pages.items():
            path = self.folder / f"{name}.rst"
            if not path.exists() or path.read_text(encoding="utf-8") != text:
                path.write_text(text, encoding="utf-8")


def not_written_yet(error: Exception, target: str) -> bool:
    """Whether ``error`` only says that the target itself does not exist (its module, or the attribute
    in it): a name whose code is still to come. Any other failure (a module that exists but raises on
    import) is a broken package, which the build must not hide."""
    module_name, _, attribute = target.partition(":")
    if isinstance(error, ModuleNotFoundError):
        return error.name is not None and module_name.startswith(error.name)
    return isinstance(error, AttributeError) and bool(attribute) and repr(attribute) in str(error)


def public_entries(package: ModuleType) -> dict[str, Entry]:
    """Every ``_PUBLIC`` name that imports, as ``sunwind.<name>``. A target that does not exist yet is
    left out with an info line; one whose module fails to import is left out with a warning."""
    entries = {}
    for name, target in package._PUBLIC.items():
        try:
            value = resolve(target)
        except Exception as error:
            say = logger.info if not_written_yet(error, target) else logger.warning
            say(f"[sunwind_api] sunwind.{name} left out: {target} does not import ({error!r})")
            continue
        entries[name] = Entry(f"{package.__name__}.{name}", value)
    return entries


def public_page(package: ModuleType, entries: dict[str, Entry], writer: Writer) -> None:
    lines = [
        ".. The sunwind API reference: written by docs/_ext/sunwind_api.py from sunwind._PUBLIC.",
        "",
        *heading("The sunwind namespace"),
        f".. automodule:: {package.__name__}",
        "   :no-members:",
        "",
    ]
    pages = []
    for title, names in public_sections(package):
        present = [entries[name] for name in names if name in entries]
        items = []
        for entry in present:
            if inspect.ismodule(entry.value):  # a namespace: its own page, a subpackage's
                relative = entry.value.__name__.removeprefix(f"{package.__name__}.")
                items.append(f"~{relative}")  # autosummary refuses the current module's prefix
            else:
                items.append(entry.short)
                pages.append(entry.name)
                writer.add(entry.name, stub(entry))
        if items:
            lines += table(package.__name__, items, title)
    writer.add("public", "\n".join([*lines, *hidden_toctree(pages)]))


def subpackage_page(module_name: str, public: dict[int, str], writer: Writer) -> str | None:
    """The page of one subpackage; its name, or None if it does not import."""
    try:
        module = importlib.import_module(module_name)
    except Exception as error:  # listed in conf.py, so expected to exist: a warning
        logger.warning(f"[sunwind_api] {module_name} left out: it does not import ({error!r})")
        return None
    items, pages = [], []
    for name in getattr(module, "__all__", ()):
        try:
            value = getattr(module, name)
        except Exception as error:  # in __all__ but not there: a warning
            logger.warning(f"[sunwind_api] {module_name}.{name} is in __all__ but fails ({error!r})")
            continue
        if id(value) in public and not isinstance(value, (int, float, str, bool, tuple)):
            items.append(f"~{public[id(value)]}")  # documented once, on its sunwind.<name> page
            continue
        entry = Entry(f"{module_name}.{name}", value)
        items.append(name)
        pages.append(entry.name)
        writer.add(entry.name, stub(entry))
    lines = [
        f".. {module_name}: written by docs/_ext/sunwind_api.py from its __all__.",
        "",
        *heading(module_name),
        f".. automodule:: {module_name}",
        "   :no-members:",
        "",
        *(table(module_name, items, "Contents") if items else []),
        *hidden_toctree(pages),
    ]
    writer.add(module_name, "\n".join(lines))
    return module_name


def generate(app: Sphinx) -> None:
    """Write the API pages under ``<srcdir>/api/generated`` (the ``builder-inited`` handler)."""
    package = importlib.import_module(app.config.sunwind_api_package)
    writer = Writer(Path(app.srcdir) / "api" / GENERATED)
    entries = public_entries(package)
    public_page(package, entries, writer)
    public = {id(entry.value): entry.name for entry in entries.values()}
    for module_name in app.config.sunwind_api_subpackages:
        subpackage_page(module_name, public, writer)
    writer.flush()
    logger.info(f"[sunwind_api] {len(writer.pages)} API pages under api/{GENERATED}/")


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_config_value("sunwind_api_package", "sunwind", "env")
    app.add_config_value("sunwind_api_subpackages", SUBPACKAGES, "env")
    app.connect("builder-inited", generate, priority=400)  # before autosummary reads the sources
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
