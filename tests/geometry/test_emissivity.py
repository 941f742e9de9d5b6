"""Infrared emissivity: the material key, the table column, the sides' emissivity and infrared optics."""

from __future__ import annotations

import math
import pickle
from dataclasses import replace

import numpy as np
import pytest
import tomllib

from helpers import quad_sheet
from sunwind.geometry.errors import MaterialError
from sunwind.geometry.materials import Material, MaterialTable, load_materials, parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft, infrared_optics, load_spacecraft
from sunwind.meshes.primitives import box
from sunwind.meshes.samples import SAMPLE_EMISSIVITY, SAMPLE_OPTICS, sample_materials_path, sample_path

MATERIALS = """
[materials.paint]
reflectivity = 0.8
specular_fraction = 0.1
emissivity = 0.9
[materials.cell]
reflectivity = 0.1
specular_fraction = 0.8
emissivity = 0.85
[materials.mli]
reflectivity = 0.6
specular_fraction = 0.4
[materials.kapton]
reflectivity = 0.5
specular_fraction = 0.4
[parts]
"bus" = "paint"
"wing" = { front = "cell", back = "paint" }
"""


def bus_and_wing(text: str = MATERIALS, source: str | None = "m.toml"):
    """A closed bus and a two-sided wing sheet, with the materials file ``text``."""
    bus = replace(box((1.0, 1.0, 1.0)), part_names=("bus",))
    wing = quad_sheet(np.array([[0, 1, 0], [1, 1, 0], [1, 3, 0], [0, 3, 0.0]]), "wing", 2)
    mesh = MeshData.concatenate([bus, wing], source="craft.obj")
    return build_spacecraft(mesh, parse_materials(tomllib.loads(text), source))


def test_emissivity_is_read_and_none_when_not_given():
    spec = parse_materials(tomllib.loads(MATERIALS))
    assert spec.materials["paint"].emissivity == 0.9
    assert spec.materials["mli"].emissivity is None
    assert Material("m", 0.5, 0.5).emissivity is None
    assert (
        Material.checked("m", {"reflectivity": 0.5, "specular_fraction": 0.5, "emissivity": 1}).emissivity
        == 1.0
    )


@pytest.mark.parametrize(
    "value, expected",
    [
        ("1.5", "emissivity = 1.5 is outside [0, 1]"),
        ("-0.1", "emissivity = -0.1 is outside [0, 1]"),
        ("nan", "emissivity = nan is outside [0, 1]"),
        ("inf", "emissivity = inf is outside [0, 1]"),
        ("'0.9'", "emissivity = '0.9' is not a number"),
        ("true", "emissivity = True is not a number"),
        ("[0.9]", "emissivity = [0.9] is not a number"),
    ],
)
def test_bad_emissivity_fails_with_one_line_naming_the_file(tmp_path, value, expected):
    path = tmp_path / "materials.toml"
    path.write_text(f"[materials.a]\nreflectivity = 0.5\nspecular_fraction = 0.1\nemissivity = {value}\n")
    with pytest.raises(MaterialError) as error:
        load_materials(path)
    message = str(error.value)
    assert expected in message and "material 'a'" in message
    assert str(path) in message and "use a number in [0, 1]" in message and "\n" not in message


def test_the_table_column_is_nan_where_absent_and_survives_indexing_and_gas_changes():
    materials = [Material("a", 0.5, 0.1, emissivity=0.7), Material("b", 0.2, 0.3, 0.1)]
    table = MaterialTable.from_materials(materials)
    assert table.eps.dtype == np.float64 and not table.eps.flags.writeable
    assert table.eps[0] == 0.7 and math.isnan(table.eps[1])
    assert [table[i] for i in range(2)] == materials
    changed = table.with_gas(wall_temperature_K=500.0)
    assert changed.eps is table.eps and changed[0].emissivity == 0.7
    assert MaterialTable.from_materials([]).eps.shape == (0,)


def test_sides_carry_their_materials_emissivity():
    craft = bus_and_wing()
    names = np.array(craft.materials.names)[craft.side_material]
    expected = np.where(names == "cell", 0.85, 0.9)
    assert craft.side_emissivity.shape == (craft.n_sides,) and craft.side_emissivity.dtype == np.float64
    assert np.array_equal(craft.side_emissivity, expected)
    assert not craft.side_emissivity.flags.writeable
    with pytest.raises(ValueError):
        craft.side_emissivity[0] = 0.5


def test_infrared_optics_are_one_minus_emissivity_diffuse_and_opaque():
    craft = bus_and_wing()
    optics = infrared_optics(craft)
    assert optics.shape == (craft.n_sides, 3) and optics.dtype == np.float64
    assert np.allclose(optics[:, 0], 1.0 - craft.side_emissivity)
    assert not optics[:, 1:].any()  # no specular part, nothing through a sheet
    assert optics.flags.c_contiguous and not optics.flags.writeable
    assert (craft.side_optics[:, 2] == 0).all()  # the solar optics are untouched


def test_a_material_without_emissivity_loads_and_only_the_infrared_refuses_it():
    text = MATERIALS.replace('"bus" = "paint"', '"bus" = "mli"')
    craft = bus_and_wing(text)
    assert np.isnan(craft.side_emissivity[craft.side_material == craft.materials.names.index("mli")]).all()
    assert craft.side_optics.shape == (craft.n_sides, 3)  # the solar band is unaffected
    with pytest.raises(MaterialError) as error:
        infrared_optics(craft)
    message = str(error.value)
    assert message == (
        "m.toml: material 'mli' has no emissivity; add emissivity = ... (infrared, 0 to 1) to "
        '[materials.mli], or finish = "NAME" from the finishes library'
    )


def test_every_material_without_emissivity_is_named_once_unused_ones_not():
    text = MATERIALS.replace('"bus" = "paint"', '"bus" = "mli"').replace('back = "paint"', 'back = "mli"')
    text = text.replace('front = "cell"', 'front = "kapton"')
    craft = bus_and_wing(text)
    with pytest.raises(MaterialError) as error:
        infrared_optics(craft)
    assert str(error.value) == (
        "m.toml: materials 'mli', 'kapton' have no emissivity; add emissivity = ... (infrared, 0 to 1) to "
        '[materials.mli], [materials.kapton], or finish = "NAME" from the finishes library'
    )
    assert "paint" not in str(error.value)


def test_without_a_materials_file_the_error_names_the_mesh_file():
    sheet = quad_sheet(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.0]]), "panel")
    mesh = replace(sheet, source="panel.obj")
    craft = build_spacecraft(mesh, uniform=Material("grey", 0.2, 0.1), two_sided=["panel"])
    assert craft.materials_source is None
    with pytest.raises(MaterialError, match=r"^panel\.obj: material 'grey' has no emissivity"):
        infrared_optics(craft)
    grey = build_spacecraft(mesh, uniform=Material("grey", 0.2, 0.1, emissivity=0.3), two_sided=["panel"])
    assert np.allclose(infrared_optics(grey), [0.7, 0.0, 0.0])


def test_the_materials_source_travels_with_the_model():
    craft = bus_and_wing(source="file.toml")
    assert craft.materials_source == "file.toml"
    assert pickle.loads(pickle.dumps(craft)).side_emissivity.tolist() == craft.side_emissivity.tolist()


def test_the_sample_spacecraft_gives_every_material_an_emissivity_and_keeps_its_solar_optics():
    spec = load_materials(sample_materials_path())
    assert set(SAMPLE_EMISSIVITY) == set(SAMPLE_OPTICS) == set(spec.materials)
    for name, material in spec.materials.items():
        assert material.emissivity == SAMPLE_EMISSIVITY[name]
        assert (material.reflectivity, material.specular_fraction, material.transmissivity) == tuple(
            SAMPLE_OPTICS[name].values()
        )
    tracking = load_materials(sample_path("sample_spacecraft_tracking.toml"))
    assert {n: m.emissivity for n, m in tracking.materials.items()} == SAMPLE_EMISSIVITY
    craft = load_spacecraft(sample_path(), sample_materials_path())
    assert not np.isnan(craft.side_emissivity).any()
    assert np.allclose(infrared_optics(craft)[:, 0], 1.0 - craft.side_emissivity)
