"""The code stays ruff clean: run as part of the test suite so CI checks it."""

import shutil
import subprocess

import pytest

from helpers import REPO

ROOT = REPO


@pytest.mark.skipif(shutil.which("ruff") is None, reason="ruff is installed with the [test] extra")
def test_ruff_finds_nothing():
    run = subprocess.run(["ruff", "check", "--quiet", str(ROOT)], capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, run.stdout + run.stderr
