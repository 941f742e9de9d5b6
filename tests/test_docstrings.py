"""Every public function and class has a numpydoc docstring that the API reference can show: a summary,
``Parameters`` for what it takes, ``Returns`` for what it gives, and an ``Examples`` section (which
``tests/test_doctests.py`` runs). Public: a name without a leading underscore, defined at module level in
a module whose own name has none; a public class's public methods and properties need a summary."""

import importlib
import inspect
import pkgutil

import pytest
from numpydoc.docscrape import ClassDoc, FunctionDoc

import sunwind

#: Modules whose public names are documented elsewhere: ``python -m sunwind`` (the click commands are
#: not functions: the CLI reference is generated from their help).
ELSEWHERE = ("sunwind.__main__",)


def public_modules() -> list[str]:
    names = [sunwind.__name__]
    for info in pkgutil.walk_packages(sunwind.__path__, "sunwind."):
        name = info.name
        if any(part.startswith("_") for part in name.split(".")) or name.startswith(ELSEWHERE):
            continue
        names.append(name)
    return sorted(names)


def own_public(module) -> list[tuple[str, object]]:
    """The public functions and classes ``module`` defines (numba kernels by their Python function)."""
    found = []
    for name, value in vars(module).items():
        if name.startswith("_"):
            continue
        value = getattr(value, "py_func", value)  # a numba dispatcher documents its Python function
        if (inspect.isfunction(value) or inspect.isclass(value)) and value.__module__ == module.__name__:
            found.append((name, value))
    return found


def problems_of(name: str, value: object) -> list[str]:
    doc = inspect.getdoc(value)
    if not doc:
        return [f"{name}: no docstring"]
    problems = []
    if inspect.isclass(value):
        parsed = ClassDoc(value, config={"show_class_members": False})
        if not (parsed["Attributes"] or parsed["Parameters"] or not _takes_arguments(value)):
            problems.append(f"{name}: no Attributes or Parameters section")
        for member, attribute in vars(value).items():
            if member.startswith("_"):
                continue
            target = getattr(attribute, "fget", getattr(attribute, "func", attribute))
            if callable(target) and not inspect.getdoc(target):
                problems.append(f"{name}.{member}: no docstring")
    else:
        parsed = FunctionDoc(value)
        signature = inspect.signature(value)
        if [p for p in signature.parameters if p not in ("self", "cls")] and not parsed["Parameters"]:
            problems.append(f"{name}: no Parameters section")
        returns = signature.return_annotation
        if returns not in (inspect.Signature.empty, None, "None") and not (
            parsed["Returns"] or parsed["Yields"]
        ):
            problems.append(f"{name}: no Returns section")
    if not parsed["Examples"]:
        problems.append(f"{name}: no Examples section")
    return problems


def _takes_arguments(kind: type) -> bool:
    try:
        return bool(inspect.signature(kind).parameters)
    except (TypeError, ValueError):
        return False


@pytest.mark.parametrize("module_name", public_modules())
def test_every_public_name_has_a_numpydoc_docstring_with_an_example(module_name):
    module = importlib.import_module(module_name)
    problems = [problem for name, value in own_public(module) for problem in problems_of(name, value)]
    assert not problems, "\n".join(problems)
