"""Eclipse against a shadow computed here independently: rays from the spacecraft to points spread
over the solar disc, each tested against the Earth's sphere (conical), and the cylinder behind the
Earth solved for its entry and exit (cylindrical)."""

from __future__ import annotations

import numpy as np
import pytest

from sunwind.forces.orbit import AU_M, Elements, Epoch, propagate, solar_fraction
from sunwind.forces.orbit.sun import MOON_RADIUS_M, SUN_RADIUS_M, moon_position, sun_position

R_EARTH = 6378.137e3
EPOCH = Epoch.of("2024-06-01T00:00:00Z")


def _disc_points(n_rings: int = 400) -> tuple[np.ndarray, np.ndarray]:
    """Points (u, v) on the unit disc with equal area weights: midpoint rings x midpoint angles."""
    rings = (np.arange(n_rings) + 0.5) / n_rings
    u, v, w = [], [], []
    for k, rho in enumerate(rings):
        count = max(8, int(2 * np.pi * rho * n_rings))
        phi = (np.arange(count) + 0.5) * 2 * np.pi / count
        u.append(rho * np.cos(phi))
        v.append(rho * np.sin(phi))
        w.append(np.full(count, (2 * k + 1) / n_rings**2 / count))  # ring area share / count
    return np.stack([np.concatenate(u), np.concatenate(v)], 1), np.concatenate(w)


def brute_fraction(r: np.ndarray, sun: np.ndarray, centre=(0.0, 0.0, 0.0), radius: float = R_EARTH) -> float:
    """Share of the solar disc (uniform brightness) whose ray from ``r`` misses the sphere of ``radius``
    at ``centre`` (the Earth by default)."""
    r = r - np.asarray(centre)
    sun = sun - np.asarray(centre)
    points, weights = _disc_points()
    axis = (sun - r) / np.linalg.norm(sun - r)
    e1 = np.cross(axis, [0.0, 0.0, 1.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(axis, e1)
    targets = sun + SUN_RADIUS_M * (points[:, :1] * e1 + points[:, 1:] * e2)
    d = targets - r
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    b = d @ r
    disc = b**2 - (r @ r - radius**2)
    blocked = (disc > 0) & (-b - np.sqrt(np.maximum(disc, 0)) > 0)
    return float(weights[~blocked].sum() / weights.sum())


def _orbit(beta_deg: float, altitude_km: float = 500.0, step: float = 1.0):
    """A circular equatorial orbit and a fixed Sun at 1 au, ``beta_deg`` out of the orbit plane."""
    period = Elements.circular(altitude_km, 0.0).period_s
    times = np.arange(0.0, period, step)
    path = propagate(Elements.circular(altitude_km, 0.0), EPOCH, times, "kepler")
    beta = np.radians(beta_deg)
    sun = np.tile(AU_M * np.array([np.cos(beta), 0.0, np.sin(beta)]), (len(times), 1))
    return path, sun


@pytest.mark.parametrize("beta_deg", [0.0, 40.0])
def test_conical_fraction_through_the_penumbra_matches_rays_to_the_solar_disc(beta_deg):
    """Every step within the penumbra (and a few in full Sun and umbra) to 1e-3 of the visible share."""
    path, sun = _orbit(beta_deg)
    fraction = solar_fraction(path.position_m, sun, "conical")
    partial = np.flatnonzero((fraction > 0) & (fraction < 1))
    assert partial.size >= 10  # the penumbra lasts ~10 s at 500 km
    picks = np.concatenate([partial, [0, int(np.argmin(fraction))]])
    for i in picks:
        assert fraction[i] == pytest.approx(brute_fraction(path.position_m[i], sun[i]), abs=1e-3)


def _crossings(times: np.ndarray, values: np.ndarray, level: float) -> list[float]:
    """Times where ``values`` crosses ``level`` (linear between samples)."""
    above = values > level
    out = []
    for i in np.flatnonzero(above[1:] != above[:-1]):
        t0, t1, v0, v1 = times[i], times[i + 1], values[i], values[i + 1]
        out.append(t0 + (level - v0) * (t1 - t0) / (v1 - v0))
    return out


@pytest.mark.parametrize("beta_deg", [0.0, 40.0])
def test_cylindrical_entry_and_exit_to_one_second(beta_deg):
    """The shadow cylinder entered and left where the distance from its axis is R on the night side:
    for a circular equatorial orbit of radius a at angle theta = n t, with the Sun at beta,
    r . s = a cos(theta) cos(beta) and |r x s|^2 = a^2 - (r . s)^2, so the shadow is
    cos(theta) < -sqrt(1 - R^2 / a^2) / cos(beta)."""
    path, sun = _orbit(beta_deg, step=0.5)
    a = np.linalg.norm(path.position_m[0])
    n = 2 * np.pi / Elements.circular(500.0, 0.0).period_s
    edge = np.arccos(-np.sqrt(1 - (R_EARTH / a) ** 2) / np.cos(np.radians(beta_deg)))
    expected = sorted([edge / n, (2 * np.pi - edge) / n])
    found = _crossings(path.time_s, solar_fraction(path.position_m, sun, "cylindrical"), 0.5)
    assert np.allclose(found, expected, atol=1.0)


def test_conical_penumbra_edges_where_the_discs_touch():
    """Penumbra entry and umbra entry where the apparent Earth and Sun discs touch outside and inside:
    separation c = a + b and c = b - a, found here by bisection on the geometry."""
    path, sun = _orbit(0.0, step=0.25)
    fraction = solar_fraction(path.position_m, sun, "conical")

    def separation_minus(t: float, sign: float) -> float:
        one = propagate(Elements.circular(500.0, 0.0), EPOCH, np.array([t]), "kepler").position_m[0]
        to_sun = sun[0] - one
        a = np.arcsin(SUN_RADIUS_M / np.linalg.norm(to_sun))
        b = np.arcsin(R_EARTH / np.linalg.norm(one))
        c = np.arccos(-one @ to_sun / (np.linalg.norm(one) * np.linalg.norm(to_sun)))
        return c - (b + sign * a)

    def root(lo: float, hi: float, sign: float) -> float:
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if np.sign(separation_minus(mid, sign)) == np.sign(separation_minus(lo, sign)):
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)

    period = path.time_s[-1]
    penumbra_in = root(0.0, period / 2, +1.0)
    umbra_in = root(0.0, period / 2, -1.0)
    first_partial = path.time_s[np.argmax(fraction < 1)]
    first_dark = path.time_s[np.argmax(fraction == 0)]
    assert first_partial == pytest.approx(penumbra_in, abs=1.0)
    assert first_dark == pytest.approx(umbra_in, abs=1.0)
    assert 5.0 < umbra_in - penumbra_in < 20.0


def test_no_eclipse_model_is_always_lit():
    path, sun = _orbit(0.0, step=60.0)
    assert np.all(solar_fraction(path.position_m, sun, "none") == 1.0)


def test_the_moon_occults_by_the_same_rules():
    """Spacecraft across the Moon's shadow during the eclipse of 2024 April 8: the visible share
    against rays to the solar disc tested against the Moon's sphere, umbra to full Sun."""
    epoch = Epoch.of("2024-04-08T18:17:00Z")
    sun, moon = sun_position(epoch, np.array([0.0]))[0], moon_position(epoch, np.array([0.0]))[0]
    axis = (moon - sun) / np.linalg.norm(moon - sun)
    side = np.cross(axis, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side)
    shares = []
    for offset_km in (0.0, 1500.0, 2500.0, 3500.0, 4500.0, 9000.0):
        r = moon + 2.0e8 * axis + offset_km * 1e3 * side  # 200 000 km behind the Moon
        share = solar_fraction(r[None], sun[None], "conical", moon[None])[0]
        earth = solar_fraction(r[None], sun[None], "conical")[0]
        expected = brute_fraction(r, sun, moon, MOON_RADIUS_M) * earth
        assert share == pytest.approx(expected, abs=1e-3)
        shares.append(share)
    assert shares[0] < 0.5 and 0 < shares[2] < 1 and shares[-1] == 1.0
