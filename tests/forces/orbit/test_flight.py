"""Orbit runs against the single-attitude calls they are made of, and the momentum against its
integral."""

from __future__ import annotations

import json

import numpy as np
import pytest

from helpers.runs import stopped_then_resumed
from sunwind.forces import Model, drag, nrlmsis, srp
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.orbit import SERIES, AttitudeLaw, Elements, Epoch, OrbitLoads, fly, propagate
from sunwind.forces.orbit.flight import geodetic
from sunwind.forces.orbit.sun import AU_M, sun_position
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.tables.jobs import GasOptions, SrpSetup
from sunwind.geometry.materials import Material
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.primitives import box_wing

EPOCH = Epoch.of("2024-06-01T00:00:00Z")
PAINT = Material("paint", 0.5, 0.4, 0.0)


@pytest.fixture(scope="module")
def model():
    craft = build_spacecraft(box_wing(facet_size=0.25), uniform=PAINT, two_sided=["wing*"])
    return Model(craft, reference_point_m=np.array([0.1, -0.05, 0.2]))


@pytest.fixture(scope="module")
def run(model):
    times = np.arange(0.0, 5700.0, 300.0)
    path = propagate(Elements.circular(450.0, 51.6, 20.0), EPOCH, times, "kepler")
    settings = ReflectionSettings("none")
    result = fly(
        model,
        path,
        AttitudeLaw.parse("lvlh:5,-10,3"),
        OrbitLoads(
            SrpSetup(reflections=settings),
            GasOptions(
                reflections=settings,
                gas_sampling=GasSampling(sky_rays=36, core_rays=4096, chain_molecules=4096),
            ),
        ),
    )
    return path, result


def test_each_sunlit_step_is_srp_at_its_body_sun_scaled_by_the_distance(model, run):
    path, result = run
    s = result.series
    sun = sun_position(EPOCH, path.time_s) - path.position_m
    lit = np.flatnonzero(s["solar_fraction"] == 1.0)
    dark = np.flatnonzero(s["solar_fraction"] == 0.0)
    assert lit.size > 5 and dark.size > 3
    for i in lit:
        flux = 1361.0 * (AU_M / np.linalg.norm(sun[i])) ** 2
        alone = srp(model, s["sun_body"][i], flux_W_m2=flux, reflections="none")
        assert np.allclose(s["srp_force_body_N"][i], alone.force_N, rtol=1e-12, atol=0)
        assert np.allclose(s["srp_torque_body_Nm"][i], alone.torque_Nm, rtol=1e-12, atol=0)
    assert np.all(s["srp_force_body_N"][dark] == 0.0)
    # the body-frame Sun is the inertial one turned by the attitude
    turned = np.einsum("nij,nj->ni", result.body_to_eci, s["sun_body"])
    assert np.abs(turned - sun / np.linalg.norm(sun, axis=1)[:, None]).max() < 1e-14


def test_each_step_is_drag_in_the_air_turning_with_the_earth_at_its_place(model, run):
    path, result = run
    s = result.series
    place = geodetic(path)
    omega = 7.292115e-5
    for i in (0, 7):
        r, v = path.position_m[i], path.velocity_m_s[i]
        v_rel = v - np.cross([0.0, 0.0, omega], r)
        body = result.body_to_eci[i].T @ v_rel
        air = nrlmsis(*place[i], EPOCH.at(path.time_s[i]))
        alone = drag(
            model,
            body,
            air,
            reflections="none",
            gas_sampling=GasSampling(sky_rays=36, core_rays=4096, chain_molecules=4096),
        )
        assert np.allclose(s["drag_force_body_N"][i], alone.force_N, rtol=1e-12, atol=0)
        assert s["density_kg_m3"][i] == air.density_kg_m3
    assert 150 < place[:, 0].min() and place[:, 0].max() < 480  # geodetic height of a 450 km circle


def test_totals_frames_and_the_angular_impulse_are_the_trapezoidal_integral_of_the_torque(run):
    _, result = run
    s = result.series
    t = s["time_s"]
    assert np.array_equal(s["force_body_N"], s["srp_force_body_N"] + s["drag_force_body_N"])
    assert np.allclose(s["force_eci_N"], np.einsum("nij,nj->ni", result.body_to_eci, s["force_body_N"]))
    torque_eci = np.einsum("nij,nj->ni", result.body_to_eci, s["torque_body_Nm"])
    for k in (1, 5, len(t) - 1):
        assert np.allclose(
            s["angular_impulse_body_Nms"][k],
            np.trapezoid(s["torque_body_Nm"][: k + 1], t[: k + 1], axis=0),
            rtol=1e-12,
            atol=0,
        )
        assert np.allclose(
            s["angular_impulse_eci_Nms"][k],
            np.trapezoid(torque_eci[: k + 1], t[: k + 1], axis=0),
            rtol=1e-12,
            atol=0,
        )
    assert np.all(s["angular_impulse_body_Nms"][0] == 0)


def test_the_json_has_every_series_by_name_one_row_per_step_and_a_summary(run):
    _, result = run
    document = json.loads(json.dumps(result.to_json(mass_kg=100.0)))
    n = len(result.series["time_s"])
    for name in SERIES:
        assert len(document[name]) == n
    summary = document["summary"]
    assert summary["ballistic_coefficient_m2_kg"] == pytest.approx(summary["drag_area_m2"] / 100.0)
    # C_D A recovers the mean drag along the flow from the dynamic pressure
    s = result.series
    v_hat = s["v_rel_body_m_s"] / np.linalg.norm(s["v_rel_body_m_s"], axis=1)[:, None]
    along = -np.einsum("ij,ij->i", s["drag_force_body_N"], v_hat)
    assert along.sum() == pytest.approx(summary["drag_area_m2"] * s["dynamic_pressure_Pa"].sum())
    assert 0.2 < summary["sunlit_fraction"] < 1.0


def test_the_summary_lists_each_eclipse_from_its_first_shadowed_step_to_the_first_lit_one(run):
    _, result = run
    t, fraction = result.series["time_s"], result.series["solar_fraction"]
    eclipses = result.summary()["eclipses_s"]
    assert len(eclipses) == 1
    start, end = eclipses[0]
    inside = (t >= start) & (t < end)
    assert np.all(fraction[inside] < 1) and np.all(fraction[~inside] == 1)


def test_an_interrupted_run_resumes_from_its_checkpoint_and_gives_the_same_series(model, tmp_path):
    """The steps run as sweep chunks: a run stopped after its first chunk keeps it, and the resumed
    run takes it up (said on the notice) and ends with the series of an uninterrupted run."""
    times = np.arange(0.0, 1800.0, 300.0)
    path = propagate(Elements.circular(450.0, 51.6, 20.0), EPOCH, times, "kepler")
    loads = OrbitLoads(SrpSetup(reflections="none"))
    law = AttitudeLaw.parse("nadir")
    whole = fly(model, path, law, loads)
    checkpoint = tmp_path / "run.checkpoint"
    resumed, notices = stopped_then_resumed(lambda run: fly(model, path, law, loads, run=run), checkpoint, 2)
    assert notices == ["checkpoint: kept 1 chunks, recomputing 2"]
    for name in ("srp_force_body_N", "torque_body_Nm", "angular_impulse_eci_Nms"):
        assert np.array_equal(resumed.series[name], whole.series[name])
    assert not checkpoint.exists()
