"""Thermal equilibrium and recoil, each against an answer written apart from the solver."""

from __future__ import annotations

import numpy as np
import pytest
import tomllib
from scipy.optimize import brentq

from helpers import quad_sheet
from helpers.shapes import groove, open_box, parallel_squares
from sunwind.forces.radiation.law import LAMBERT_FACTOR, SPEED_OF_LIGHT
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.thermal import STEFAN_BOLTZMANN, ThermalModel, infrared_exchange
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material, ThermalRule, parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives

SIGMA = STEFAN_BOLTZMANN
#: View factors sampled coarsely: the tests that use them check balances, not sampled numbers.
COARSE = ReflectionSettings("full", rays_per_side=256, cache_dir=False)
PAINT = Material("paint", 0.3, 0.2, emissivity=0.7)
FLUX = 1361.0


def sunlit(craft, absorptance: float = 0.6, sun=(0.3, -0.2, 0.9)) -> np.ndarray:
    """Absorbed sunlight per side [W] on an unshadowed convex body: ``alpha S A max(n . u, 0)``."""
    u = np.asarray(sun, dtype=float) / np.linalg.norm(sun)
    return absorptance * FLUX * craft.side_areas * np.maximum(craft.side_normals @ u, 0.0)


def sheet(front_eps: float, back_eps: float, n: int = 2):
    """A unit square sheet in z = 0, front +z, with its own emissivity on each side."""
    spec = parse_materials(
        tomllib.loads(
            f"""
            [materials.front]
            reflectivity = 0.1
            specular_fraction = 0.0
            emissivity = {front_eps}
            [materials.back]
            reflectivity = 0.1
            specular_fraction = 0.0
            emissivity = {back_eps}
            [parts]
            plate = {{ front = "front", back = "back" }}
            """
        )
    )
    corners = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.0]])
    return build_spacecraft(quad_sheet(corners, "plate", n), spec)


def front_load(craft, per_area_W_m2: float) -> np.ndarray:
    """``per_area_W_m2`` absorbed on every front side, nothing on the backs [W]."""
    return np.where(craft.side_sign > 0, per_area_W_m2 * craft.side_areas, 0.0)


@pytest.mark.parametrize("with_exchange", [False, True])
def test_an_isothermal_sphere_has_the_radiative_temperature_and_no_recoil(with_exchange):
    """One node: ``T = (Q / (eps A sigma))^(1/4)``; uniform emission over a closed mesh pushes nothing:
    ``sum -(2/3) e A_i n_i / c`` and its moment vanish to round-off (below 1e-12 of ``sum e / c``)."""
    craft = build_spacecraft(primitives.sphere(1.0, 12), uniform=PAINT)
    exchange = infrared_exchange(craft, COARSE) if with_exchange else None
    model = ThermalModel(craft, exchange, rules=(ThermalRule("sphere", isothermal=True),))
    q = sunlit(craft)
    state = model.equilibrium(q, reference_m=[0.1, 0.2, -0.3])
    expected = (q.sum() / (0.7 * craft.side_areas.sum() * SIGMA)) ** 0.25
    assert model.nodes.n_nodes == 1 and list(model.nodes.names) == ["sphere"]
    np.testing.assert_allclose(state.temperature_K, expected, rtol=1e-12)
    scale = state.emitted_W_total / SPEED_OF_LIGHT
    assert np.abs(state.force_N).max() < 1e-12 * scale
    assert np.abs(state.torque_Nm).max() < 1e-12 * scale
    assert state.escaped_W == pytest.approx(q.sum(), rel=1e-12)
    assert abs(state.imbalance) < 1e-12


@pytest.mark.parametrize("with_exchange", [False, True])
def test_a_sheet_at_one_temperature_radiates_from_both_sides(with_exchange):
    """Infinite conductance: ``T = (q / (sigma (eps_f + eps_b)))^(1/4)``,
    ``F = -(2/3) sigma T^4 A (eps_f - eps_b) n / c``."""
    craft = sheet(0.85, 0.25)
    exchange = infrared_exchange(craft, COARSE) if with_exchange else None
    model = ThermalModel(craft, exchange, rules=())
    q = 600.0
    state = model.equilibrium(front_load(craft, q), reference_m=[0.0, 0.0, 0.0])
    t = (q / (SIGMA * (0.85 + 0.25))) ** 0.25
    np.testing.assert_allclose(state.temperature_K, t, rtol=1e-12)
    push = -LAMBERT_FACTOR * SIGMA * t**4 * (0.85 - 0.25) / SPEED_OF_LIGHT
    np.testing.assert_allclose(state.force_N, [0, 0, push], rtol=1e-12, atol=1e-12 * abs(push))
    # the push acts at the sheet's centre (0.5, 0.5, 0): torque r x F
    np.testing.assert_allclose(
        state.torque_Nm, [0.5 * push, -0.5 * push, 0], rtol=1e-12, atol=1e-13 * abs(push)
    )
    assert model.nodes.n_nodes == craft.n_facets
    assert str(model.nodes.names[0]) == "plate/facet 0"


def sheet_temperatures(q: float, eps_f: float, eps_b: float, h: float) -> tuple[float, float]:
    """Front and back temperature of a sheet absorbing ``q`` [W/m^2] on its front, written apart:
    ``q = eps_f sigma T_f^4 + h (T_f - T_b)``, ``h (T_f - T_b) = eps_b sigma T_b^4``, by bisection
    on ``T_b``."""

    def front(tb: float) -> float:
        return tb + eps_b * SIGMA * tb**4 / h

    def excess(tb: float) -> float:
        return eps_f * SIGMA * front(tb) ** 4 + eps_b * SIGMA * tb**4 - q

    tb = brentq(excess, 0.0, (q / (eps_b * SIGMA)) ** 0.25, xtol=1e-13, rtol=1e-15)
    return front(tb), tb


@pytest.mark.parametrize("h", [0.5, 5.0, 200.0])
def test_a_sheet_with_a_finite_conductance_matches_a_scalar_root(h):
    craft = sheet(0.85, 0.25)
    rules = (ThermalRule("plate", conductance_W_m2K=h),)
    for exchange in (None, infrared_exchange(craft, COARSE)):
        model = ThermalModel(craft, exchange, rules=rules)
        state = model.equilibrium(front_load(craft, 600.0))
        tf, tb = sheet_temperatures(600.0, 0.85, 0.25, h)
        expected = np.where(craft.side_sign > 0, tf, tb)
        np.testing.assert_allclose(state.temperature_K, expected, rtol=1e-12)
        assert abs(state.imbalance) < 1e-12
    assert model.nodes.n_nodes == craft.n_sides
    assert len(model.nodes.links) == craft.n_facets
    assert model.nodes.link_conductance_W_K.sum() == pytest.approx(h * 1.0, rel=1e-12)
    assert str(model.nodes.names[0]) == "plate/facet 0 front"


def test_a_black_front_side_of_no_emissivity_is_heated_through_the_sheet():
    """``eps_f = 0``: the back emits everything, ``T_b = (q / (eps_b sigma))^(1/4)``,
    ``T_f = T_b + q / h``."""
    craft = sheet(0.0, 0.6)
    model = ThermalModel(craft, rules=(ThermalRule("plate", conductance_W_m2K=20.0),))
    state = model.equilibrium(front_load(craft, 400.0))
    tb = (400.0 / (0.6 * SIGMA)) ** 0.25
    np.testing.assert_allclose(
        state.temperature_K, np.where(craft.side_sign > 0, tb + 400.0 / 20.0, tb), rtol=1e-12
    )


def test_a_node_that_cannot_emit_has_no_equilibrium():
    craft = sheet(0.0, 0.0)
    with pytest.raises(InputError, match=r"emissivity 0 .* no thermal equilibrium"):
        ThermalModel(craft).equilibrium(front_load(craft, 100.0))
    one = sheet(0.0, 0.5)
    with pytest.raises(InputError, match="'plate/facet 0 front'"):
        ThermalModel(one, rules=(ThermalRule("plate", conductance_W_m2K=0.0),)).equilibrium(
            front_load(one, 1.0)
        )


def node_residual(model: ThermalModel, state, q: np.ndarray) -> np.ndarray:
    """Each node's power balance [W], summed from the state's per-side numbers and the links."""
    nodes = model.nodes
    t = state.node_temperature_K
    a, b = nodes.links.T
    flow = nodes.link_conductance_W_K * (t[b] - t[a])  # into a, out of b
    conduction = np.bincount(a, flow, nodes.n_nodes) - np.bincount(b, flow, nodes.n_nodes)
    gained = np.bincount(nodes.side_node, q + state.absorbed_infrared_W - state.emitted_W, nodes.n_nodes)
    return gained + conduction


@pytest.mark.parametrize("shape", ["open box", "groove"])
@pytest.mark.parametrize("h", [np.inf, 3.0])
def test_power_balances_in_a_cavity_that_sends_itself_infrared(shape, h):
    craft = (open_box if shape == "open box" else groove)(PAINT)
    model = ThermalModel(
        craft, infrared_exchange(craft, COARSE), rules=(ThermalRule("*", conductance_W_m2K=h),)
    )
    q = np.random.default_rng(3).random(craft.n_sides) * 50.0
    state = model.equilibrium(q)
    assert abs(state.imbalance) < 1e-9
    assert np.abs(node_residual(model, state, q)).max() < 1e-9 * q.sum()
    assert state.absorbed_infrared_W.sum() > 0.05 * state.emitted_W_total  # it does see itself
    assert state.escaped_W + state.lost_W == pytest.approx(q.sum(), rel=1e-9)


def test_infrared_a_model_lacks_sides_for_is_lost_and_reported():
    """Two one-sided plates facing +z, one above the other: the lower one's infrared that meets the
    upper one's back reaches no side (lost); the balance still closes."""
    low = quad_sheet(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.0]]), "low", 3)
    high = quad_sheet(np.array([[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1.0]]), "high", 3)
    spec = parse_materials(
        tomllib.loads(
            "[materials.paint]\nreflectivity = 0.2\nspecular_fraction = 0.0\nemissivity = 0.8\n"
            '[parts]\nlow = { front = "paint" }\nhigh = { front = "paint" }\n'
        )
    )
    craft = build_spacecraft(MeshData.concatenate([low, high]), spec)
    model = ThermalModel(craft, infrared_exchange(craft, COARSE), rules=())
    state = model.equilibrium(np.full(craft.n_sides, 10.0))
    assert state.lost_W > 0.05 * state.emitted_W_total
    assert abs(state.imbalance) < 1e-12


def test_facing_plates_warm_each_other_as_the_two_surface_exchange_says():
    """Two black unit squares 1 m apart, facing; one absorbs ``Q``. With ``F`` the closed-form view
    factor (Incropera): ``sigma A T_a^4 (1 - F^2) = Q``, ``T_b^4 = F T_a^4``; without the exchange
    ``T_a = (Q / (sigma A))^(1/4)``. The sampled view factors carry ~0.2 % on F: 3e-3 on T."""
    a = quad_sheet(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.0]]), "a", 4)
    b = quad_sheet(np.array([[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1.0]]), "b", 4)
    black = {"reflectivity": 0.0, "specular_fraction": 0.0, "emissivity": 1.0}
    spec = parse_materials({"materials": {"black": black}, "parts": {"*": {"front": "black"}}})
    craft = build_spacecraft(MeshData.concatenate([a, b]), spec)
    rules = (ThermalRule("*", isothermal=True),)
    q = np.where(craft.facet_part[craft.side_facet] == 0, 100.0 * craft.side_areas, 0.0)
    alone = ThermalModel(craft, None, rules=rules).equilibrium(q)
    seen = ThermalModel(craft, infrared_exchange(craft, "full"), rules=rules).equilibrium(q)
    f = parallel_squares(1.0)
    t_a = (100.0 / (SIGMA * (1 - f * f))) ** 0.25
    np.testing.assert_allclose(seen.node_temperature_K, [t_a, f**0.25 * t_a], rtol=3e-3)
    np.testing.assert_allclose(alone.node_temperature_K, [(100.0 / SIGMA) ** 0.25, 0.0], rtol=1e-12)
    assert seen.node_temperature_K[0] > alone.node_temperature_K[0] * (1 + 1e-3)
