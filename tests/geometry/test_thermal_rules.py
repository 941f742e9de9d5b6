"""``[thermal."GLOB"]`` tables: parsing, their checks and messages, and the model that carries them."""

from __future__ import annotations

import math
import pickle
from dataclasses import replace

import numpy as np
import pytest
import tomllib

from helpers import quad_sheet
from sunwind.geometry.errors import MaterialError
from sunwind.geometry.materials import ThermalRule, load_materials, parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft, pose
from sunwind.meshes.primitives import box

PAINT = "[materials.w]\nreflectivity = 0.5\nspecular_fraction = 0.5\n"
PARTS = '[parts]\n"wing" = { front = "w", back = "w" }\n"*" = "w"\n'


def write(tmp_path, text: str):
    path = tmp_path / "materials.toml"
    path.write_text(text)
    return path


def craft_with(thermal: str, source: str = "m.toml"):
    """A closed bus and a two-sided wing sheet with the ``[thermal]`` tables ``thermal``."""
    bus = replace(box((1.0, 1.0, 1.0)), part_names=("/craft/bus",))
    wing = quad_sheet(np.array([[0, 1, 0], [1, 1, 0], [1, 3, 0], [0, 3, 0.0]]), "wing", 2)
    mesh = MeshData.concatenate([bus, wing], source="craft.obj")
    spec = parse_materials(tomllib.loads(PAINT + PARTS + thermal), source)
    return build_spacecraft(mesh, spec)


def test_rules_parse_in_order_with_their_defaults(tmp_path):
    spec = load_materials(
        write(
            tmp_path,
            '[thermal."bus"]\nisothermal = true\nheat_capacity_J_K = 4500\n'
            '[thermal."wing_*"]\nconductance_W_m2K = 200\n'
            '[thermal."boom"]\nconductance_W_m2K = "inf"\n'
            '[thermal."dish"]\nconductance_W_m2K = inf\n'
            '[thermal."*"]\n',
        )
    )
    assert spec.thermal == (
        ThermalRule("bus", isothermal=True, heat_capacity_J_K=4500.0),
        ThermalRule("wing_*", conductance_W_m2K=200.0),
        ThermalRule("boom"),
        ThermalRule("dish"),
        ThermalRule("*"),
    )
    rule = spec.thermal[0]
    assert rule.conductance_W_m2K == math.inf and isinstance(rule.heat_capacity_J_K, float)
    assert ThermalRule("x").isothermal is False and ThermalRule("x").heat_capacity_J_K is None
    assert parse_materials({}).thermal == ()


def test_a_rule_matches_full_names_and_prim_path_leaves():
    assert ThermalRule("wing*").matches("/craft/wing_left") and ThermalRule("/craft/*").matches("/craft/bus")
    assert not ThermalRule("wing*").matches("/craft/bus")


@pytest.mark.parametrize(
    "body, expected",
    [
        ("colour = 1", "[thermal] \"bus\" has unknown key 'colour'"),
        ("isothermal = 1", '[thermal] "bus": isothermal = 1 is not true or false'),
        ('isothermal = "yes"', "[thermal] \"bus\": isothermal = 'yes' is not true or false"),
        ("conductance_W_m2K = 0", "conductance_W_m2K = 0 W/(m^2 K) is not above 0 W/(m^2 K)"),
        ("conductance_W_m2K = -5.0", "conductance_W_m2K = -5 W/(m^2 K) is not above 0 W/(m^2 K)"),
        ("conductance_W_m2K = nan", "conductance_W_m2K = nan W/(m^2 K) is not above 0 W/(m^2 K)"),
        ('conductance_W_m2K = "infinite"', "conductance_W_m2K = 'infinite' is not a number"),
        ("conductance_W_m2K = true", "conductance_W_m2K = True is not a number"),
        ("heat_capacity_J_K = 0", "heat_capacity_J_K = 0 J/K is not above 0 J/K"),
        ("heat_capacity_J_K = -1e3", "heat_capacity_J_K = -1000 J/K is not above 0 J/K"),
        ("heat_capacity_J_K = inf", "heat_capacity_J_K = inf J/K is not above 0 J/K"),
        ('heat_capacity_J_K = "big"', "heat_capacity_J_K = 'big' is not a number"),
    ],
)
def test_bad_rules_fail_with_one_line_naming_the_file_and_a_fix(tmp_path, body, expected):
    path = write(tmp_path, f'[thermal."bus"]\n{body}\n')
    with pytest.raises(MaterialError) as error:
        load_materials(path)
    message = str(error.value)
    assert expected in message and str(path) in message and "\n" not in message
    assert error.value.hint


def test_a_conductance_error_says_inf_is_allowed(tmp_path):
    with pytest.raises(MaterialError) as error:
        load_materials(write(tmp_path, '[thermal."bus"]\nconductance_W_m2K = -1\n'))
    assert '"inf"' in error.value.hint


@pytest.mark.parametrize(
    "document, expected",
    [
        ({"thermal": {"bus": 3}}, '[thermal] "bus" must be a table'),
        ({"thermal": [1, 2]}, "[thermal] must hold one table per glob"),
        ({"thermals": {}}, "unknown top-level table 'thermals'"),
    ],
)
def test_misshapen_thermal_tables_are_refused(document, expected):
    with pytest.raises(MaterialError) as error:
        parse_materials(document, "m.toml")
    assert expected in str(error.value)
    if "top-level" in expected:
        assert '[thermal."GLOB"]' in error.value.hint


def test_every_bad_rule_is_listed_at_once_with_the_other_problems():
    document = {
        "materials": {"a": {"reflectivity": 2, "specular_fraction": 0.1}},
        "thermal": {"bus": {"isothermal": "no"}, "wing": {"heat_capacity_J_K": -1}},
    }
    with pytest.raises(MaterialError) as error:
        parse_materials(document, "m.toml")
    message = str(error.value)
    assert message.startswith("m.toml: 3 problems:")
    assert "reflectivity = 2" in message and '"bus"' in message and '"wing"' in message


def test_the_model_carries_its_rules_through_poses_and_pickling():
    craft = craft_with('[thermal."bus"]\nisothermal = true\n[thermal."wing"]\nconductance_W_m2K = 50\n')
    assert craft.thermal == (ThermalRule("bus", isothermal=True), ThermalRule("wing", conductance_W_m2K=50.0))
    assert pickle.loads(pickle.dumps(craft)).thermal == craft.thermal
    hinged = craft_with(
        '[thermal."wing"]\nconductance_W_m2K = 50\n'
        '[articulation."wing"]\naxis = [0, 1, 0]\norigin_m = [0, 0, 0]\nangle_deg = 30\n'
    )
    assert hinged.thermal == (ThermalRule("wing", conductance_W_m2K=50.0),)
    assert pose(hinged, hinged.hinges, {"wing": 60.0}).thermal == hinged.thermal
    assert craft_with("").thermal == ()


def test_a_glob_that_matches_no_part_is_an_error_naming_the_glob_and_the_parts():
    with pytest.raises(MaterialError) as error:
        craft_with('[thermal."boom*"]\nisothermal = true\n[thermal."bus"]\nisothermal = true\n', "file.toml")
    message = str(error.value)
    assert message.startswith('file.toml: [thermal] "boom*" matches no part of craft.obj')
    assert "the parts are: /craft/bus, wing" in message and "\n" not in message
