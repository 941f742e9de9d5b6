"""The house: one installed package, imports that flow one way, small modules and short signatures,
and every METHOD.md section the code and README cite present in METHOD.md."""

from __future__ import annotations

import ast
import re
import sys
from functools import cache
from pathlib import Path

import pytest
import tomllib

from helpers import REPO

ROOT = REPO
PACKAGES = ("forces", "geometry", "meshes", "validation")
#: Longest module [lines of code: docstrings, comments and blank lines not counted, so that documenting
#: a module never splits it] and most parameters of a function outside the numba kernels.
MAX_LINES, MAX_PARAMETERS = 500, 8


def module_name(path: Path) -> str:
    parts = ["sunwind", *path.relative_to(ROOT).with_suffix("").parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@cache
def modules() -> dict[str, Path]:
    files = [p for package in PACKAGES for p in (ROOT / package).rglob("*.py")]
    return {module_name(p): p for p in [*files, ROOT / "__init__.py", ROOT / "__main__.py"]}


@cache
def tree(name: str) -> ast.Module:
    return ast.parse(modules()[name].read_text())


def imports(name: str) -> dict[str, bool]:
    """The sunwind modules ``name`` imports, each with whether the import is at module level (not
    inside a function); every import counts, lazy and ``TYPE_CHECKING`` ones included."""
    path, found = modules()[name], {}
    inside = {id(n) for f in ast.walk(tree(name)) if isinstance(f, ast.FunctionDef) for n in ast.walk(f)}
    for node in ast.walk(tree(name)):
        targets = []
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
                base = ".".join(
                    package[: len(package) - node.level + 1] + ([node.module] if node.module else [])
                )
            targets = [
                f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules() else base
                for alias in node.names
            ]
        elif isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        for target in targets:
            if target in modules():
                found[target] = found.get(target, False) or id(node) not in inside
    return found


def test_the_repository_installs_as_one_package_with_every_folder_listed():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert config["package-dir"] == {"sunwind": "."}
    folders = {
        module_name(p.parent / "__init__.py")
        for package in PACKAGES
        for p in (ROOT / package).rglob("__init__.py")
    }
    assert set(config["packages"]) == {"sunwind", *folders}
    old = re.compile(rf"^\s*(from|import)\s+({'|'.join(PACKAGES)})\b", re.M)
    for path in [*modules().values(), *(ROOT / "tests").rglob("*.py")]:
        assert not old.search(path.read_text()), (
            f"{path} imports a top-level {old.search(path.read_text())[2]}"
        )
    for block in re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), flags=re.S):
        assert not old.search(block), "README imports a package by its old name"


def test_no_module_imports_another_in_a_circle():
    graph = {name: set(imports(name)) for name in modules()}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    circles = []
    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10_000))

    def visit(v: str) -> None:  # Tarjan's strongly connected components
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while (w := stack.pop()) != v:
                component.append(w)
            if component:
                circles.append(sorted([v, *component]))

    for v in graph:
        if v not in index:
            visit(v)
    assert not circles


#: What each part of the package may import of sunwind (module-name prefixes), floor by floor.
LAYERS = {
    "sunwind.geometry": ("sunwind.geometry",),
    "sunwind.meshes": ("sunwind.geometry", "sunwind.meshes"),
    "sunwind.forces.model": ("sunwind.geometry",),
    # the record of derivatives, which every floor that makes them fills
    "sunwind.forces.sensitivity": ("sunwind.geometry", "sunwind.forces.vocabulary"),
    "sunwind.forces.radiation": (
        "sunwind.geometry",
        "sunwind.forces.sensitivity",
        "sunwind.forces.radiation",
    ),
    "sunwind.forces.reflection": (
        "sunwind.geometry",
        "sunwind.forces.sensitivity",
        "sunwind.forces.radiation",
        "sunwind.forces.reflection",
    ),
    "sunwind.forces.gas": (
        "sunwind.geometry",
        "sunwind.forces.sensitivity",
        "sunwind.forces.radiation",
        "sunwind.forces.reflection",
        "sunwind.forces.gas",
    ),
    "sunwind.forces.export": ("sunwind.geometry", "sunwind.forces"),
    "sunwind.forces.cli": ("sunwind.geometry", "sunwind.meshes", "sunwind.forces"),
    "sunwind.forces.bench": ("sunwind.geometry", "sunwind.meshes", "sunwind.forces"),
    "sunwind.forces.sweep_bench": ("sunwind.geometry", "sunwind.meshes", "sunwind.forces"),
    "sunwind.forces": ("sunwind.geometry", "sunwind.forces"),
}
#: The independent references: closed forms and brute-force tracers, which import nothing of the solver.
REFERENCES = re.compile(r"sunwind\.validation\.(analytic|photon|tpmc)")


def reached(name: str) -> set[str]:
    """Every sunwind module ``name`` imports, directly or through others."""
    seen, todo = set(), [name]
    while todo:
        for target in imports(todo.pop()):
            if target not in seen:
                seen.add(target)
                todo.append(target)
    return seen


def layer(name: str) -> tuple[str, ...] | None:
    owners = [
        prefix
        for prefix in LAYERS
        if name == prefix or name.startswith(prefix + ".") or name.startswith(prefix + "_")
    ]
    return LAYERS[max(owners, key=len)] if owners else None


@pytest.mark.parametrize("name", sorted(modules()))
def test_imports_flow_one_way(name):
    """geometry <- meshes; geometry <- forces' floors (model, radiation, reflection, gas, results and
    entry points, tables) <- {export, cli}; the closed forms and tracers import at most geometry;
    nothing in forces imports validation at module level, nor export or cli below them."""
    allowed = layer(name)
    if REFERENCES.match(name):
        assert not {t for t in reached(name) if t.startswith(("sunwind.forces", "sunwind.meshes"))}
    for target, top_level in imports(name).items():
        if target.startswith("sunwind.validation") and name.startswith("sunwind.forces"):
            assert not top_level and name == "sunwind.forces.cli.tools", f"{name} imports {target}"
            continue
        below_export = name.startswith("sunwind.forces") and not name.startswith(
            ("sunwind.forces.export", "sunwind.forces.cli")
        )
        if below_export:
            assert not target.startswith(("sunwind.forces.export", "sunwind.forces.cli")), (
                f"{name} imports {target}"
            )
        if allowed is not None:
            assert target == "sunwind" or target.startswith(allowed), f"{name} imports {target}"


def code_lines(name: str) -> int:
    """Lines of module ``name`` that hold code: not blank, not only a comment, not in a docstring."""
    lines = modules()[name].read_text().splitlines()
    documented = set()
    for node in ast.walk(tree(name)):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            first = node.body[0] if node.body else None
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                if isinstance(first.value.value, str):
                    documented.update(range(first.lineno - 1, first.end_lineno))
    return sum(
        1
        for k, line in enumerate(lines)
        if k not in documented and line.strip() and not line.strip().startswith("#")
    )


def test_code_lines_leave_out_docstrings_and_comments():
    assert (
        0
        < code_lines("sunwind.forces.vocabulary")
        < len(modules()["sunwind.forces.vocabulary"].read_text().splitlines())
    )


@pytest.mark.parametrize("name", sorted(modules()))
def test_modules_are_small_and_signatures_short(name):
    assert code_lines(name) <= MAX_LINES
    for node in ast.walk(tree(name)):
        if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            continue
        if any("njit" in ast.unparse(d) or "numba" in ast.unparse(d) for d in node.decorator_list):
            continue  # numba kernels take their arrays one by one
        a = node.args
        count = len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs) + bool(a.vararg) + bool(a.kwarg)
        count -= bool(a.args) and a.args[0].arg in ("self", "cls")
        assert count <= MAX_PARAMETERS, f"{name}.{node.name} takes {count} parameters"


def method_sections() -> set[str]:
    return set(re.findall(r"^## (.+?)\s*$", (ROOT / "METHOD.md").read_text(), flags=re.M))


def test_every_cited_method_section_exists():
    """``METHOD.md "Section"`` (several may follow: ``"A", "B"``) in code, help texts and README."""
    sections = method_sections()
    cited = re.compile(r'METHOD\.md,?\s+((?:"[^"]+"(?:,\s*|\s+and\s+)?)+)')
    texts = [*modules().values(), ROOT / "README.md"]
    found = 0
    for path in texts:
        for match in cited.finditer(re.sub(r"\s+", " ", path.read_text())):  # lines joined
            for name in re.findall(r'"([^"]+)"', match.group(1)):
                found += 1
                assert name in sections, f"{path.name} cites METHOD.md {name!r}, not a section there"
    assert found > 20


#: Functions a package exports under its own submodule's name, on purpose: ``from sunwind.forces import
#: srp, drag`` (the submodules stay importable as ``sunwind.forces.srp`` by ``from ... import``).
SHADOWING = {"sunwind.forces.srp", "sunwind.forces.drag"}


def test_no_package_hides_a_submodule_behind_another_name():
    import importlib

    for name, path in modules().items():
        if path.name != "__init__.py" or name == "sunwind":
            continue
        package = importlib.import_module(name)
        for child in modules():
            if child.rsplit(".", 1)[0] == name and child not in SHADOWING:
                value = getattr(package, child.rsplit(".", 1)[1], None)
                assert value is None or value is sys.modules.get(child), f"{child} is hidden by {value!r}"
