"""What makes the free-molecular solver fast changes nothing: rays it skips, laws per group, threads."""

from __future__ import annotations

import dataclasses
import importlib
import math

import numpy as np
import pytest

from sunwind.forces.drag import drag
from sunwind.forces.gas.atmosphere import BOLTZMANN, SPECIES_MASS_KG, Atmosphere
from sunwind.forces.gas.laws import GasSurfaces, panel_coefficients
from sunwind.forces.model import Model
from sunwind.geometry.materials import GasSurface, Material, MaterialTable
from sunwind.geometry.rays.hull import Clearance
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives
from sunwind.meshes.samples import sample_spacecraft

AIR = Atmosphere({"O": 4e14, "N2": 1e14, "He": 2e13}, 1000.0, "test")
SPEED = 7600.0
FLOWS = [np.array(d) / np.linalg.norm(d) for d in ([0.6, -0.48, 0.64], [-1, 0.2, 0.1], [0.1, 0.3, -1])]
LAWS = (
    GasSurface("sentman", 0.9),
    GasSurface("dria", 0.8, wall_temperature_K=500.0),
    GasSurface("schaaf-chambre", normal_accommodation=0.8, tangential_accommodation=0.9),
    GasSurface("cll", normal_accommodation=0.7, tangential_accommodation=0.8),
    GasSurface("specular"),
)


def with_laws(craft, seed=0):
    """``craft`` with every side given one of :data:`LAWS` at random."""
    table = MaterialTable.from_materials([Material(f"m{k}", 0.3, 0.5, gas=g) for k, g in enumerate(LAWS)])
    side_material = np.random.default_rng(seed).integers(0, len(LAWS), craft.n_sides).astype(np.int32)
    return dataclasses.replace(craft, materials=table, side_material=side_material)


@pytest.fixture(scope="module")
def sample():
    return with_laws(build_spacecraft(sample_spacecraft(5_000)))


def counting_rays(monkeypatch, craft):
    """Count the rays ``craft``'s scene is asked about; returns the list of batch sizes."""
    batches = []

    def counting(query):
        def counted(origins, directions):
            batches.append(len(origins))
            return query(origins, directions)

        return counted

    for name in ("occluded", "clear"):
        monkeypatch.setattr(craft.scene, name, counting(getattr(craft.scene, name)))
    return batches


@pytest.mark.parametrize("samples", [1, 4])
def test_convex_body_casts_no_ray_beyond_the_flow_shadow(monkeypatch, samples):
    craft = build_spacecraft(primitives.box((1.0, 2.0, 0.5), divisions=4), uniform=Material("m", 0.3, 0.5))
    batches = counting_rays(monkeypatch, craft)
    result = drag(craft, SPEED * FLOWS[0], AIR, sampling=ShadowSampling(samples=samples), reflections="full")
    assert sum(batches) == result.rays  # the shadow pass along the flow only: no core rays, no chains
    assert len(result.open_sky.direction) == 0  # and no side's sky was sampled


def test_every_side_of_a_convex_body_is_its_own_gas_surface_law():
    """Mixed laws, CLL included, on a sphere: each side's force is the reference law's, lee faces too."""
    craft = with_laws(
        build_spacecraft(primitives.sphere(1.0, subdivisions=12), uniform=Material("m", 0.3, 0.5))
    )
    u = FLOWS[1]
    result = drag(craft, SPEED * u, AIR, sampling=ShadowSampling(samples=1), reflections="none")
    n, gamma = craft.side_normals, craft.side_normals @ u
    along = u - gamma[:, None] * n
    tangent = -along / np.linalg.norm(along, axis=1)[:, None]
    law = GasSurfaces.of(craft.side_gas)
    expected = np.zeros((craft.n_sides, 3))
    for species, density in AIR.number_density_m3.items():
        mass = SPECIES_MASS_KG[species]
        ratio = SPEED / math.sqrt(2 * BOLTZMANN * AIR.temperature_K / mass)
        c_n, c_t = panel_coefficients(law, gamma, ratio, AIR.temperature_K, "full")
        q = 0.5 * density * mass * SPEED**2
        expected += (q * craft.side_areas)[:, None] * (-c_n[:, None] * n + c_t[:, None] * tangent)
    error = np.linalg.norm(result.side_force_N - expected, axis=1)
    assert np.all(error <= 1e-12 * np.linalg.norm(expected, axis=1) + 1e-15 * np.abs(expected).max())


@pytest.mark.slow
@pytest.mark.parametrize("samples", [1, 4, None])
def test_skipping_rays_that_meet_nothing_changes_nothing(monkeypatch, sample, samples):
    kwargs = {"sampling": ShadowSampling(samples=samples), "reflections": "full"}
    fast = [drag(sample, SPEED * u, AIR, **kwargs) for u in FLOWS]
    batches = counting_rays(monkeypatch, sample)
    nothing_cleared = Clearance(
        np.zeros(sample.n_sides, bool),
        np.zeros(sample.n_sides, bool),
        np.zeros((sample.n_sides, 0), bool),
        np.zeros((0, 3)),
        np.zeros((0, 3)),
    )
    monkeypatch.setattr(
        importlib.import_module("sunwind.forces.gas.core_rays"), "clearance", lambda craft: nothing_cleared
    )
    for u, result in zip(FLOWS, fast, strict=True):
        slow = drag(sample, SPEED * u, AIR, **kwargs)
        assert np.array_equal(result.force_N, slow.force_N)
        assert np.array_equal(result.torque_Nm, slow.torque_Nm)
        assert np.array_equal(result.side_force_N, slow.side_force_N)
    assert sum(batches) > 0


@pytest.mark.slow
def test_results_do_not_depend_on_the_thread_count(sample):
    results = [
        drag(sample, SPEED * u, AIR, sampling=ShadowSampling(samples=1), reflections="full") for u in FLOWS
    ]
    for u, result in zip(FLOWS, results, strict=True):
        alone = drag(
            Model(sample, threads=1), SPEED * u, AIR, sampling=ShadowSampling(samples=1), reflections="full"
        )
        assert np.array_equal(result.force_N, alone.force_N)
        assert np.array_equal(result.torque_Nm, alone.torque_Nm)
        assert np.array_equal(result.side_force_N, alone.side_force_N)
