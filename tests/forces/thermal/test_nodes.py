"""Thermal nodes from the [thermal] rules, and what the model refuses."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.reflection.diffuse import DiffuseExchange
from sunwind.forces.reflection.views import model_view_factors
from sunwind.forces.thermal import ThermalModel, infrared_exchange, thermal_nodes
from sunwind.geometry.errors import InputError, MaterialError
from sunwind.geometry.materials import Material, ThermalRule
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives

PAINT = Material("paint", 0.3, 0.2, emissivity=0.7)


def box_wing():
    return build_spacecraft(primitives.box_wing(facet_size=0.5), uniform=PAINT, two_sided=["wing*"])


def test_rules_make_part_nodes_linked_sheet_sides_and_merged_sheet_facets():
    craft = box_wing()
    rules = (
        ThermalRule("bus", isothermal=True, heat_capacity_J_K=5000.0),
        ThermalRule("wing_left", conductance_W_m2K=12.0),
        ThermalRule("wing_*", conductance_W_m2K=0.0),  # wing_right only: the first match wins
    )
    nodes = thermal_nodes(craft, rules)
    part = craft.facet_part[craft.side_facet]
    left, right = (craft.part_names.index(name) for name in ("wing_left", "wing_right"))
    n_left = int(np.sum(craft.facet_part == left))
    assert nodes.n_nodes == 1 + 2 * n_left + 2 * int(np.sum(craft.facet_part == right))
    assert np.all(nodes.side_node[part == craft.part_names.index("bus")] == 0)
    assert nodes.names[0] == "bus" and nodes.heat_capacity_J_K[0] == 5000.0
    assert np.all(nodes.heat_capacity_J_K[1:] == 0)
    assert len(nodes.links) == n_left  # front to back of each left-wing facet
    assert nodes.link_conductance_W_K.sum() == pytest.approx(12.0 * 3.0 * 1.0, rel=1e-12)
    assert nodes.area_m2.sum() == pytest.approx(craft.side_areas.sum(), rel=1e-12)
    names = set(nodes.names.tolist())
    assert len(names) == nodes.n_nodes
    assert any(name.startswith("wing_right/facet ") and name.endswith(" back") for name in names)
    # default: front and back of a sheet facet are one node, a closed body's facets their own
    default = thermal_nodes(craft, ())
    assert default.n_nodes == craft.n_facets and len(default.links) == 0


def test_a_heat_capacity_is_shared_by_the_parts_a_rule_matches_by_area():
    craft = box_wing()
    nodes = thermal_nodes(craft, (ThermalRule("wing_*", isothermal=True, heat_capacity_J_K=300.0),))
    wings = nodes.heat_capacity_J_K > 0
    assert wings.sum() == 2
    np.testing.assert_allclose(nodes.heat_capacity_J_K[wings], [150.0, 150.0], rtol=1e-12)
    with pytest.raises(InputError, match="needs isothermal"):
        thermal_nodes(craft, (ThermalRule("bus", heat_capacity_J_K=10.0),))


def test_rules_are_read_from_the_model_by_default():
    craft = replace(box_wing(), thermal=(ThermalRule("*", isothermal=True),))
    assert ThermalModel(craft).nodes.n_nodes == 3


def test_the_model_refuses_missing_emissivities_light_exchanges_and_bad_input():
    craft = build_spacecraft(primitives.box(), uniform=Material("bare", 0.3, 0.2))
    with pytest.raises(MaterialError, match="emissivity"):
        ThermalModel(craft)
    craft = build_spacecraft(
        primitives.box_wing(facet_size=0.5),
        uniform=Material("white", 0.3, 0.2, emissivity=0.9),
        two_sided=["wing*"],
    )
    settings = ReflectionSettings("full", rays_per_side=64, cache_dir=False)
    light = DiffuseExchange(craft, model_view_factors(craft, settings))
    with pytest.raises(InputError, match="not the infrared one"):
        ThermalModel(craft, light)
    assert infrared_exchange(craft, "none") is None
    model = ThermalModel(craft, infrared_exchange(craft, settings))
    with pytest.raises(InputError, match="absorbed_W"):
        model.equilibrium(np.ones(3))
    with pytest.raises(InputError, match="absorbed_W"):
        model.equilibrium(-np.ones(craft.n_sides))


def test_a_state_writes_json_with_units_in_its_keys():
    craft = box_wing()
    model = ThermalModel(craft, rules=(ThermalRule("*", isothermal=True),))
    state = model.equilibrium(np.where(craft.side_normals[:, 0] > 0.5, 100.0, 0.0) * craft.side_areas)
    out = json.loads(json.dumps(state.to_json()))
    assert set(out["node_temperature_K"]) == {"bus", "wing_left", "wing_right"}
    for key in ("force_N", "torque_Nm", "reference_point_m", "absorbed_W", "escaped_W", "lost_W"):
        assert key in out
    assert out["frame"] == "body frame of the mesh"
    assert math.isfinite(out["imbalance"]) and abs(out["imbalance"]) < 1e-12
