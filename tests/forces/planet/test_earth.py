"""The planet's albedo and infrared on meshes against the independent references of
``sunwind.validation.planet_fluxes`` (brute-force integrals over the planet's surface, closed forms, rays)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from helpers import quad_sheet
from helpers.shapes import open_box, plate_over_plate
from sunwind.forces.earth import CapSampling, Place, planet_radiation
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.planet.cap import Cap
from sunwind.geometry.materials import Material, MaterialSpec, PartRule
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives
from sunwind.validation import planet_fluxes as ref

EARTH = planet("earth")
FLUX = 1361.0
LIGHT = PlanetLight.of(EARTH, FLUX)
#: Directions: nadir -z; Suns at zenith angles 0-150 deg (terminator and night included), off-plane.
NADIR = np.array([0.0, 0.0, -1.0])
SUNS = [
    np.array([math.sin(z) * math.cos(0.4), math.sin(z) * math.sin(0.4), math.cos(z)])
    for z in np.radians([0, 40, 75, 90, 100, 150])
]
#: Plate normals from nadir (psi 0) to 180 deg from it, at two azimuths.
NORMALS = np.array([
    [math.sin(p) * math.cos(a), math.sin(p) * math.sin(a), -math.cos(p)]
    for p in np.radians(np.arange(0, 181, 15)) for a in (0.0, 2.1)
])  # fmt: skip
OPTICS = {"absorbing": (0.0, 0.0, 0.0), "specular": (1.0, 1.0, 0.0), "diffuse": (1.0, 0.0, 0.0)}


def _cap(altitude_km: float, sun: np.ndarray, band: str) -> Cap:
    law = LIGHT.albedo if band == "albedo" else LIGHT.infrared
    return Cap(NADIR, sun, np.array([0.0, 1.0, 0.0]), EARTH.radius_m + altitude_km * 1e3, EARTH.radius_m, law)


@pytest.mark.parametrize("altitude_km", [400.0, 2000.0, 35786.0])
@pytest.mark.parametrize("band", ["albedo", "infrared"])
def test_cap_integrals_equal_the_brute_force_over_the_planet(altitude_km, band):
    """I_0 (absorbed flux factor), I_1 and I_2 of a plate against the surface integral, terminator and
    partial view included: 1e-6 of the unshadowed nadir value."""
    body = ref.SphericalPlanet(EARTH.radius_m, altitude_km * 1e3, FLUX, EARTH.albedo)
    for sun in SUNS[:: (1 if band == "albedo" else 6)]:
        cap = _cap(altitude_km, sun, band)
        i0, i1, i2 = cap.side_integrals(NORMALS)
        scale = ref.plate_moments(NADIR, sun, NADIR, body, "infrared").irradiance_W_m2
        for k, n in enumerate(NORMALS):
            expected = ref.plate_moments(NADIR, sun, n, body, band)
            assert abs(i0[k] - expected.irradiance_W_m2) <= 1e-6 * scale
            assert np.abs(i1[k] - expected.vector_W_m2).max() <= 1e-6 * scale
            assert abs(i2[k] - expected.second_W_m2) <= 1e-6 * scale


def _one_sided(mesh: MeshData, material: Material):
    """``mesh`` as a one-sided sheet of ``material``."""
    spec = MaterialSpec({material.name: material}, (PartRule("*", material.name, None, True),))
    return build_spacecraft(mesh, spec)


@pytest.mark.parametrize("finish", sorted(OPTICS))
def test_plate_force_is_the_momentum_integral_not_flux_over_c(finish):
    """The force on a plate from each band equals the brute-force integral of eq. (4) over the cap
    (1e-6 relative to the largest), at 500 km, normals across the range, Sun near the terminator."""
    rho, beta, sigma = OPTICS[finish]
    material = Material(finish, rho, beta, sigma, emissivity=1.0 - rho)
    body = ref.SphericalPlanet(EARTH.radius_m, 500e3, FLUX, EARTH.albedo)
    sun = SUNS[3]
    for n in NORMALS[::5]:
        craft = _one_sided(quad_sheet(_square(n), "plate", 1), material)
        result = planet_radiation(craft, Place(NADIR, 500.0, sun), LIGHT, reflections="none")
        albedo = ref.plate_force(NADIR, sun, n, body, (rho, beta, sigma), "albedo")
        infrared = ref.plate_force(NADIR, sun, n, body, (1.0 - material.emissivity, 0.0, 0.0), "infrared")
        assert np.abs(result.albedo.force_N - albedo).max() <= 1e-6 * max(np.abs(albedo).max(), 1e-12)
        assert np.abs(result.infrared.force_N - infrared).max() <= 1e-6 * np.abs(infrared).max() + 1e-20


def _square(normal: np.ndarray) -> np.ndarray:
    """Corners of a 1 m^2 square facing ``normal``, counter-clockwise seen from the front."""
    a = np.cross(normal, [0.3, 0.7, 0.2])
    a /= np.linalg.norm(a)
    b = np.cross(normal, a)
    return np.array([-a - b, a - b, a + b, -a + b]) / 2


@pytest.mark.slow
def test_absorbing_sphere_against_its_closed_forms():
    """Infrared and subsolar albedo force on an absorbing sphere of radius 1 m: faceting only (1e-4)."""
    craft = build_spacecraft(primitives.sphere(1.0), uniform=Material("black", 0.0, 0.0, 0.0, emissivity=1.0))
    for altitude_km in (400.0, 35786.0):
        result = planet_radiation(
            craft, Place(NADIR, altitude_km, -NADIR), LIGHT, reflections="none"
        )  # convex
        h = altitude_km * 1e3
        infrared = ref.sphere_force_infrared(1.0, EARTH.radius_m, h, (1 - EARTH.albedo) * FLUX / 4)
        albedo = ref.sphere_force_albedo_subsolar(1.0, EARTH.radius_m, h, EARTH.albedo, FLUX)
        area = craft.side_areas.sum() / (4 * math.pi)  # the faceted sphere is this much smaller
        np.testing.assert_allclose(
            result.infrared.force_N, infrared * area * -NADIR, rtol=1e-4, atol=1e-12 * infrared
        )
        np.testing.assert_allclose(
            result.albedo.force_N, albedo * area * -NADIR, rtol=1e-3, atol=1e-3 * albedo
        )


@pytest.mark.parametrize(
    "step_deg, tolerance", [(10.0, 2e-2), pytest.param(2.5, 3e-3, marks=pytest.mark.slow)]
)
def test_plate_behind_a_plate_against_rays(step_deg, tolerance):
    """A 1 m plate facing the planet with a 0.4 m plate 0.3 m below it: the shadowed irradiance and force
    on the big plate against the ray brute force, falling with the cell size."""
    craft, big, small = plate_over_plate()
    body = ref.SphericalPlanet(EARTH.radius_m, 500e3, FLUX, EARTH.albedo)
    sun = SUNS[1]
    result = planet_radiation(
        craft, Place(NADIR, 500.0, sun), LIGHT, reflections="none", cap=CapSampling(step_deg)
    )
    part = craft.facet_part[craft.side_facet]
    facing = (part == craft.part_names.index("big")) & (craft.side_normals[:, 2] < 0)
    blockers = np.array([small[[0, 1, 2]], small[[0, 2, 3]]])
    for band in ("albedo", "infrared"):
        expected = ref.shadowed_plate_irradiance(blockers, big, [0, 0, -1.0], NADIR, sun, body, band)
        got = getattr(result, band).incident_side_W[facing].sum()
        assert abs(got - expected.irradiance_W_m2) <= tolerance * expected.irradiance_W_m2


def test_the_plate_mode_gives_every_side_the_closed_form_factors_of_a_plate_alone():
    """``reflections="plates"``: each side of the shadowing pair gets the dissertation's ``M phi_1``
    and, with the Sun overhead (where the closed form is exact), ``A S phi_2``, as if it were alone; no
    ray is cast. The default, which shadows, gives the big plate less."""
    craft, _, _ = plate_over_plate()
    sun = SUNS[0]
    alone = planet_radiation(craft, Place(NADIR, 500.0, sun), LIGHT, reflections="plates")
    theta_0 = float(ref.theta_0_of(EARTH.radius_m, 500e3))
    normals, areas = craft.side_normals, craft.side_areas
    infrared = (1 - EARTH.albedo) * FLUX / 4 * np.asarray(ref.infrared_factor_closed(NADIR, normals, theta_0))
    albedo = EARTH.albedo * FLUX * np.asarray(ref.albedo_factor_closed(NADIR, sun, normals, theta_0))
    assert np.all(ref.albedo_closed_is_exact(NADIR, sun, normals[infrared > 0], theta_0))
    assert np.allclose(alone.infrared.incident_side_W, infrared * areas, rtol=1e-9, atol=1e-12)
    assert np.allclose(alone.albedo.incident_side_W, albedo * areas, rtol=1e-9, atol=1e-12)
    assert alone.rays == 0 and alone.reflections == "plates"
    shadowed = planet_radiation(craft, Place(NADIR, 500.0, sun), LIGHT, reflections="none")
    big = craft.facet_part[craft.side_facet] == craft.part_names.index("big")
    assert shadowed.infrared.incident_side_W[big].sum() < 0.9 * alone.infrared.incident_side_W[big].sum()


@pytest.mark.slow
def test_power_balances_in_a_cavity_with_every_reflection():
    """An open box with mixed finishes: incident = absorbed + escaped + cut off to round-off, per band;
    per-side absorbed power plus what no side absorbs is the band's absorbed power."""
    craft = open_box(Material("m", 0.7, 0.6, 0.1, emissivity=0.5), 3)
    result = planet_radiation(
        craft, Place([0.3, 0.2, -1.0], 500.0, [0.5, 0.2, 0.4]), LIGHT, reflections="full"
    )
    for band in (result.albedo, result.infrared, result.solar):
        assert abs(band.power.imbalance) < 1e-9
        on_sides = band.absorbed_side_W.sum() + band.reflected_side_W.sum() + band.lost_W
        assert on_sides == pytest.approx(band.power.absorbed_W + band.power.truncated_W, rel=1e-9)


def test_a_material_without_emissivity_is_named():
    craft = build_spacecraft(primitives.sphere(1.0), uniform=Material("bare", 0.5, 0.5, 0.0))
    with pytest.raises(Exception, match="'bare' has no emissivity"):
        planet_radiation(craft, Place(NADIR, 500.0, -NADIR))
