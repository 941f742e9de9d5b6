"""The examples in the docstrings run and print what they show: every module of the installed package
that has ``>>>`` examples is one test, its doctests run with ELLIPSIS and NORMALIZE_WHITESPACE in a
temporary working folder (an example that writes a file leaves nothing in the checkout)."""

from __future__ import annotations

import doctest
import importlib
import importlib.util
import io
import pkgutil
from pathlib import Path

import dask
import pytest

import sunwind

#: Modules whose import runs the program (``python -m sunwind``), not collected.
RUN_ON_IMPORT = {"sunwind.__main__"}
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


def _source(name: str) -> str:
    try:
        spec = importlib.util.find_spec(name)
    except Exception:  # a package whose __init__ fails: the test of it says why
        return ">>>"
    origin = spec.origin if spec else None
    return Path(origin).read_text(encoding="utf-8") if origin and origin.endswith(".py") else ""


def modules_with_examples() -> list[str]:
    """Every sunwind module whose source holds ``>>>``, found without importing the modules themselves
    (only the packages, to walk them); a package that fails to import is listed, and fails its test."""
    names = [sunwind.__name__]
    broken: list[str] = []
    walk = pkgutil.walk_packages(sunwind.__path__, prefix="sunwind.", onerror=broken.append)
    names += [info.name for info in walk if info.name not in RUN_ON_IMPORT]
    return sorted({name for name in names if ">>>" in _source(name)} | set(broken))


@pytest.mark.parametrize("name", modules_with_examples())
def test_docstring_examples(name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    module = importlib.import_module(name)
    tests = [t for t in doctest.DocTestFinder(exclude_empty=True).find(module, name) if t.examples]
    if not tests:
        pytest.skip(f"{name}: its '>>>' is not in a docstring doctest collects")
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    out = io.StringIO()
    scheduler = _dask_scheduler()
    for test in tests:
        runner.run(test, out=out.write)
    assert runner.failures == 0, (
        f"{runner.failures} of {runner.tries} examples failed in {name}:\n{out.getvalue()}"
    )
    # an example (or the code it runs) must not leave process-wide state behind: a Dask client that
    # failed to start once left dask's scheduler set, and every later netCDF write in that process failed
    assert _dask_scheduler() == scheduler, f"{name} left dask's global scheduler changed"


def _dask_scheduler() -> tuple:
    """Dask's process-wide scheduler settings, which a Dask client sets while it is open."""
    return dask.config.get("scheduler", None), dask.config.get("shuffle", None)
