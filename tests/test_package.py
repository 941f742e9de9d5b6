"""Installed, the distribution is one package: ``sunwind`` and its subpackages, nothing else on the path."""

import subprocess
import sys


def run(code: str, cwd) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, capture_output=True, text=True)


def test_only_sunwind_is_importable_outside_the_checkout(tmp_path):
    found = run(
        "import sunwind.forces, sunwind.geometry, sunwind.meshes, sunwind.validation; print('ok')", tmp_path
    )
    assert found.stdout.strip() == "ok", found.stderr
    for name in ("forces", "geometry", "meshes", "validation"):
        missing = run(f"import {name}", tmp_path)
        assert missing.returncode == 1 and "ModuleNotFoundError" in missing.stderr, name


def test_python_m_sunwind_runs_the_command_line(tmp_path):
    result = subprocess.run(
        [sys.executable, "-m", "sunwind", "--version"], cwd=tmp_path, capture_output=True, text=True
    )
    assert result.returncode == 0 and result.stdout.startswith("sunwind "), result.stderr


def test_the_public_api_is_importable_under_its_documented_names(tmp_path):
    code = (
        "from sunwind.forces import load, srp, drag, sweep, nrlmsis, SrpSetup, DragSetup, SweepRun\n"
        "from sunwind.forces.export import write\n"
        "from sunwind.geometry import load_spacecraft, Spacecraft\n"
        "from sunwind.forces.gas import sentman, dria, schaaf_chambre, cll, specular, GSI_PARAMS\n"
        "print('ok')"
    )
    assert run(code, tmp_path).stdout.strip() == "ok"
