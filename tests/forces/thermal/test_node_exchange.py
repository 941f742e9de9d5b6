"""Node-level exchange factors (Gebhart's) against the side-level infrared balance they reduce: the same
temperatures, recoil and transient to the solves' tolerance, the emission of each node accounted for,
kept once in the model's cache, and the rule that chooses them."""

from __future__ import annotations

import numpy as np
import pytest

from helpers.shapes import open_box
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.thermal import STEFAN_BOLTZMANN, ThermalModel, infrared_exchange, integrate, thermal_model
from sunwind.forces.thermal import model as thermal_module
from sunwind.geometry.materials import Conductance, Material, ThermalRule

SIGMA = STEFAN_BOLTZMANN
PAINT = Material("paint", 0.3, 0.2, emissivity=0.7)
COARSE = ReflectionSettings("full", rays_per_side=256, cache_dir=False)
#: Isothermal walls (two with heat capacities, joined), a wall of finite conductance (a front and a back
#: node per facet, linked) and two of a node per facet: 34 nodes in an open box that sees itself.
RULES = (
    ThermalRule("wall0", isothermal=True, heat_capacity_J_K=4000.0),
    ThermalRule("wall1", isothermal=True, heat_capacity_J_K=1500.0),
    ThermalRule("wall2", conductance_W_m2K=3.0),
    Conductance(("wall0", "wall1"), 0.8),
)


@pytest.fixture(scope="module")
def box():
    craft = open_box(PAINT, n=2)
    exchange = infrared_exchange(craft, COARSE)
    rng = np.random.default_rng(11)
    powers = rng.random((6, craft.n_sides)) * 40.0 * craft.side_areas[None, :]
    return craft, exchange, powers


def both(craft, exchange, rules):
    node = ThermalModel(craft, exchange, rules=rules)
    side = ThermalModel(craft, exchange, rules=rules, node_level=False)
    assert node.node_exchange is not None and side.node_exchange is None
    return node, side


def close(a, b) -> float:
    return float(np.abs(np.asarray(a) - b).max() / np.abs(b).max())


@pytest.mark.parametrize("rules", [(ThermalRule("wall*", isothermal=True),), RULES], ids=["linear", "linked"])
def test_node_factors_give_the_side_level_equilibrium_to_round_off(box, rules):
    """Without links the linear solution, with links Newton's: temperatures within 1e-12 (the solves
    stop at a relative 1e-13), the recoil of the state alike."""
    craft, exchange, powers = box
    node, side = both(craft, exchange, rules)
    for q in powers[:3]:
        a, b = node.equilibrium(q), side.equilibrium(q)
        assert close(a.node_temperature_K, b.node_temperature_K) < 1e-12
        assert close(a.force_N, b.force_N) < 1e-10 and close(a.torque_Nm, b.torque_Nm) < 1e-10
        assert abs(a.imbalance) < 1e-11 and abs(b.imbalance) < 1e-11
        assert a.absorbed_infrared_W.sum() > 0.05 * a.emitted_W_total  # the box sees itself


def test_node_factors_give_the_side_level_transient_to_round_off(box):
    """Steps and an SDIRK integration with sub-steps, linked nodes with and without heat capacity: the
    same temperatures, error estimates, sub-steps and recoil (the node path's from its factors)."""
    craft, exchange, powers = box
    node, side = both(craft, exchange, RULES)
    start = node.state_at(np.full(node.nodes.n_nodes, 250.0), powers[0])
    a, b = node.step(start, powers[1], 120.0), side.step(start, powers[1], 120.0)
    assert close(a.node_temperature_K, b.node_temperature_K) < 1e-12
    assert abs(a.stored_W - b.stored_W) < 1e-9 * a.absorbed_W
    times = np.arange(0.0, 601.0, 120.0)
    runs = [integrate(model, times, powers, initial=start, tolerance_K=1e-3) for model in (node, side)]
    a, b = runs
    assert np.array_equal(a.substeps, b.substeps) and a.substeps.sum() > len(times)
    assert close(a.node_temperature_K, b.node_temperature_K) < 1e-12
    # the estimates are differences of temperatures: equal to the temperatures' round-off
    assert np.abs(a.node_error_K - b.node_error_K).max() < 1e-12 * a.node_temperature_K.max()
    assert close(a.force_N, b.force_N) < 1e-10 and close(a.torque_Nm, b.torque_Nm) < 1e-10
    for name in ("escaped_W", "lost_W", "stored_W"):
        assert np.abs(getattr(a, name) - getattr(b, name)).max() < 1e-10 * a.absorbed_W.max(), name
    assert np.abs(a.imbalance[1:]).max() < 1e-11  # the start, as given, is not balanced


def test_node_factors_account_for_every_watt_a_node_emits(box):
    """Of what node ``k`` emits, the nodes absorb ``absorbed_m2[:, k]``, ``sums_m2[k, 6]`` escapes and
    ``sums_m2[k, 7]`` is lost: they add up to ``sum eps A`` of the node; Gebhart's factors are shares."""
    craft, exchange, _ = box
    factors = ThermalModel(craft, exchange, rules=RULES).node_exchange
    total = factors.absorbed_m2.sum(axis=0) + factors.sums_m2[:, 6] + factors.sums_m2[:, 7]
    np.testing.assert_allclose(total, factors.emitting_m2, rtol=1e-12)
    gebhart = factors.gebhart
    assert gebhart.min() >= 0 and gebhart.sum(axis=1).max() < 1
    model = ThermalModel(craft, exchange, rules=RULES)
    blind = gebhart.sum(axis=1) == 0  # wall2's outer sides see nothing: all they emit escapes
    assert blind.sum() == 8 and all(name.startswith("wall2/") for name in model.nodes.names[blind])
    assert gebhart.sum(axis=1)[~blind].min() > 0.05  # the others send some to the rest of the box


def test_node_factors_are_made_once_and_kept_in_the_model_cache(box, monkeypatch):
    craft, exchange, _ = box
    rules = (ThermalRule("*", isothermal=True),)
    first = ThermalModel(craft, exchange, rules=rules).node_exchange
    assert ThermalModel(craft, exchange, rules=rules).node_exchange is first  # another model, same nodes
    keys = [key for key in craft.cache if key[0] == "thermal node exchange"]
    assert keys and keys[0][1:-1] == COARSE.view_key  # beside the exchange it reduces
    assert ThermalModel(craft, exchange, rules=RULES).node_exchange is not first  # other nodes
    model = thermal_model(craft, COARSE)  # a node per sheet facet: 40
    assert model.nodes.n_nodes == 40 and model.node_exchange is not None
    monkeypatch.setattr(thermal_module, "EXCHANGE_NODES", 39)  # the rule: too many nodes, the sides
    assert ThermalModel(craft, exchange).node_exchange is None
    assert ThermalModel(craft, exchange, node_level=True).node_exchange is not None
    assert ThermalModel(craft, None, node_level=True).node_exchange is None  # nothing to reduce
