"""The named finishes library and ``finish = "NAME"`` in a materials file."""

from __future__ import annotations

import re

import pytest
import tomllib

from helpers import REPO
from sunwind.geometry import finishes
from sunwind.geometry.errors import MaterialError
from sunwind.geometry.finishes import FINISHES, Finish, finish
from sunwind.geometry.materials import GSI_MODELS, GasSurface, Material, load_materials, parse_materials

ENAMELS = {"khs-973": (0.715, 0.725), "khs-928": (0.925, 0.815), "ekom-1": (0.275, 0.91)}


@pytest.mark.parametrize("name", sorted(FINISHES))
def test_every_finish_is_a_valid_material_with_a_source(name):
    item = FINISHES[name]
    assert item.name == name and isinstance(item, Finish)
    material = Material.checked(name, item.keys)
    assert material.reflectivity == pytest.approx(1.0 - item.absorptance - item.transmissivity, abs=1e-9)
    assert material.absorptivity == pytest.approx(item.absorptance, abs=1e-9)
    assert material.emissivity == item.emissivity and material.specular_fraction == item.specular_fraction
    assert item.transmissivity == 0.0
    assert "specular_fraction estimated" in item.source  # no source tabulates it


def test_the_library_holds_the_enamels_and_a_dozen_handbook_finishes():
    assert 13 <= len(FINISHES) <= 18
    for name, (absorptance, emissivity) in ENAMELS.items():
        assert (FINISHES[name].absorptance, FINISHES[name].emissivity) == (absorptance, emissivity)
        assert "Lavochkin" in FINISHES[name].source and "eps_n" in FINISHES[name].source
    handbook = [f for f in FINISHES.values() if f.name not in ENAMELS]
    assert all(re.search("Gilmore|Henninger", f.source) for f in handbook)
    assert (FINISHES["az-93"].absorptance, FINISHES["az-93"].emissivity) == (0.15, 0.91)
    assert (FINISHES["osr"].absorptance, FINISHES["osr"].emissivity) == (0.07, 0.80)
    assert FINISHES["khs-973"].reflectivity == 0.285  # rounded, not 0.28500000000000003


def test_the_library_is_read_only():
    with pytest.raises(TypeError):
        FINISHES["new"] = FINISHES["gold"]  # type: ignore[index]
    with pytest.raises(AttributeError):
        FINISHES["gold"].emissivity = 0.5  # type: ignore[misc]


def test_finish_looks_up_and_suggests_close_names():
    assert finish("gold") is FINISHES["gold"]
    with pytest.raises(MaterialError) as error:
        finish("az93")
    assert str(error.value).startswith("finish = 'az93' is not in the finishes library")
    assert '"az-93"' in error.value.hint
    with pytest.raises(MaterialError, match="finish = 3 is not in the finishes library"):
        finish(3)


def test_a_material_takes_the_finish_and_keys_beside_it_override():
    spec = parse_materials(
        tomllib.loads(
            '[materials.a]\nfinish = "az-93"\n'
            '[materials.b]\nfinish = "az-93"\nspecular_fraction = 0.3\nemissivity = 0.8\n'
            '[materials.c]\nfinish = "osr"\nreflectivity = 0.5\ntransmissivity = 0.1\ngsi = "dria"\n'
        )
    )
    a, b, c = (spec.materials[n] for n in "abc")
    assert (a.reflectivity, a.specular_fraction, a.transmissivity, a.emissivity) == (0.85, 0.05, 0.0, 0.91)
    assert (b.reflectivity, b.specular_fraction, b.emissivity) == (0.85, 0.3, 0.8)
    assert (c.reflectivity, c.specular_fraction, c.transmissivity, c.emissivity) == (0.5, 0.95, 0.1, 0.8)
    assert c.gas.model == "dria"


@pytest.mark.parametrize(
    "body, expected",
    [
        ('finish = "az93"', "material 'a': finish = 'az93' is not in the finishes library"),
        ("finish = 7", "material 'a': finish = 7 is not in the finishes library"),
        ('finish = "osr"\nemissivity = 2', "emissivity = 2 is outside [0, 1]"),
        ('finish = "osr"\ntransmissivity = 0.5', "reflectivity + transmissivity = 1.43 exceeds 1"),
        ('finish = "osr"\ncolour = "white"', "unknown key 'colour'"),
    ],
)
def test_bad_finishes_fail_with_one_line_naming_the_file(tmp_path, body, expected):
    path = tmp_path / "materials.toml"
    path.write_text(f"[materials.a]\n{body}\n")
    with pytest.raises(MaterialError) as error:
        load_materials(path)
    message = str(error.value)
    assert expected in message and str(path) in message and "\n" not in message


def test_an_unknown_finish_lists_close_names():
    with pytest.raises(MaterialError) as error:
        parse_materials({"materials": {"a": {"finish": "silver-teflonn"}}}, "m.toml")
    assert '"silver-teflon"' in error.value.hint and "FINISHES" in error.value.hint
    with pytest.raises(MaterialError) as error:
        parse_materials({"materials": {"a": {"reflectivity": 0.5}}}, "m.toml")
    assert "or a finish" in error.value.hint


def test_the_gas_surface_parameters_are_still_importable_from_materials():
    assert GasSurface is finishes.GasSurface and GSI_MODELS is finishes.GSI_MODELS
    assert Material("m", 0.5, 0.5).gas == GasSurface()


def test_the_materials_guide_table_is_the_library():
    guide = (REPO / "docs" / "guides" / "meshes.md").read_text()
    section = guide.split("## Materials\n")[1].split("\n## ")[0]
    rows = re.findall(r"^\s*\| `([a-z0-9-]+)` \| [^|]+ \| ([\d.]+) \| ([\d.]+) \| ([\d.]+) \|", section, re.M)
    table = {name: tuple(map(float, numbers)) for name, *numbers in rows}
    assert table == {n: (f.absorptance, f.emissivity, f.specular_fraction) for n, f in FINISHES.items()}
