"""The shadow pass's error estimate carried into results: the relative normalisation, and that SRP, drag
and the Earth's cap passes hand the check the load one unit of each side's lit area takes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from helpers import quad_sheet
from sunwind.forces.drag import drag
from sunwind.forces.earth import CapSampling, Place, planet_radiation
from sunwind.forces.error_estimate import ErrorEstimate, scaled, summed
from sunwind.forces.gas.atmosphere import BOLTZMANN, SPECIES_MASS_KG, Atmosphere
from sunwind.forces.gas.laws import GasSurfaces, panel_coefficients
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, SPEED_OF_LIGHT
from sunwind.forces.srp import srp
from sunwind.geometry.materials import Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.certificate import LoadsError, ShadowCheck
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.samples import sample_spacecraft

BLACK = Material("black", 0.0, 0.0, 0.0, emissivity=0.8)
P = SOLAR_FLUX_1AU / SPEED_OF_LIGHT


def test_relative_estimate_of_hand_made_errors():
    force, size = np.array([3.0, 4.0, 0.0]), 10.0  # |F| = 5; a torque of 0.01 |F| L is 0.5
    big = ErrorEstimate.of(LoadsError(0.5, 0.2), force, np.array([0.0, 0.0, 2.0]), size)
    assert big.force == pytest.approx(0.1) and big.torque == pytest.approx(0.1)  # against |M| = 2
    small = ErrorEstimate.of(LoadsError(0.5, 0.2), force, np.array([0.0, 0.1, 0.0]), size)
    assert small.torque == pytest.approx(0.4)  # |M| = 0.1 < 0.5: against 0.01 |F| L
    assert small.worst == small.torque and small.to_json() == {"force": 0.1, "torque": small.torque}
    dark = ErrorEstimate.of(LoadsError(0.0, 0.0), np.zeros(3), np.zeros(3), size)
    assert dark == ErrorEstimate(0.0, 0.0)
    assert ErrorEstimate.of(LoadsError(1e-9, 0.0), np.zeros(3), np.zeros(3), size).force == math.inf
    assert summed([LoadsError(1.0, 2.0), LoadsError(0.5, 0.25)]) == LoadsError(1.5, 2.25)
    assert summed([LoadsError(1.0, 2.0), None]) is None and summed([]) == LoadsError(0.0, 0.0)
    assert scaled(LoadsError(1.0, 2.0), 3.0) == LoadsError(3.0, 6.0)


@pytest.fixture
def loads_seen(monkeypatch):
    """Every ``load_per_area`` the check is handed, (n_sides, 3) each, with the check that took it."""
    seen = []
    original = ShadowCheck.loads_error

    def spy(check, craft, load_per_area, reference_m):
        seen.append((check, np.array(load_per_area)))
        return original(check, craft, load_per_area, reference_m)

    monkeypatch.setattr(ShadowCheck, "loads_error", spy)
    return seen


def _asked(check: ShadowCheck) -> np.ndarray:
    """The sides whose load the check reads: its sample's and its chords' bands'."""
    return np.union1d(check.sides, check.band_sides)


def test_srp_estimate_is_the_checks_bands_times_the_load_of_eq_4(loads_seen):
    """One unit of lit area takes ``-P cos [(1 - sigma - rho_s) u + (2 rho_s cos + 2/3 rho_d) n]``: the
    check must be handed that, and where its sample found nothing the force error is the bands' area
    times it, side by side."""
    craft = build_spacecraft(sample_spacecraft(2000), uniform=BLACK)  # the sample's own materials
    rho, beta, sigma = craft.side_optics.T
    banded = 0
    for u in np.random.default_rng(1).normal(size=(8, 3)):
        u /= np.linalg.norm(u)
        result = srp(craft, u, reflections="none")
        check, load = loads_seen[-1]
        assert check is result.illumination.check
        cos = craft.side_normals @ u
        along_normal = 2 * rho * beta * cos + 2 / 3 * rho * (1 - beta)
        expected = (
            -P
            * cos[:, None]
            * ((1 - sigma - rho * beta)[:, None] * u + along_normal[:, None] * craft.side_normals)
        )
        asked = _asked(check)
        assert np.all(cos[asked] > 0)
        assert np.allclose(load[asked], expected[asked], rtol=1e-12, atol=0)
        error = result.shadow_error
        assert result.error_estimate.force == pytest.approx(error.force_N / np.linalg.norm(result.force_N))
        if not np.any(check.area_m2) and len(check.band_sides):
            bands = np.linalg.norm(expected[check.band_sides], axis=1) * check.band_m2
            assert error.force_N == pytest.approx(bands.sum(), rel=1e-12)
            banded += 1
    assert banded, "no attitude whose check reported chords' bands: the test has no teeth"
    assert srp(craft, u, reflections="none", sampling=ShadowSampling(samples=4)).error_estimate is None


def test_drag_estimate_takes_the_stream_one_lit_unit_of_area_takes(loads_seen):
    """A small plate over a large one, a fast stream (speed ratio 14: the core cone holds all but
    ~1e-4 of it): the load per unit lit area handed to the check is the panel law's force per unit
    area of the whole stream on each facing side, to that share."""
    lower = quad_sheet(np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0.0]]), "lower", 6)
    upper = quad_sheet(
        np.array([[-0.7, -0.5, 1], [0.6, -0.6, 1], [0.5, 0.7, 1], [-0.6, 0.5, 1.0]]), "upper", 2
    )
    craft = build_spacecraft(MeshData.concatenate([lower, upper]), uniform=BLACK, two_sided=["*"])
    air = Atmosphere({"O": 1e15}, 300.0, "test")
    speed = 14.0 * math.sqrt(2 * BOLTZMANN * 300.0 / SPECIES_MASS_KG["O"])
    u = np.array([0.3, 0.2, 1.0]) / np.linalg.norm([0.3, 0.2, 1.0])
    result = drag(craft, speed * u, air, reflections="none", gas_sampling=GasSampling(sky_rays=36))
    check, load = loads_seen[-1]
    asked = _asked(check)
    n = craft.side_normals[asked]
    gamma = n @ u
    facing = craft.side_normals @ u > 0
    assert len(asked) and np.all(gamma > 0) and result.lit_area_m2 < craft.side_areas[facing].sum()
    c_n, c_t = panel_coefficients(GasSurfaces.of(craft.side_gas).take(asked), gamma, 14.0, 300.0, "full")
    along = u - gamma[:, None] * n
    tangent = -along / np.linalg.norm(along, axis=1, keepdims=True)
    q = 0.5 * 1e15 * SPECIES_MASS_KG["O"] * speed**2
    whole_stream = q * (-c_n[:, None] * n + c_t[:, None] * tangent)
    assert np.allclose(load[asked], whole_stream, rtol=2e-3, atol=0)
    assert result.shadow_error == check.loads_error(craft, load, result.reference_point_m)
    assert result.to_json()["error_estimate"] == result.error_estimate.to_json()
    fixed = drag(
        craft,
        speed * u,
        air,
        reflections="none",
        sampling=ShadowSampling(samples=4),
        gas_sampling=GasSampling(sky_rays=36),
    )
    assert fixed.error_estimate is None and fixed.to_json()["error_estimate"] is None


def test_earth_estimate_adds_the_cells_passes_of_albedo_and_infrared(loads_seen):
    craft = build_spacecraft(sample_spacecraft(2000), uniform=BLACK)
    place = Place([0.3, -0.2, -1.0], 500.0, [1.0, 0.4, 0.2])
    # the cells' method: a pass per cell at every call (the visibility's passes may come from the disk cache)
    result = planet_radiation(craft, place, reflections="none", cap=CapSampling(30.0, "cells"))
    assert len(loads_seen) > 2  # a pass per cell, each handed the albedo's and the infrared's loads
    bands = (result.albedo.shadow_error, result.infrared.shadow_error)
    assert result.shadow_error == summed(bands)
    assert result.to_json()["error_estimate"] == result.error_estimate.to_json()
    assert planet_radiation(craft, place, reflections="plates").error_estimate is None
    fixed = planet_radiation(
        craft, place, reflections="none", cap=CapSampling(30.0, "cells"), sampling=ShadowSampling(samples=1)
    )
    assert fixed.error_estimate is None and fixed.to_json()["error_estimate"] is None
