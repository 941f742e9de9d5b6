"""Sensitivities of drag: the derivatives by every material's accommodation coefficients are those of
``drag`` itself, central differences of the whole model loaded again with one coefficient moved."""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from sunwind.forces.drag import drag
from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.gas.incident import cll_reflected_normal, rice_mean, rice_mean_slope
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.sensitivity import ACCOMMODATIONS
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import GasSurface, Material, MaterialTable
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives

AIR = Atmosphere({"O": 4e14, "N2": 1e14, "He": 2e13}, 1000.0, "test")
FLOW = np.array([0.8, 0.35, 0.3]) / np.linalg.norm([0.8, 0.35, 0.3])
REFERENCE = np.array([0.3, -0.2, 0.1])
SAMPLING = GasSampling(sky_rays=64, core_rays=4096, chain_molecules=4096)
LAWS = {
    "sentman": GasSurface("sentman", 0.8),
    "dria": GasSurface("dria", 0.7, wall_temperature_K=500.0),
    "schaaf-chambre": GasSurface("schaaf-chambre", normal_accommodation=0.7, tangential_accommodation=0.8),
    "cll": GasSurface("cll", normal_accommodation=0.6, tangential_accommodation=0.7),
    "specular": GasSurface("specular"),
}
#: The accommodations each law reads (the others' derivatives must be zero).
READS = {
    "sentman": ("energy_accommodation",),
    "dria": ("energy_accommodation",),
    "schaaf-chambre": ("normal_accommodation", "tangential_accommodation"),
    "cll": ("normal_accommodation", "tangential_accommodation"),
    "specular": (),
}
STEP = 1e-5


@functools.cache
def concave(laws: tuple[str, ...], seed: int = 0):
    """The box-and-wing model (concave: the wings see the bus) with its sides given the ``laws``, one
    material each, at random."""
    craft = build_spacecraft(primitives.box_wing(facet_size=0.5), uniform=Material("w", 0.3, 0.5))
    table = MaterialTable.from_materials([Material(name, 0.3, 0.5, gas=LAWS[name]) for name in laws])
    side_material = np.random.default_rng(seed).integers(0, len(laws), craft.n_sides).astype(np.int32)
    return dataclasses.replace(craft, materials=table, side_material=side_material)


def moved(craft, material: int, coefficient: str, step: float):
    """``craft`` with one material's accommodation moved by ``step``: a copy, whose caches start empty."""
    gas = list(craft.materials.gas)
    gas[material] = dataclasses.replace(
        gas[material], **{coefficient: getattr(gas[material], coefficient) + step}
    )
    return dataclasses.replace(craft, materials=dataclasses.replace(craft.materials, gas=tuple(gas)))


def run(craft, velocity, reflections, sensitivities=False):
    settings = ReflectionSettings.of(reflections)
    if settings.mode in ("full", "specular"):
        settings = ReflectionSettings(settings.mode, rays_per_side=64, cache_dir=False)
    return drag(
        craft,
        velocity,
        AIR,
        reference_point_m=REFERENCE,
        reflections=settings,
        gas_sampling=SAMPLING,
        sensitivities=sensitivities,
    )


def check_against_differences(laws: tuple[str, ...], reflections: str, speed: float, law: str) -> None:
    """Every accommodation of material ``law`` (named after its law) of a model with ``laws``."""
    craft = concave(laws)
    velocity = speed * FLOW
    result = run(craft, velocity, reflections, sensitivities=True)
    plain = run(craft, velocity, reflections)
    assert np.array_equal(result.force_N, plain.force_N) and np.array_equal(result.torque_Nm, plain.torque_Nm)
    assert plain.sensitivities is None
    record = result.sensitivities
    assert record.materials == laws
    assert not np.any(record.force_N[:, :4]) and not np.any(record.torque_Nm[:, :4])
    length = float(np.ptp(craft.triangles.reshape(-1, 3), axis=0).max())
    m = laws.index(law)
    for coefficient in ACCOMMODATIONS:
        derivative = record.of(f"{law}.{coefficient}")
        if coefficient not in READS[law]:
            assert not np.any(derivative.force_N) and not np.any(derivative.torque_Nm)
            continue
        up = run(moved(craft, m, coefficient, STEP), velocity, reflections)
        down = run(moved(craft, m, coefficient, -STEP), velocity, reflections)
        force = (up.force_N - down.force_N) / (2 * STEP)
        torque = (up.torque_Nm - down.torque_Nm) / (2 * STEP)
        scale = max(np.abs(force).max(), np.abs(torque).max() / length)
        assert scale > 0.0, (law, coefficient)
        assert np.abs(derivative.force_N - force).max() <= 1e-6 * scale, (law, coefficient, "force")
        assert np.abs(derivative.torque_Nm - torque).max() <= 1e-6 * scale * length, (law, coefficient)


@pytest.mark.parametrize("law", ["sentman", "dria", "schaaf-chambre", "cll", "specular"])
@pytest.mark.parametrize("speed", [7600.0, 900.0])
@pytest.mark.parametrize("reflections", ["none", "plates"])
def test_every_law_without_reflections_matches_central_differences(reflections, speed, law):
    check_against_differences(tuple(LAWS), reflections, speed, law)


@pytest.mark.parametrize("law", ["sentman", "dria", "schaaf-chambre", "cll"])
@pytest.mark.parametrize("speed", [7600.0, 900.0])
def test_the_molecular_chains_match_central_differences(speed, law):
    check_against_differences(tuple(LAWS), "specular", speed, law)


@pytest.mark.parametrize("law", ["sentman", "dria", "schaaf-chambre", "cll"])
@pytest.mark.parametrize("speed", [7600.0, 900.0])
def test_the_molecular_exchange_matches_central_differences(speed, law):
    check_against_differences(tuple(LAWS), "full", speed, law)


@pytest.mark.parametrize("reflections", ["specular", "full"])
def test_the_reflected_part_alone_matches_central_differences(reflections):
    """What the chains and the exchange add, small beside the panel law, checked on its own (the
    exchange's factors, differenced through schaaf-chambre's mirrored share, included)."""
    laws = tuple(LAWS)
    craft, velocity = concave(laws), 900.0 * FLOW
    with_reflections = run(craft, velocity, reflections, True).sensitivities
    without = run(craft, velocity, "none", True).sensitivities
    for m, law in enumerate(laws):
        for coefficient in READS[law]:
            up = run(moved(craft, m, coefficient, STEP), velocity, reflections).reflected
            down = run(moved(craft, m, coefficient, -STEP), velocity, reflections).reflected
            expected = np.concatenate([up.force_N - down.force_N, up.torque_Nm - down.torque_Nm]) / (2 * STEP)
            got = [record.of(f"{law}.{coefficient}") for record in (with_reflections, without)]
            found = np.concatenate([got[0].force_N - got[1].force_N, got[0].torque_Nm - got[1].torque_Nm])
            # schaaf-chambre's sigma_t moves no molecule the chains follow: both zero then
            scale = np.abs(expected).max()
            assert np.abs(found - expected).max() <= 1e-5 * scale, (law, coefficient)


def test_the_chains_and_the_exchange_change_the_derivatives():
    """On the concave model the reflections are part of what is differentiated."""
    craft = concave(tuple(LAWS))
    velocity = 900.0 * FLOW
    none = run(craft, velocity, "none", True).sensitivities
    full = run(craft, velocity, "full", True).sensitivities
    assert np.abs(full.force_N - none.force_N).max() > 1e-3 * np.abs(none.force_N).max()


@pytest.mark.parametrize("edge", [{"normal_accommodation": 1.0}, {"tangential_accommodation": 0.0}])
def test_cll_draws_at_the_edge_are_refused_with_reflections(edge):
    craft = concave(("cll", "sentman"))
    gas = (dataclasses.replace(craft.materials.gas[0], **edge), craft.materials.gas[1])
    edged = dataclasses.replace(craft, materials=dataclasses.replace(craft.materials, gas=gas))
    with pytest.raises(InputError, match="need normal_accommodation < 1"):
        run(edged, 7600.0 * FLOW, "specular", sensitivities=True)
    assert run(edged, 7600.0 * FLOW, "none", sensitivities=True).sensitivities is not None


def test_a_batch_gives_every_result_its_sensitivities():
    craft = concave(("sentman", "schaaf-chambre"))
    batch = run(craft, np.array([7600.0 * FLOW, [0.0, 7000.0, 500.0]]), "none", True)
    for velocity, result in zip([7600.0 * FLOW, [0.0, 7000.0, 500.0]], batch.results, strict=True):
        one = run(craft, velocity, "none", True).sensitivities
        assert np.array_equal(result.sensitivities.force_N, one.force_N)
        assert np.array_equal(result.sensitivities.reference_point_m, REFERENCE)


def test_the_rice_mean_slope_and_the_cll_normal_slope_match_differences():
    x = np.linspace(0.0, 6.0, 25)
    for alpha in (1e-3, 0.3, 0.99, 1.0):
        a = np.full_like(x, alpha)
        h = 1e-7
        down = rice_mean(x, a - h, np.full_like(x, 0.4))
        up = rice_mean(x, np.minimum(a + h, 1.0), np.full_like(x, 0.4))
        step = (up - down) / (np.minimum(a + h, 1.0) - (a - h))
        assert np.allclose(rice_mean_slope(x, a, np.full_like(x, 0.4)), step, rtol=1e-5, atol=1e-7)
    gamma = np.linspace(-1.0, 1.0, 9)
    alpha, tau = np.full(9, 0.6), np.full(9, 0.3)
    slope = cll_reflected_normal(gamma, alpha, tau, 4.0, "full", rice_mean_slope)
    step = (
        cll_reflected_normal(gamma, alpha + 1e-6, tau, 4.0, "full")
        - cll_reflected_normal(gamma, alpha - 1e-6, tau, 4.0, "full")
    ) / 2e-6
    assert np.allclose(slope, step, rtol=1e-7, atol=1e-10)
