"""Trajectories and the Sun against conservation laws, secular rates, frame identities and the
almanac."""

from __future__ import annotations

import erfa
import numpy as np
import pytest

from sunwind.forces.gas.flow import EARTH_GM
from sunwind.forces.orbit import AU_M, Elements, Epoch, ephemeris_trajectory, propagate, sun_position
from sunwind.forces.orbit.tle import teme_to_gcrf, tle_trajectory
from sunwind.forces.orbit.trajectory import EARTH_J2
from sunwind.geometry.errors import InputError

EPOCH = Epoch.of("2024-06-01T00:00:00Z")
ISS = (
    "ISS (ZARYA)\n"
    "1 25544U 98067A   24153.50000000  .00016717  00000-0  30159-3 0  9993\n"
    "2 25544  51.6400 208.9163 0005541  35.8890 324.2420 15.49560000456782\n"
)


def test_two_body_keeps_energy_and_momentum_and_closes_after_a_period():
    elements = Elements(7500e3, 0.12, 28.5, 60.0, 120.0, 200.0)
    times = np.linspace(0.0, elements.period_s, 301)
    path = propagate(elements, EPOCH, times, "kepler")
    r, v = path.position_m, path.velocity_m_s
    energy = 0.5 * np.sum(v**2, 1) - EARTH_GM / np.linalg.norm(r, axis=1)
    momentum = np.cross(r, v)
    assert np.ptp(energy) / abs(energy[0]) < 1e-12
    assert np.abs(momentum - momentum[0]).max() / np.linalg.norm(momentum[0]) < 1e-12
    assert np.abs(r[-1] - r[0]).max() < 1e-3
    assert energy[0] == pytest.approx(-EARTH_GM / (2 * elements.a_m), rel=1e-12)


def test_j2_turns_the_node_at_the_secular_rate():
    """dRAAN/dt = -3/2 n J2 (R/p)^2 cos i (Vallado eq. 9-41): the node of the osculating orbit, averaged
    over the last and the first orbit of ten, moves by that rate times the time between, to 2 %."""
    elements = Elements.circular(700.0, 98.0)
    period = elements.period_s
    times = np.linspace(0.0, 10 * period, 4001)
    path = propagate(elements, EPOCH, times, "j2")
    h = np.cross(path.position_m, path.velocity_m_s)
    node = np.unwrap(np.arctan2(h[:, 0], -h[:, 1]))
    first, last = node[times <= period].mean(), node[times >= 9 * period].mean()
    n = 2 * np.pi / period
    rate = -1.5 * n * EARTH_J2 * (6378.137e3 / elements.a_m) ** 2 * np.cos(np.radians(98.0))
    assert (last - first) / (9 * period) == pytest.approx(rate, rel=0.02)


def test_sun_on_the_march_equinox_and_at_perihelion():
    """2024 March 20 03:06 UTC: the Sun crosses the equator of date at the equinox (RA 0, dec 0); 2024
    January 3 00:39 UTC: perihelion at 0.98331 au (Astronomical Almanac)."""
    equinox = Epoch.of("2024-03-20T03:06:00Z")
    direction = sun_position(equinox, np.array([0.0]))[0]
    of_date = erfa.pnm06a(*equinox.jd_tt) @ (direction / np.linalg.norm(direction))
    assert np.abs(of_date - [1.0, 0.0, 0.0]).max() < 2e-4  # 20" of aberration, 1 min of timing
    perihelion = Epoch.of("2024-01-03T00:39:00Z")
    days = np.linspace(-2, 2, 5) * 86400.0
    distance = np.linalg.norm(sun_position(perihelion, days), axis=1) / AU_M
    assert distance.min() == pytest.approx(0.98331, abs=2e-5)
    assert int(np.argmin(distance)) == 2


def test_teme_to_gcrf_agrees_with_the_greenwich_sidereal_route_to_the_earth_fixed_frame():
    """TEME is turned to the Earth-fixed frame by GMST alone (Vallado: r_PEF = R3(GMST) r_TEME); the same
    vector through GCRF and ERFA's full IAU 2006/2000A celestial-to-terrestrial matrix lands within
    the models' differences (well under 1e-6 rad)."""
    seconds = np.array([0.0, 4e5, 9e6])
    rotation = teme_to_gcrf(EPOCH, seconds)
    vector = np.array([4.0e6, -5.0e6, 3.0e6])
    for k, t in enumerate(seconds):
        tt, ut = EPOCH.tt(t), EPOCH.ut1(t)
        gmst = erfa.gmst82(*ut)
        c, s = np.cos(gmst), np.sin(gmst)
        pef = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1.0]]) @ vector
        itrs = erfa.c2t06a(*tt, *ut, 0.0, 0.0) @ (rotation[k] @ vector)
        assert np.linalg.norm(itrs - pef) / np.linalg.norm(vector) < 1e-6


def test_a_tle_propagates_to_a_low_orbit(tmp_path):
    file = tmp_path / "iss.tle"
    file.write_text(ISS)
    times = np.arange(0.0, 5600.0, 60.0)
    path = tle_trajectory(file, Epoch.of("2024-06-01T12:00:00Z"), times)
    altitude = path.altitude_km
    assert 380 < altitude.min() < altitude.max() < 440
    h = np.cross(path.position_m, path.velocity_m_s)
    inclination = np.degrees(np.arccos(h[:, 2] / np.linalg.norm(h, axis=1)))
    assert np.abs(inclination - 51.64).max() < 0.1


def test_an_ephemeris_file_reproduces_the_orbit_it_samples(tmp_path):
    """Rows 10 s apart of a two-body orbit, Hermite-interpolated to other times: within 1 mm (the
    bound h^4 n^4 r / 384 is 0.3 mm)."""
    elements = Elements.circular(450.0, 51.6, 30.0, 10.0)
    rows = np.arange(0.0, 3000.0, 10.0)
    sampled = propagate(elements, EPOCH, rows, "kepler")
    lines = ["time_s,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s"]
    for t, r, v in zip(rows, sampled.position_m, sampled.velocity_m_s, strict=True):
        lines.append(",".join(repr(float(x)) for x in (t, *r, *v)))
    file = tmp_path / "ephemeris.csv"
    file.write_text("\n".join(lines))
    times = np.arange(3.0, 2900.0, 37.0)
    path = ephemeris_trajectory(file, EPOCH, times)
    assert np.abs(path.position_m - propagate(elements, EPOCH, times, "kepler").position_m).max() < 1e-3
    with pytest.raises(InputError, match="outside the ephemeris"):
        ephemeris_trajectory(file, EPOCH, np.array([0.0, 4000.0]))


@pytest.mark.parametrize(
    ("elements", "message"),
    [((6000e3, 0.0, 0, 0, 0, 0), "inside the Earth"), ((8000e3, 1.2, 0, 0, 0, 0), "closed orbit")],
)
def test_impossible_orbits_are_refused(elements, message):
    with pytest.raises(InputError, match=message):
        Elements(*elements)


def test_j2_runs_backward_before_the_epoch_as_forward_after_it():
    """Times before the epoch are integrated backward: J2 moves the craft from the two-body orbit by at
    most half its largest acceleration (3 J2 GM R^2 / r^4 at most) times t^2, before as after."""
    elements = Elements.circular(500.0, 51.6)
    epoch = Epoch.of("2024-03-20T00:00:00Z")
    times = np.array([-600.0, -60.0, 0.0, 60.0, 600.0])
    kepler = propagate(elements, epoch, times, "kepler")
    j2 = propagate(elements, epoch, times, "j2")
    apart = np.linalg.norm(kepler.position_m - j2.position_m, axis=1)
    r = elements.a_m
    bound = 0.5 * 3 * 1.0826e-3 * 3.986e14 * 6.378e6**2 / r**4 * times**2
    assert np.all(apart <= bound + 1e-3)
    assert apart[0] == pytest.approx(apart[-1], rel=0.05) and apart[0] > 100.0  # J2 acts both ways


def test_an_empty_time_list_is_refused_in_one_line():
    with pytest.raises(InputError, match="non-empty list of finite times"):
        propagate(Elements.circular(500.0, 51.6), Epoch.of("2024-03-20T00:00:00Z"), [], "j2")
