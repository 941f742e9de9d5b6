"""The materials file: parsing, range checks and their messages."""

import math

import pytest

from sunwind.geometry.errors import MaterialError
from sunwind.geometry.materials import Material, load_materials, part_matches

GOOD = """
[materials.white_paint]
reflectivity = 0.8         # rho
specular_fraction = 0.1    # beta
transmissivity = 0.0       # sigma
[materials.solar_cell]
reflectivity = 0.2
specular_fraction = 0.8
[materials.cfrp]
reflectivity = 0.1
specular_fraction = 0.0
[parts]
"wing*" = { front = "solar_cell", back = "cfrp" }
"antenna" = { front = "white_paint" }
"*" = "white_paint"
"""


def write(tmp_path, text):
    path = tmp_path / "materials.toml"
    path.write_text(text)
    return path


def test_a_good_file_parses_with_rules_in_order(tmp_path):
    spec = load_materials(write(tmp_path, GOOD))
    assert spec.materials["white_paint"] == Material("white_paint", 0.8, 0.1, 0.0)
    assert spec.materials["solar_cell"].transmissivity == 0.0
    assert math.isclose(spec.materials["white_paint"].absorptivity, 0.2)
    assert [r.pattern for r in spec.rules] == ["wing*", "antenna", "*"]
    wing = spec.rule_for("wing_left")
    assert (wing.front, wing.back, wing.sheet) == ("solar_cell", "cfrp", True)
    antenna = spec.rule_for("antenna")
    assert (antenna.back, antenna.sheet) == (None, True)
    assert spec.rule_for("bus").front == "white_paint" and not spec.rule_for("bus").sheet


def test_globs_match_full_names_and_usd_prim_path_leaves():
    assert part_matches("/craft/wing_left", "wing*")
    assert part_matches("/craft/wing_left", "/craft/*")
    assert not part_matches("/craft/bus", "wing*")


@pytest.mark.parametrize(
    "text, expected",
    [
        ("[materials.a]\nreflectivity = 0.5\nspecular_fraction = 0.1\ncolour = 1\n", "unknown key 'colour'"),
        (
            "[materials.a]\nreflectivity = 1.5\nspecular_fraction = 0.1\n",
            "reflectivity = 1.5 is outside [0, 1]",
        ),
        ("[materials.a]\nreflectivity = -0.1\nspecular_fraction = 0.1\n", "outside [0, 1]"),
        ("[materials.a]\nreflectivity = nan\nspecular_fraction = 0.1\n", "outside [0, 1]"),
        ("[materials.a]\nreflectivity = 0.7\nspecular_fraction = 0.1\ntransmissivity = 0.5\n", "exceeds 1"),
        ("[materials.a]\nreflectivity = '0.5'\nspecular_fraction = 0.1\n", "is not a number"),
        ("[materials.a]\nreflectivity = true\nspecular_fraction = 0.1\n", "is not a number"),
        ("[materials.a]\nreflectivity = 0.5\n", "lacks 'specular_fraction'"),
        ("[material.a]\nreflectivity = 0.5\n", "unknown top-level table 'material'"),
        ("[parts]\n'*' = 'missing'\n", "names material 'missing', which is not defined"),
        (
            "[materials.a]\nreflectivity = 0.5\nspecular_fraction = 0.1\n[parts]\n'w' = { top = 'a' }\n",
            "unknown key 'top'",
        ),
        ("[materials.a\nreflectivity = 0.5\n", "not valid TOML"),
    ],
)
def test_bad_files_fail_with_one_line_naming_the_file(tmp_path, text, expected):
    path = write(tmp_path, text)
    with pytest.raises(MaterialError) as error:
        load_materials(path)
    message = str(error.value)
    assert expected in message
    assert str(path) in message
    assert "\n" not in message


def test_missing_file(tmp_path):
    with pytest.raises(MaterialError, match="no such file"):
        load_materials(tmp_path / "absent.toml")
