"""The documentation site builds with every warning an error: the API pages from the docstrings
(numpydoc), the command-line reference from the click group, METHOD.md with its equations, the
validation and performance tables from their artefacts, and the gallery, whose scripts run."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
import time

import pytest

from helpers import REPO

DOCS = REPO / "docs"


@pytest.mark.slow
@pytest.mark.skipif(
    importlib.util.find_spec("sphinx") is None, reason="sphinx is not installed (pip install '.[docs]')"
)
def test_the_site_builds_without_warnings(tmp_path):
    command = [
        sys.executable,
        "-m",
        "sphinx",
        "-W",
        "--keep-going",
        "-b",
        "html",
        "-d",
        str(tmp_path / "doctrees"),
        "-D",
        "sphinx_gallery_conf.run_stale_examples=True",  # run every example, not only the changed ones
        str(DOCS),
        str(tmp_path / "html"),
    ]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, cwd=REPO, check=False)
    took = time.perf_counter() - start
    warnings = [line for line in done.stderr.splitlines() if "WARNING" in line or "ERROR" in line]
    assert done.returncode == 0 and not warnings, (
        f"sphinx-build exited {done.returncode} after {took:.0f} s with {len(warnings)} warnings:\n"
        + "\n".join(warnings)
        + "\n\nend of stderr:\n"
        + "\n".join(done.stderr.splitlines()[-40:])
    )
    assert (tmp_path / "html" / "index.html").is_file()
    for page in ("api/index", "cli", "method", "validation", "performance", "gallery/index"):
        assert (tmp_path / "html" / f"{page}.html").is_file(), f"{page} was not built"
