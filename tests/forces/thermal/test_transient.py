"""The lumped transient: backward Euler steps against the exponential and the steady state."""

from __future__ import annotations

import math

import numpy as np
import pytest

from helpers.shapes import open_box
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.thermal import STEFAN_BOLTZMANN, ThermalModel, infrared_exchange
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material, ThermalRule
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives

SIGMA = STEFAN_BOLTZMANN
PAINT = Material("paint", 0.3, 0.2, emissivity=0.7)
CAPACITY = 9000.0  # [J/K]


def sphere_model() -> tuple[ThermalModel, np.ndarray]:
    craft = build_spacecraft(primitives.sphere(1.0, 8), uniform=PAINT)
    rules = (ThermalRule("sphere", isothermal=True, heat_capacity_J_K=CAPACITY),)
    q = 500.0 * craft.side_areas * np.maximum(craft.side_normals[:, 2], 0.0)
    return ThermalModel(craft, rules=rules), q


def test_a_small_departure_decays_as_the_linearised_exponential():
    """``C dT/dt = Q - eps A sigma T^4`` about ``T_eq``: ``dT(t) = dT_0 exp(-t / tau)``,
    ``tau = C / (4 eps A sigma T_eq^3)``. 500 steps of tau/500 to t = tau: backward Euler is off the
    exponential by ~ t dt / (2 tau^2) = 1e-3 relative, the linearisation by ~ 3 dT_0 / (2 T_eq) = 1.5e-5:
    within 2e-3 of e^-1, and within 1e-4 of the linear recursion ``(1 + dt / tau)^-n``."""
    model, q = sphere_model()
    steady = model.equilibrium(q)
    t_eq = float(steady.node_temperature_K[0])
    emitting = 0.7 * model.craft.side_areas.sum()
    tau = CAPACITY / (4 * emitting * SIGMA * t_eq**3)
    state = model.state_at(np.array([t_eq * (1 + 1e-5)]), q)
    start = state.node_temperature_K[0] - t_eq
    n = 500
    for _ in range(n):
        state = model.step(state, q, tau / n)
        assert abs(state.imbalance) < 1e-10
    ratio = (state.node_temperature_K[0] - t_eq) / start
    assert ratio == pytest.approx(math.exp(-1.0), rel=2e-3)
    assert ratio == pytest.approx((1 + 1 / n) ** -n, rel=1e-4)


def test_steps_relax_to_the_steady_state():
    model, q = sphere_model()
    steady = model.equilibrium(q)
    state = model.state_at(np.array([40.0]), q)
    for _ in range(60):
        state = model.step(state, q, 600.0)
    np.testing.assert_allclose(state.node_temperature_K, steady.node_temperature_K, rtol=1e-10)
    assert abs(state.stored_W) < 1e-8 * state.absorbed_W


def test_nodes_without_heat_capacity_follow_their_steady_state_at_every_step():
    """A box cavity: the floor holds heat, the walls do not. After a step, the walls balance their
    power to round-off, the whole model stores what it does not radiate away."""
    craft = open_box(PAINT, n=2)
    rules = (ThermalRule("wall0", isothermal=True, heat_capacity_J_K=2000.0),)
    model = ThermalModel(
        craft, infrared_exchange(craft, ReflectionSettings("full", rays_per_side=256)), rules=rules
    )
    q = np.random.default_rng(5).random(craft.n_sides) * 20.0
    state = model.state_at(np.full(model.nodes.n_nodes, 250.0), q)
    for _ in range(3):
        state = model.step(state, q, 300.0)
        assert abs(state.imbalance) < 1e-10
    nodes = model.nodes
    gained = np.bincount(nodes.side_node, q + state.absorbed_infrared_W - state.emitted_W, nodes.n_nodes)
    walls = nodes.heat_capacity_J_K == 0
    assert np.abs(gained[walls]).max() < 1e-10 * q.sum()
    assert gained[~walls].sum() == pytest.approx(state.stored_W, rel=1e-9)
    assert list(nodes.names[~walls]) == ["wall0"]


def test_a_node_that_cannot_emit_still_warms_in_time_but_has_no_equilibrium():
    black_body = Material("gold", 0.9, 0.0, emissivity=0.0)
    craft = build_spacecraft(primitives.sphere(1.0, 4), uniform=black_body)
    model = ThermalModel(craft, rules=(ThermalRule("*", isothermal=True, heat_capacity_J_K=100.0),))
    q = np.full(craft.n_sides, 1.0)
    state = model.step(model.state_at(np.array([10.0]), q), q, 5.0)
    assert state.node_temperature_K[0] == pytest.approx(10.0 + q.sum() * 5.0 / 100.0, rel=1e-12)
    with pytest.raises(InputError, match="no thermal equilibrium"):
        model.equilibrium(q)
    with pytest.raises(InputError, match="dt_s"):
        model.step(state, q, 0.0)
