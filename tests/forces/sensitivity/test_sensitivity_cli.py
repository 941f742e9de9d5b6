"""``sunwind srp --sensitivities`` and ``sunwind drag --sensitivities``: the same numbers as the Python
calls, in JSON and as text."""

from __future__ import annotations

import json

import numpy as np

import sunwind as sw
from sunwind.geometry.io import save_mesh

MATERIALS = """
[materials.white]
reflectivity = 0.7
specular_fraction = 0.2
[materials."cell.glass"]
reflectivity = 0.1
specular_fraction = 0.9
transmissivity = 0.05
[parts]
bus = "white"
"wing_*" = { front = "cell.glass", back = "white" }
"""
AIR = ["--density", "3e-12", "--temperature", "900", "--composition", "O:0.8,N2:0.2"]


def files(tmp_path):
    mesh, materials = tmp_path / "craft.obj", tmp_path / "craft.toml"
    save_mesh(sw.meshes.box_wing(facet_size=0.5), mesh)
    materials.write_text(MATERIALS)
    return mesh, materials


def test_srp_sensitivities_on_the_command_line_are_the_python_ones(run_cli, tmp_path):
    mesh, materials = files(tmp_path)
    args = ("srp", mesh, "-m", materials, "--sun", "0.6", "0.7", "0.2", "--reflections", "specular")
    code, out, err = run_cli(*args, "--sensitivities", "--json")
    assert code == 0, err
    document = json.loads(out)["sensitivities"]
    model = sw.load(mesh, materials=materials)
    found = sw.srp(model, [0.6, 0.7, 0.2], reflections="specular", sensitivities=True).sensitivities
    mine = found.of("cell.glass.transmissivity")  # a material name holding a dot: split at the last
    assert np.allclose(document["cell.glass"]["transmissivity"]["force_N"], mine.force_N, rtol=1e-12, atol=0)
    code, text, err = run_cli(*args, "--sensitivities")
    assert code == 0, err
    assert "cell.glass.transmissivity" in text and "d torque [N m]" in text
    _, plain, _ = run_cli(*args)
    assert "d/d coefficient" not in plain


def test_drag_sensitivities_on_the_command_line(run_cli, tmp_path):
    mesh, materials = files(tmp_path)
    args = ("drag", mesh, "-m", materials, "--velocity", "7600", "300", "0", *AIR, "--reflections", "none")
    code, out, err = run_cli(*args, "--sensitivities", "--json")
    assert code == 0, err
    document = json.loads(out)["sensitivities"]
    assert np.any(document["white"]["energy_accommodation"]["force_N"])
    assert not np.any(document["white"]["reflectivity"]["force_N"])  # drag reads no optics
