"""Rows smoothed with the attitude's rate (METHOD.md "Attitude from heat fluxes"): a constant-rate
tumble on a circular orbit, the fluxes made by the flux model with noise, solved row by row and then
smoothed; against the truth, the noise-free limit, an ambiguous row and a change of rate."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import sunwind as sw
from sunwind.forces.gas.flow import EARTH_GM
from sunwind.forces.sensing import (
    AttitudeSolution,
    FluxRows,
    Minimum,
    attitude_from_fluxes,
    smoothed_attitudes,
)
from sunwind.forces.sensing.forward import flux_model
from sunwind.forces.sensing.smoothing import smoothed_rows

ALTITUDE_KM = 500.0
MEAN_MOTION = math.sqrt(EARTH_GM / (6378137.0 + ALTITUDE_KM * 1e3) ** 3)


def angle_deg(a, b):
    return np.degrees(np.arccos(np.clip(np.sum(a * b, axis=-1), -1.0, 1.0)))


def tumble(times, rate_deg_s, seed=7, still_after=np.inf):
    """Body-frame Sun and nadir of a body turning at a constant rate about a random axis (still after
    ``still_after`` s) on a circular orbit in the inertial x-y plane (the Sun fixed), the rate [deg/s],
    and the inertial directions of each row."""
    rng = np.random.default_rng(seed)
    axis = rng.normal(size=3)
    omega = math.radians(rate_deg_s) * axis / np.linalg.norm(axis)
    start = Rotation.random(random_state=3)
    sun_eci = np.array([0.3, -0.8, 0.5]) / np.linalg.norm([0.3, -0.8, 0.5])
    phase = MEAN_MOTION * np.asarray(times)
    nadir_eci = -np.column_stack([np.cos(phase), np.sin(phase), np.zeros_like(phase)])
    velocity_eci = np.column_stack([-np.sin(phase), np.cos(phase), np.zeros_like(phase)])
    turns = [(start * Rotation.from_rotvec(omega * min(t, still_after))).inv() for t in times]
    sun = np.array([turn.apply(sun_eci) for turn in turns])
    nadir = np.array([turn.apply(n) for turn, n in zip(turns, nadir_eci, strict=True)])
    return sun, nadir, np.degrees(omega), (np.tile(sun_eci, (len(times), 1)), nadir_eci, velocity_eci)


def row(t, sun, nadir, sigma_deg=0.1, alternatives=()):
    best = Minimum(sun, nadir, 1.0, sigma_deg, sigma_deg, np.zeros(6), 4)
    return AttitudeSolution(t, best, tuple(alternatives), False, None, None, np.zeros(6), 0.0)


@pytest.mark.slow
@pytest.mark.parametrize(("noise", "end_s"), [(0.0, 400.0), (0.03, 1200.0)])
def test_a_tumble_smoothed_against_the_truth(noise, end_s):
    """Rows 10 s apart, 0.4 deg/s, a 120 s window. Noise-free (41 rows): the truth to 1e-4 deg. 3 % noise
    (121 rows, 47 in eclipse): row by row the Sun is found to 0.63 deg (median) and one nadir is 80 deg
    off (an ambiguous row); smoothed, the medians fall below 0.3 deg, every row within 1.1 deg, the sigma
    consistent and the body rate found."""
    times = np.arange(0.0, end_s + 1.0, 10.0)
    sun, nadir, rate, inertial = tumble(times, 0.4)
    black = sw.Material("black", 0.07, 0.0, emissivity=0.82)
    cube = sw.load(sw.meshes.sensor_cube(), uniform=black, threads=1)
    model = flux_model(cube, ALTITUDE_KM)
    rng = np.random.default_rng(11)
    fluxes = np.array([model.fluxes(s, n).total for s, n in zip(sun, nadir, strict=True)])
    fluxes *= 1.0 + noise * rng.normal(size=fluxes.shape)
    rows = FluxRows(times, cube.craft.part_names, fluxes, *inertial)
    found = smoothed_attitudes(
        attitude_from_fluxes(cube, rows, ALTITUDE_KM, sigma=max(noise, 1e-3)), rows, 120.0
    )
    lit = [k for k, r in enumerate(found.rows) if not r.eclipse]
    assert len(lit) == (74 if end_s == 1200.0 else len(lit)) and all(
        found.smoothed[k] is not None for k in lit
    )
    assert all(found.smoothed[k] is None for k in range(len(times)) if k not in lit)
    smoothed = [found.smoothed[k] for k in lit]
    sun_error = angle_deg(np.array([s.sun for s in smoothed]), sun[lit])
    nadir_error = angle_deg(np.array([s.nadir for s in smoothed]), nadir[lit])
    rate_error = np.array([np.linalg.norm(s.rate_deg_s - rate) for s in smoothed])
    if noise == 0.0:
        assert sun_error.max() < 1e-4 and nadir_error.max() < 1e-4 and rate_error.max() < 1e-6
        return
    raw_sun = angle_deg(np.array([found.rows[k].best.sun for k in lit]), sun[lit])
    raw_nadir = angle_deg(np.array([found.rows[k].best.nadir for k in lit]), nadir[lit])
    assert np.median(sun_error) < 0.6 * np.median(raw_sun) and np.median(nadir_error) < 0.6 * np.median(
        raw_nadir
    )
    assert raw_nadir.max() > 30.0 and max(sun_error.max(), nadir_error.max()) < 2.0
    sigma_sun = np.array([s.sigma_sun_deg for s in smoothed])
    sigma_nadir = np.array([s.sigma_nadir_deg for s in smoothed])
    for error, sigma in ((sun_error, sigma_sun), (nadir_error, sigma_nadir)):
        assert np.mean(error <= 3.0 * sigma) >= 0.9 and 0.3 <= np.median(error / sigma) <= 1.5
    sigma_rate = np.array([s.sigma_rate_deg_s for s in smoothed])
    assert np.median(rate_error) <= 2.0 * np.median(sigma_rate) and np.median(rate_error) < 0.05
    assert all(s.explained for s in smoothed) and sum(s.switched for s in smoothed) > 0


def test_an_ambiguous_row_takes_the_alternative_the_motion_agrees_with():
    """Seven exact rows of a 0.5 deg/s turn; row 3's best is a wrong attitude and the truth only its
    alternative: the smoothed row is the truth and says it switched, as do its neighbours' windows."""
    times = np.arange(0.0, 61.0, 10.0)
    sun, nadir, rate, _ = tumble(times, 0.5, seed=2)
    rows = [row(t, s, n) for t, s, n in zip(times, sun, nadir, strict=True)]
    truth = rows[3].best
    wrong = Minimum(-sun[3], nadir[3] * [1, 1, -1] / 1.0, 0.5, 0.1, 0.1, np.zeros(6), 4)
    rows[3] = AttitudeSolution(30.0, wrong, (truth,), False, None, None, np.zeros(6), 0.0)
    fitted = smoothed_rows(tuple(rows), 60.0, MEAN_MOTION)
    assert [f.switched for f in fitted] == [1] * 7  # every window holds row 3
    assert angle_deg(fitted[3].sun, sun[3]) < 1e-5 and angle_deg(fitted[3].nadir, nadir[3]) < 1e-5
    np.testing.assert_allclose(fitted[3].rate_deg_s, rate, atol=1e-8)


def noisy_rows(times, sun, nadir, noise_deg, seed=0):
    """Rows whose directions are the truth turned by ``noise_deg`` along each tangent, that 1-sigma said."""
    rng = np.random.default_rng(seed)

    def noisy(v):
        v = v + math.radians(noise_deg) * rng.normal(size=3)
        return v / np.linalg.norm(v)

    total = noise_deg * math.sqrt(2.0)  # a direction's 1-sigma: noise_deg along each of its two tangents
    return tuple(
        row(t, noisy(s), noisy(n), sigma_deg=total) for t, s, n in zip(times, sun, nadir, strict=True)
    )


def test_a_stop_inside_the_window_leaves_out_the_rows_past_it():
    """A body that stops turning halfway (0.5 deg/s, then still), 0.02 deg of noise, a 60 s window: the
    windows across the stop fit the majority's rate and leave out the rows on the other side of it (the
    row at the stop agrees with both); windows away from it leave nothing out; every row is found within
    3 sigma, and the rate on each side is its own."""
    times = np.arange(0.0, 201.0, 10.0)
    sun, nadir, rate, _ = tumble(times, 0.5, seed=4, still_after=100.0)
    fitted = smoothed_rows(noisy_rows(times, sun, nadir, 0.02), 60.0, MEAN_MOTION)
    assert all(f.rejected >= 1 for f in fitted[8:13]) and all(f.explained for f in fitted)
    assert all(f.rejected == 0 for f in fitted[:7] + fitted[14:])
    for k, f in enumerate(fitted):
        assert angle_deg(f.sun, sun[k]) <= 3.0 * f.sigma_sun_deg
        assert angle_deg(f.nadir, nadir[k]) <= 3.0 * f.sigma_nadir_deg
    assert all(np.linalg.norm(f.rate_deg_s - rate) < 0.01 for f in fitted[:9])


@pytest.mark.slow
def test_a_body_spinning_up_is_not_explained_by_one_rate():
    """A body spun up at 0.005 deg/s^2 from rest, rows every 20 s with 0.02 deg of noise, a 100 s window:
    no majority of a window's rows turns at one rate (over 60 s the spin-up is 2 deg from any constant
    rate), so the windows are said not explained and their misfit is large."""
    times = np.arange(0.0, 201.0, 20.0)
    axis = np.array([0.36, -0.48, 0.8])
    start = Rotation.random(random_state=3)
    sun_eci = np.array([0.3, -0.8, 0.5]) / np.linalg.norm([0.3, -0.8, 0.5])
    phase = MEAN_MOTION * times
    nadir_eci = -np.column_stack([np.cos(phase), np.sin(phase), np.zeros_like(phase)])
    turns = [(start * Rotation.from_rotvec(axis * math.radians(0.0025) * t**2)).inv() for t in times]
    sun = np.array([turn.apply(sun_eci) for turn in turns])
    nadir = np.array([turn.apply(n) for turn, n in zip(turns, nadir_eci, strict=True)])
    fitted = smoothed_rows(noisy_rows(times, sun, nadir, 0.02), 100.0, MEAN_MOTION)
    assert all(not f.explained and f.misfit > 3.0 for f in fitted[2:9])


def test_windows_too_short_are_left_alone_and_eclipses_are_not_smoothed():
    times = np.array([0.0, 10.0, 20.0, 500.0])
    sun, nadir, _, _ = tumble(times, 0.3)
    rows = [row(t, s, n) for t, s, n in zip(times, sun, nadir, strict=True)]
    dark = Minimum(None, nadir[1], 1.0, None, 0.1, np.zeros(6), 2)
    rows[1] = AttitudeSolution(10.0, dark, (), True, None, None, np.zeros(6), 0.0)
    assert smoothed_rows(tuple(rows), 60.0, MEAN_MOTION) == (None, None, None, None)


def test_a_wrong_row_without_alternatives_is_left_out_and_found_from_the_others():
    """21 rows of a 0.5 deg/s turn found to 0.05 deg; row 10's solution is 30 deg off and has no
    alternative (a confident wrong answer). Every 80 s window holding it leaves it out (its chi2 is far
    beyond the 99.9 % quantile), is explained, and finds the truth; row 10's own smoothed directions come
    from the other rows, within 4 sigma of the truth. Windows without it leave nothing out."""
    times = np.arange(0.0, 201.0, 10.0)
    sun, nadir, rate, _ = tumble(times, 0.5, seed=5)
    rng = np.random.default_rng(3)

    def noisy(v):
        v = v + math.radians(0.05) * rng.normal(size=3)
        return v / np.linalg.norm(v)

    total = 0.05 * math.sqrt(2.0)
    rows = [row(t, noisy(s), noisy(n), sigma_deg=total) for t, s, n in zip(times, sun, nadir, strict=True)]
    turn = Rotation.from_rotvec(math.radians(30.0) * np.array([0.6, 0.8, 0.0]))
    rows[10] = row(100.0, turn.apply(sun[10]), turn.apply(nadir[10]), sigma_deg=total)
    fitted = smoothed_rows(tuple(rows), 80.0, MEAN_MOTION)
    holding = [abs(t - 100.0) <= 40.0 for t in times]
    assert [f.rejected for f in fitted] == [int(h) for h in holding]
    assert [f.outlier for f in fitted] == [k == 10 for k in range(21)]
    assert all(f.explained for f in fitted)
    for k, f in enumerate(fitted):
        assert angle_deg(f.sun, sun[k]) <= 4.0 * f.sigma_sun_deg
        assert angle_deg(f.nadir, nadir[k]) <= 4.0 * f.sigma_nadir_deg
        assert np.linalg.norm(f.rate_deg_s - rate) <= 4.0 * f.sigma_rate_deg_s


@pytest.mark.slow
def test_a_row_with_two_sensor_channels_swapped_is_said_and_mended(run_cli, tmp_path):
    """Telemetry of a 0.3 deg/s turn every 10 s (the flux model, 1 % noise) where row 10 has the +x and
    -x sensors' channels swapped: alone, that row is explained by the mirrored attitude, many degrees
    off; smoothed over 80 s it is left out, said on a warning, and its smoothed directions are the truth's
    within 4 sigma; the CSV says which rows left it out."""
    times = np.arange(0.0, 201.0, 10.0)
    sun, nadir, _, _ = tumble(times, 0.3, seed=8)
    black = sw.Material("black", 0.07, 0.0, emissivity=0.82)
    cube = sw.load(sw.meshes.sensor_cube(), uniform=black, threads=1)
    model = flux_model(cube, ALTITUDE_KM)
    fluxes = np.array([model.fluxes(s, n).total for s, n in zip(sun, nadir, strict=True)])
    fluxes *= 1.0 + 0.01 * np.random.default_rng(5).normal(size=fluxes.shape)
    px, mx = (cube.craft.part_names.index(name) for name in ("sensor_px", "sensor_mx"))
    fluxes[10, [px, mx]] = fluxes[10, [mx, px]]
    assert min(fluxes[10, px], fluxes[10, mx]) > 10.0  # both lit or warm: a swap that changes the answer
    path = tmp_path / "fluxes.csv"
    lines = [",".join(["time_s", *cube.craft.part_names])]
    lines += [",".join(f"{v:.6g}" for v in (t, *f)) for t, f in zip(times, fluxes, strict=True)]
    path.write_text("\n".join(lines) + "\n")
    mesh = sw.meshes.sample_path().parent / "sensor_cube.obj"  # sensor_cube(), bundled
    base = ["attitude", mesh, "--reflectivity", "0.07", "--specular-fraction", "0", "--emissivity", "0.82"]
    base += ["--fluxes", path, "--altitude", str(ALTITUDE_KM), "--smooth", "80"]
    output = tmp_path / "rows.csv"
    code, out, err = run_cli(*base, "--json", "-o", output)
    assert code == 0, err
    rows = json.loads(out)["rows"]
    assert angle_deg(np.array(rows[10]["sun_body"]), sun[10]) > 5.0
    smoothed = rows[10]["smoothed"]
    assert smoothed["outlier"] and smoothed["explained"]
    assert "t = 100 s: the row's own solution disagrees with the motion of the 8 rows around it" in err
    assert "sunwind: notice: 9 windows (the first at t = 60 s) leave out rows that disagree" in err
    assert angle_deg(np.array(smoothed["sun_body"]), sun[10]) <= 4.0 * smoothed["sigma_deg"]["sun"]
    assert angle_deg(np.array(smoothed["nadir_body"]), nadir[10]) <= 4.0 * smoothed["sigma_deg"]["nadir"]
    table = [line.split(",") for line in output.read_text().splitlines() if not line.startswith("#")]
    rejected = [int(line[table[0].index("smoothed_rejected")]) for line in table[1:]]
    assert rejected == [int(abs(t - 100.0) <= 40.0) for t in times]
