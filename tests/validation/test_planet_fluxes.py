"""Checks of the planet albedo and infrared references (:mod:`sunwind.validation.planet_fluxes`).

The brute-force integral over the planet's surface against the dissertation's closed forms (the view
factor everywhere, the albedo form where it is exact, and its known failure at the terminator), its own
convergence, the sphere's closed forms and optics factor, and the ray brute force against the unshadowed
integral, a blocker hiding the whole planet and a half-plane that hides exactly half of it.
"""

from __future__ import annotations

import numpy as np
import pytest

from sunwind.validation.planet_fluxes import (
    SPEED_OF_LIGHT_M_S,
    SphericalPlanet,
    albedo_closed_is_exact,
    albedo_factor_closed,
    f_2,
    infrared_factor_closed,
    phi_1,
    plate_force,
    plate_irradiance,
    plate_moments,
    plate_points,
    shadowed_plate_irradiance,
    sphere_force,
    sphere_force_albedo_lit_cap,
    sphere_force_albedo_subsolar,
    sphere_force_infrared,
    sphere_optics_factor,
    sphere_optics_factor_quadrature,
)

R_EARTH = 6_371_000.0
ALTITUDES = (400e3, 2_000e3, 20_200e3, 35_786e3)
#: A fixed rotation, so that nadir is off every axis and the brute force's frame is exercised.
TURN = np.linalg.qr(np.random.default_rng(7).normal(size=(3, 3)))[0]
NADIR = TURN @ [0.0, 0.0, -1.0]
OPTICS = [(0.0, 0.0, 0.0), (1.0, 1.0, 0.0), (1.0, 0.0, 0.0), (0.6, 0.3, 0.1)]


def from_nadir(psi: float, azimuth: float) -> np.ndarray:
    """The unit vector at ``psi`` [rad] from the nadir, azimuth ``azimuth`` [rad] about it."""
    return TURN @ [np.sin(psi) * np.cos(azimuth), np.sin(psi) * np.sin(azimuth), -np.cos(psi)]


def sun_at(gamma: float, azimuth: float) -> np.ndarray:
    """The Sun at solar zenith angle ``gamma`` [rad] over the sub-spacecraft point."""
    return from_nadir(np.pi - gamma, azimuth)


@pytest.mark.parametrize("altitude", ALTITUDES)
def test_view_factor_equals_brute_force_in_all_three_ranges(altitude):
    planet = SphericalPlanet(R_EARTH, altitude)
    t0, exitance = planet.theta_0, planet.exitance
    psis = np.concatenate(
        [np.radians(np.arange(0, 181, 5)), np.pi / 2 + t0 * np.array([-1, -0.5, 0.5, 0.99])]
    )
    ranges = set()
    for psi in psis:
        n = from_nadir(psi, 0.7)
        got = plate_irradiance(NADIR, None, n, planet, "infrared") / exitance
        want = phi_1(t0, psi)
        # at the branch ends (psi = pi/2 -+ t0) arccos near +-1 turns round-off of 1e-16 into 1e-9
        assert want == pytest.approx(infrared_factor_closed(NADIR, n, t0), rel=1e-8, abs=1e-15)
        if psi > np.pi / 2 + t0:
            assert got == 0.0 and want == 0.0
        else:
            assert got == pytest.approx(want, rel=1e-6, abs=1e-15)
        ranges.add(int(psi > np.pi / 2 - t0) + int(psi > np.pi / 2 + t0))
    assert ranges == {0, 1, 2}


def test_closed_forms_take_arrays():
    t0 = np.array([[0.2], [1.2]])
    psi = np.linspace(0.0, np.pi, 7)
    assert np.shape(phi_1(t0, psi)) == (2, 7)
    assert phi_1(t0, psi)[1, 3] == pytest.approx(float(phi_1(1.2, np.pi / 2)), rel=1e-15)
    normals = np.array([from_nadir(p, 0.3) for p in psi])
    assert np.shape(infrared_factor_closed(NADIR, normals, 1.2)) == (7,)
    assert np.shape(albedo_factor_closed(NADIR, sun_at(0.1, 0.0), normals, 1.2)) == (7,)


def test_brute_force_converges_with_both_kinks_in_view():
    """Partial view (the plate's horizon crosses the cap) and the terminator on the cap."""
    planet = SphericalPlanet(R_EARTH, 400e3)
    args = (NADIR, sun_at(np.radians(75.0), 0.0), from_nadir(np.radians(92.0), 2.0), planet)
    values = [plate_irradiance(*args, order=order) for order in (8, 16, 32, 64)]
    errors = [abs(v - values[-1]) / values[-1] for v in values[:-1]]
    assert errors[0] > errors[1] > errors[2] and errors[1] < 1e-4
    assert errors[2] < 1e-10


@pytest.mark.parametrize("altitude", ALTITUDES)
def test_albedo_closed_form_is_exact_when_the_whole_cap_is_lit_and_in_view(altitude):
    planet = SphericalPlanet(R_EARTH, altitude)
    t0, rng = planet.theta_0, np.random.default_rng(int(altitude))
    for _ in range(12):
        sun = sun_at(rng.uniform(0.0, t0), rng.uniform(0.0, 2 * np.pi))
        n = from_nadir(rng.uniform(0.0, np.pi / 2 - t0), rng.uniform(0.0, 2 * np.pi))
        assert albedo_closed_is_exact(NADIR, sun, n, t0)
        got = plate_irradiance(NADIR, sun, n, planet) / (planet.albedo * planet.solar_flux_W_m2)
        assert got == pytest.approx(albedo_factor_closed(NADIR, sun, n, t0), rel=1e-6)


def test_albedo_closed_form_fails_at_the_terminator():
    """A nadir plate with the Sun on the sub-spacecraft horizon: the closed form gives 0, the truth 2 %."""
    planet = SphericalPlanet(R_EARTH, 400e3)
    sun = sun_at(np.pi / 2, 0.4)
    assert not albedo_closed_is_exact(NADIR, sun, NADIR, planet.theta_0)
    assert albedo_factor_closed(NADIR, sun, NADIR, planet.theta_0) < 1e-15
    got = plate_irradiance(NADIR, sun, NADIR, planet) / (planet.albedo * planet.solar_flux_W_m2)
    assert 0.015 < got < 0.03  # 0.0203


@pytest.mark.parametrize("source", ["albedo", "infrared"])
def test_a_plate_facing_away_sees_nothing(source):
    planet = SphericalPlanet(R_EARTH, 400e3)
    sun = sun_at(0.3, 1.0)
    for n in (-NADIR, from_nadir(np.pi / 2 + planet.theta_0 + 1e-6, 0.5)):
        assert plate_irradiance(NADIR, sun, n, planet, source) == 0.0
        assert not np.any(plate_force(NADIR, sun, n, planet, (0.6, 0.3, 0.1), source))
    assert plate_irradiance(NADIR, NADIR, NADIR, planet) == 0.0  # the Sun behind the planet: night below


@pytest.mark.parametrize("optics", OPTICS)
def test_nadir_plate_force_in_infrared_against_its_closed_form(optics):
    """Nadir plate, uniform planet: ``int (M/pi) cos^2 dOmega = (2M/3)(1 - cos^3 theta_0)``."""
    rho, beta, sigma = optics
    planet = SphericalPlanet(R_EARTH, 1_000e3)
    m, t0 = planet.exitance, planet.theta_0
    second = 2 * m / 3 * (1 - np.cos(t0) ** 3)
    along = (
        (1 - sigma - rho * beta) * second
        + 2 * rho * beta * second
        + 2 / 3 * rho * (1 - beta) * m * np.sin(t0) ** 2
    )
    got = plate_force(NADIR, None, NADIR, planet, optics, "infrared")
    np.testing.assert_allclose(
        got, -along / SPEED_OF_LIGHT_M_S * NADIR, rtol=1e-12, atol=1e-12 * abs(along) / 3e8
    )


def test_opposite_plates_differ_by_the_flux_vector():
    """``E(n) - E(-n) = n . int L omega dOmega``: the plate and sphere quadratures agree."""
    planet, a = SphericalPlanet(R_EARTH, 800e3), 0.7
    sun = sun_at(np.radians(80.0), 0.9)
    flux = -sphere_force(a, NADIR, sun, planet) * SPEED_OF_LIGHT_M_S / (np.pi * a**2)
    for psi in np.radians([0.0, 30.0, 70.0, 90.0, 110.0]):
        n = from_nadir(psi, 2.5)
        difference = plate_irradiance(NADIR, sun, n, planet) - plate_irradiance(NADIR, sun, -n, planet)
        assert difference == pytest.approx(n @ flux, rel=1e-10, abs=1e-10 * np.linalg.norm(flux))


@pytest.mark.parametrize("altitude", ALTITUDES)
def test_sphere_closed_forms_against_brute_force(altitude):
    planet, a = SphericalPlanet(R_EARTH, altitude), 0.5
    ir = sphere_force(a, NADIR, None, planet, source="infrared")
    np.testing.assert_allclose(
        ir, -sphere_force_infrared(a, R_EARTH, altitude, planet.exitance) * NADIR, rtol=1e-10
    )
    subsolar = sphere_force(a, NADIR, -NADIR, planet)
    magnitude = sphere_force_albedo_subsolar(a, R_EARTH, altitude, planet.albedo, planet.solar_flux_W_m2)
    np.testing.assert_allclose(subsolar, -magnitude * NADIR, rtol=1e-10)
    assert magnitude == pytest.approx(
        np.pi * a**2 * planet.albedo * planet.solar_flux_W_m2 * f_2(planet.theta_0) / SPEED_OF_LIGHT_M_S
    )
    for gamma in planet.theta_0 * np.array([0.3, 1.0]):
        sun = sun_at(gamma, 1.3)
        np.testing.assert_allclose(
            sphere_force(a, NADIR, sun, planet),
            sphere_force_albedo_lit_cap(a, NADIR, sun, planet),
            rtol=1e-10,
        )


def test_sphere_optics_factor_by_quadrature_and_over_the_surface():
    """The factor by quadrature of eq. (4) under one beam, and the force on a sphere under the extended
    planet as plate forces integrated over its surface (normals: Gauss in the polar angle from nadir,
    split where a plate starts and stops seeing the whole disc, uniform in azimuth)."""
    for optics in OPTICS:
        assert sphere_optics_factor_quadrature(*optics) == pytest.approx(
            sphere_optics_factor(*optics), rel=1e-13
        )
    assert sphere_optics_factor(1.0, 0.0, 0.0) == pytest.approx(1 + 4 / 9)
    planet, a = SphericalPlanet(R_EARTH, 2_000e3), 1.0
    sun, t0 = sun_at(np.radians(50.0), 0.4), planet.theta_0
    x, w = np.polynomial.legendre.leggauss(10)
    breaks = np.array([0.0, np.pi / 2 - t0, np.pi / 2 + t0, np.pi])
    psi = (0.5 * (breaks[1:, None] + breaks[:-1, None]) + 0.5 * np.diff(breaks)[:, None] * x).ravel()
    w_psi = (0.5 * np.diff(breaks)[:, None] * w).ravel() * np.sin(psi)
    azimuths = np.arange(36) * 2 * np.pi / 36
    moments = [plate_moments(NADIR, sun, from_nadir(p, az), planet, order=16) for p in psi for az in azimuths]
    weights = np.repeat(w_psi, len(azimuths)) * 2 * np.pi / 36 * a**2
    for optics in OPTICS:
        total = sum(wk * m.force_N_m2(*optics) for wk, m in zip(weights, moments, strict=True))
        want = sphere_force(a, NADIR, sun, planet, optics)
        assert np.linalg.norm(total - want) < 1e-6 * np.linalg.norm(want)  # 6e-8


def square(centre, side: float, turn_deg: float) -> np.ndarray:
    """Corners (4, 3) of a square in a plane z = const, turned about z, counter-clockwise seen from +z."""
    c, s = np.cos(np.radians(turn_deg)), np.sin(np.radians(turn_deg))
    corners = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]) * side / 2
    return corners @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]).T + np.asarray(centre, dtype=float)


def triangles(quad: np.ndarray) -> np.ndarray:
    return np.array([quad[[0, 1, 2]], quad[[0, 2, 3]]])


# The ray cases: the planet toward +z in the body frame, a 1 m plate at z = 0 facing it.
UP = np.array([0.0, 0.0, 1.0])
PLATE = square([0.0, 0.0, 0.0], 1.0, 0.0)
SUN_UNDER = -np.array([0.4, 0.3, 0.85]) / np.linalg.norm([0.4, 0.3, 0.85])


def test_plate_points_share_the_area():
    points, share = plate_points(PLATE[:3], 5)
    assert len(points) == 25 and share.sum() == pytest.approx(1.0)
    np.testing.assert_allclose(share @ points, PLATE[:3].mean(axis=0), atol=1e-15)
    points, share = plate_points(PLATE, 4)
    np.testing.assert_allclose(share @ points, 0.0, atol=1e-15)


def test_rays_without_blockers_equal_the_unshadowed_brute_force():
    planet = SphericalPlanet(R_EARTH, 400e3)
    n = np.array([0.3, 0.0, 1.0]) / np.hypot(0.3, 1.0)
    got = shadowed_plate_irradiance(np.zeros((0, 3, 3)), PLATE, n, UP, SUN_UNDER, planet)
    same_nodes = plate_moments(UP, SUN_UNDER, n, planet, order=16)
    assert got.irradiance_W_m2 == pytest.approx(same_nodes.irradiance_W_m2, rel=1e-12)
    np.testing.assert_allclose(
        got.force_N_m2(0.6, 0.3, 0.1), same_nodes.force_N_m2(0.6, 0.3, 0.1), rtol=1e-12
    )
    exact = plate_irradiance(UP, SUN_UNDER, n, planet)
    assert got.irradiance_W_m2 == pytest.approx(exact, rel=1e-4)  # the coarse cap quadrature


def test_a_blocker_over_the_whole_cap_leaves_nothing_and_one_behind_changes_nothing():
    planet = SphericalPlanet(R_EARTH, 400e3)
    wall = triangles(square([0.0, 0.0, 0.1], 2_000.0, 0.0))
    hidden = shadowed_plate_irradiance(wall, PLATE, UP, UP, SUN_UNDER, planet, resolution=(8, 8))
    assert hidden.irradiance_W_m2 == 0.0 and not np.any(hidden.force_N_m2(0.6, 0.3, 0.1))
    behind = triangles(square([0.0, 0.0, -0.1], 2_000.0, 0.0))
    open_sky = shadowed_plate_irradiance(behind, PLATE, UP, UP, SUN_UNDER, planet, resolution=(8, 8))
    assert open_sky.irradiance_W_m2 == pytest.approx(
        plate_moments(UP, SUN_UNDER, UP, planet, order=8).irradiance_W_m2, rel=1e-14
    )


def test_a_half_plane_hides_half_of_a_uniform_planet():
    """A blocker over x > 0 at 0.2 m: points at x and -x see complementary halves, so the mean is half."""
    planet = SphericalPlanet(R_EARTH, 400e3)
    half = triangles(np.array([[0.0, -1e3, 0.2], [1e3, -1e3, 0.2], [1e3, 1e3, 0.2], [0.0, 1e3, 0.2]]))
    got = shadowed_plate_irradiance(half, PLATE, UP, UP, None, planet, "infrared").irradiance_W_m2
    assert got == pytest.approx(0.5 * plate_irradiance(UP, None, UP, planet, "infrared"), rel=1e-4)  # 2e-6


def test_a_small_plate_above_a_large_one_converges():
    """A 0.4 m plate 0.3 m toward the planet, turned 23 deg: the default within 1e-4 of a finer run."""
    planet = SphericalPlanet(R_EARTH, 400e3)
    blocker = triangles(square([0.1, -0.05, 0.3], 0.4, 23.0))
    coarse = shadowed_plate_irradiance(blocker, PLATE, UP, UP, SUN_UNDER, planet)
    fine = shadowed_plate_irradiance(blocker, PLATE, UP, UP, SUN_UNDER, planet, resolution=(64, 32))
    open_sky = plate_moments(UP, SUN_UNDER, UP, planet)
    assert 0.5 * open_sky.irradiance_W_m2 < fine.irradiance_W_m2 < 0.95 * open_sky.irradiance_W_m2
    assert abs(coarse.irradiance_W_m2 - fine.irradiance_W_m2) < 1e-4 * open_sky.irradiance_W_m2  # 2.3e-5
    for optics in OPTICS:
        scale = np.linalg.norm(open_sky.force_N_m2(*optics))
        assert (
            np.linalg.norm(coarse.force_N_m2(*optics) - fine.force_N_m2(*optics)) < 3e-4 * scale
        )  # at most 1.1e-4
