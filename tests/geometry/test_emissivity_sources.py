"""Emissivity from the command line (``--emissivity``) and from USD files (``sunwind:emissivity``): both
reach the material, as a materials file's ``emissivity`` does."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from pxr import Sdf, Usd, UsdGeom, UsdShade

from helpers.planet import materials_toml
from sunwind.forces.cli.options import uniform_material
from sunwind.geometry.errors import InputError, MaterialError, MeshError
from sunwind.geometry.io import load_mesh, save_mesh
from sunwind.geometry.materials import Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import load_spacecraft
from sunwind.meshes.primitives import box

#: The optics every source below gives the whole box.
SOLAR = {"reflectivity": 0.3, "specular_fraction": 0.0, "transmissivity": 0.0}
MATERIALS = materials_toml("paint", 0.3, 0.0, 0.8)
FLAGS = ["--reflectivity", "0.3", "--specular-fraction", "0", "--emissivity", "0.8"]
EARTH = ["--earth", "0", "0", "-1", "--altitude", "500", "--sun", "0", "0", "1"]


def write_usd_craft(path: Path, materials: dict[str, dict[str, float]]) -> None:
    """A stage with one unit box per material, ``/craft/<name>``, bound to Material ``<name>`` carrying
    ``materials[name]`` as ``float sunwind:*`` attributes (USD names, e.g. ``specularFraction``)."""
    cube = box((1.0, 1.0, 1.0))
    stage = Usd.Stage.CreateNew(str(path))
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    stage.SetDefaultPrim(UsdGeom.Xform.Define(stage, "/craft").GetPrim())
    for shift, (name, attributes) in enumerate(materials.items()):
        material = UsdShade.Material.Define(stage, f"/craft/Looks/{name}")
        for attribute, value in attributes.items():
            material.GetPrim().CreateAttribute(f"sunwind:{attribute}", Sdf.ValueTypeNames.Float).Set(value)
        mesh = UsdGeom.Mesh.Define(stage, f"/craft/{name}")
        mesh.CreatePointsAttr((cube.vertices + np.array([2.0 * shift, 0.0, 0.0])).tolist())
        mesh.CreateFaceVertexCountsAttr([3] * len(cube.faces))
        mesh.CreateFaceVertexIndicesAttr(cube.faces.ravel().tolist())
        UsdShade.MaterialBindingAPI.Apply(mesh.GetPrim()).Bind(material)
    stage.GetRootLayer().Save()


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Path:
    """A unit box as OBJ, its materials file, and the same box as USD carrying the optics itself."""
    folder = tmp_path_factory.mktemp("emissivity")
    save_mesh(box((1.0, 1.0, 1.0)), folder / "box.obj")
    (folder / "paint.toml").write_text(MATERIALS)
    usd = {"reflectivity": 0.3, "specularFraction": 0.0, "transmissivity": 0.0, "emissivity": 0.8}
    write_usd_craft(folder / "box.usda", {"paint": usd})
    return folder


# ------------------------------------------------------------------------------------- command line
def test_the_uniform_material_carries_the_flag_checked_as_a_materials_file_key():
    values = {"reflectivity": 0.3, "specular_fraction": 0.0, "transmissivity": None, "emissivity": 0.8}
    assert uniform_material(values) == Material("uniform", 0.3, 0.0, 0.0, emissivity=0.8)
    assert uniform_material({**values, "emissivity": None}).emissivity is None
    with pytest.raises(MaterialError, match=r"emissivity = 1.5 is outside \[0, 1\]"):
        uniform_material({**values, "emissivity": 1.5})
    with pytest.raises(InputError, match="needs --reflectivity and --specular-fraction"):
        uniform_material({**values, "reflectivity": None, "specular_fraction": None})


def _earth(run_cli, *args) -> dict:
    code, out, err = run_cli("earth", *args, *EARTH, "--thermal", "--json")
    assert code == 0, err
    return json.loads(out)


def _physics(doc: dict) -> dict:
    """What the run computes, without the names of parts and nodes (a USD part is its prim path)."""
    loads = {key: (doc[key]["force_N"], doc[key]["torque_Nm"]) for key in ("albedo", "infrared", "solar")}
    thermal = {key: value for key, value in doc["thermal"].items() if key != "node_temperature_K"}
    temperatures = sorted(doc["thermal"]["node_temperature_K"].values())
    return {**loads, "thermal": thermal, "temperatures": temperatures, "parts": list(doc["parts"].values())}


def _numbers(value: object) -> list[float]:
    """Every number in ``value`` (nested dicts, lists and tuples), in order."""
    if isinstance(value, dict):
        return [x for item in value.values() for x in _numbers(item)]
    if isinstance(value, list | tuple):
        return [x for item in value for x in _numbers(item)]
    return [value] if isinstance(value, int | float) else []


def test_emissivity_flag_gives_the_materials_file_result(run_cli, files):
    flags = _earth(run_cli, files / "box.obj", *FLAGS)
    toml = _earth(run_cli, files / "box.obj", "-m", files / "paint.toml")
    assert flags["parts"] == toml["parts"]
    assert _physics(flags) == _physics(toml)
    assert math.isfinite(flags["parts"]["box"]["temperature_K"])


def test_usd_emissivity_gives_the_materials_file_result(run_cli, files):
    usd = _earth(run_cli, files / "box.usda")
    toml = _earth(run_cli, files / "box.obj", "-m", files / "paint.toml")
    np.testing.assert_allclose(_numbers(_physics(usd)), _numbers(_physics(toml)), rtol=1e-12, atol=1e-20)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (
            ["--reflectivity", "0.3", "--specular-fraction", "0", "--emissivity", "1.5"],
            "emissivity = 1.5 is outside [0, 1]",
        ),
        (["--emissivity", "0.8"], "a uniform material needs --reflectivity and --specular-fraction"),
    ],
)
def test_bad_emissivity_flag_is_one_line(run_cli, files, extra, message):
    code, out, err = run_cli("earth", files / "box.obj", *extra, *EARTH)
    assert code == 1 and out == ""
    assert err.startswith("sunwind: error:") and message in err and err.count("\n") == 1, err


# ---------------------------------------------------------------------------------------------- USD
def test_usd_emissivity_is_optional_and_lands_in_the_material(tmp_path):
    path = tmp_path / "craft.usda"
    solar = {"reflectivity": 0.3, "specularFraction": 0.5, "transmissivity": 0.0}
    write_usd_craft(path, {"paint": {**solar, "emissivity": 0.8}, "foil": solar})
    mesh = load_mesh(path)
    foil = {**SOLAR, "specular_fraction": 0.5}
    assert mesh.file_optics == {"paint": {**foil, "emissivity": 0.8}, "foil": foil}  # float32 as written
    craft = load_spacecraft(path)
    by_name = {craft.materials[i].name: craft.materials[i] for i in range(len(craft.materials))}
    assert by_name["paint"] == Material("paint", 0.3, 0.5, 0.0, emissivity=0.8)
    assert by_name["foil"] == Material("foil", 0.3, 0.5, 0.0)  # as before: no emissivity
    part = np.array(craft.part_names)[craft.facet_part[craft.side_facet]]
    np.testing.assert_array_equal(craft.side_emissivity[part == "/craft/paint"], 0.8)
    assert np.isnan(craft.side_emissivity[part == "/craft/foil"]).all()


def test_usd_emissivity_round_trips_through_save_mesh(tmp_path):
    optics = {"paint": {**SOLAR, "emissivity": 0.8}}
    cube = box((1.0, 1.0, 1.0))
    mesh = MeshData(
        cube.vertices, cube.faces, cube.face_part, ("body",), np.zeros(len(cube.faces)), ("paint",)
    )
    save_mesh(mesh, tmp_path / "box.usda", optics=optics)
    assert "float sunwind:emissivity = 0.8" in (tmp_path / "box.usda").read_text()
    assert load_mesh(tmp_path / "box.usda").file_optics == optics


def test_usd_emissivity_is_checked_and_needs_the_solar_optics(tmp_path):
    hot = {"reflectivity": 0.3, "specularFraction": 0.0, "transmissivity": 0.0, "emissivity": 1.5}
    write_usd_craft(tmp_path / "hot.usda", {"paint": hot})
    with pytest.raises(MaterialError, match=r"material 'paint': emissivity = 1.5 is outside \[0, 1\]"):
        load_spacecraft(tmp_path / "hot.usda")
    write_usd_craft(tmp_path / "bare.usda", {"paint": {"emissivity": 0.8}})
    with pytest.raises(MeshError, match="has some sunwind optics but lacks sunwind:reflectivity"):
        load_mesh(tmp_path / "bare.usda")
