"""Shared fixtures: a private view-factor cache, and a runner for the command line."""

from __future__ import annotations

import contextlib

import pytest

from sunwind.forces.cli.app import main
from sunwind.geometry.parallel import using_threads


@pytest.fixture(autouse=True, scope="session")
def _private_view_factor_cache(tmp_path_factory):
    """Keep view factors computed by tests out of the user's cache directory."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SUNWIND_CACHE_DIR", str(tmp_path_factory.mktemp("view-factor-cache")))
        yield


@pytest.fixture
def limit_threads():
    """``limit_threads(n)``: the rest of the test runs its parallel work on ``n`` threads."""
    with contextlib.ExitStack() as stack:
        yield lambda n: stack.enter_context(using_threads(n))


@pytest.fixture
def run_cli(capsys):
    """Run ``sunwind ARGS`` in-process; return (exit code, stdout, stderr)."""

    def run(*args: str) -> tuple[int, str, str]:
        code = 0
        try:
            main([str(a) for a in args])
        except SystemExit as exit_:
            code = int(exit_.code or 0)
        out = capsys.readouterr()
        return code, out.out, out.err

    return run


def pytest_addoption(parser):
    """``--update-docs``: tests/test_doc_outputs.py rewrites the printed outputs of README.md and the
    site's guides from actual runs."""
    parser.addoption(
        "--update-docs", action="store_true", help="rewrite the printed example outputs of README and docs"
    )


def pytest_configure(config):
    """``--update-docs`` rewrites files from every test: refuse it on several workers (``-n 0``)."""
    if config.getoption("--update-docs") and (getattr(config.option, "numprocesses", 0) or 0) > 0:
        raise pytest.UsageError("--update-docs writes README.md and docs/ from one process: add -n 0")
