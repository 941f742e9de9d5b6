"""Orbit runs with sensitivities: each step's derivatives are those of its terms' calls (SRP at the
eclipsed flux, i.e. times the solar fraction), summed; in every output; resumable."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

from helpers.runs import stopped_then_resumed
from sunwind.forces import drag, load, planet_radiation, srp
from sunwind.forces.earth import CapSampling, Place
from sunwind.forces.gas import explicit
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, fly, propagate
from sunwind.forces.orbit.earth_terms import EarthTerms
from sunwind.forces.orbit.flight import step_inputs
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.sensitivity import COEFFICIENTS
from sunwind.forces.tables.jobs import GasOptions, SrpSetup
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.sampling import ShadowSampling

EPOCH = Epoch.of("2024-06-01T00:00:00Z")
SAMPLING = ShadowSampling(samples=4)
AIR = explicit(3e-12, 900.0, "O:0.8,N2:0.2")
MATERIALS = """
[materials.foil]
reflectivity = 0.6
specular_fraction = 0.8
emissivity = 0.5
[materials.cell]
reflectivity = 0.2
specular_fraction = 0.3
transmissivity = 0.1
emissivity = 0.85
[parts]
bus = "foil"
"wing_*" = { front = "cell", back = "foil" }
"""
LAW = AttitudeLaw.parse("lvlh:5,-10,3")


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    from sunwind.geometry.io.obj import write_obj
    from sunwind.meshes.primitives import box_wing

    folder = tmp_path_factory.mktemp("orbit-sensitivities")
    write_obj(box_wing(facet_size=0.5), folder / "craft.obj")
    (folder / "craft.toml").write_text(MATERIALS)
    return folder / "craft.obj", folder / "craft.toml"


@pytest.fixture(scope="module")
def model(files):
    return load(*files, threads=1)


@pytest.fixture(scope="module")
def path():
    return propagate(Elements.circular(450.0, 51.6, 20.0), EPOCH, np.arange(0.0, 5700.0, 475.0), "kepler")


def _srp_only():
    return OrbitLoads(SrpSetup(reflections="none", sampling=SAMPLING), sensitivities=True)


def test_each_step_holds_the_srp_derivatives_times_its_solar_fraction(model, path):
    loads = _srp_only()
    result = fly(model, path, LAW, loads)
    steps = step_inputs(path, LAW, loads)
    s = result.series
    assert s["sensitivity_force_N"].shape == (len(path.time_s), 2, len(COEFFICIENTS), 3)
    fraction = s["solar_fraction"]
    assert (fraction == 0).sum() >= 2 and (fraction == 1).sum() >= 2
    options = {"reflections": "none", "sampling": SAMPLING, "sensitivities": True}
    for i, sun in enumerate(s["sun_body"]):
        if fraction[i] == 0:  # no light, no derivative
            assert not s["sensitivity_force_N"][i].any() and not s["sensitivity_torque_Nm"][i].any()
            continue
        at_flux = srp(model, sun, flux_W_m2=s["srp_flux_W_m2"][i], **options).sensitivities
        np.testing.assert_array_equal(s["sensitivity_force_N"][i], at_flux.force_N)
        np.testing.assert_array_equal(s["sensitivity_torque_Nm"][i], at_flux.torque_Nm)
        whole_sun = srp(model, sun, flux_W_m2=steps.sunlight_W_m2[i], **options).sensitivities
        scaled = whole_sun.scaled(fraction[i])
        np.testing.assert_allclose(s["sensitivity_force_N"][i], scaled.force_N, rtol=1e-12, atol=1e-24)
        np.testing.assert_allclose(s["sensitivity_torque_Nm"][i], scaled.torque_Nm, rtol=1e-12, atol=1e-24)


def test_drag_and_the_earth_add_their_derivatives_to_the_sum(model, path):
    times = path.time_s[:4]
    short = propagate(Elements.circular(450.0, 51.6, 20.0), EPOCH, times, "kepler")
    light = SrpSetup(reflections="none", sampling=SAMPLING)
    gas = GasOptions(reflections="none", sampling=SAMPLING, gas_sampling=GasSampling(sky_rays=36))
    earth = EarthTerms(light, cell_deg=30.0)
    loads = OrbitLoads(light, gas, AIR, 0.0, earth, sensitivities=True)
    result = fly(model, short, LAW, loads)
    steps = step_inputs(short, LAW, loads)
    for i in range(len(times)):
        total = np.zeros((2, len(COEFFICIENTS), 3))
        if steps.flux_W_m2[i] > 0:
            total += srp(
                model, steps.sun_body[i], flux_W_m2=steps.flux_W_m2[i], **light.options(), sensitivities=True
            ).sensitivities.force_N
        total += drag(
            model, steps.velocity_body_m_s[i], AIR, **gas.options(), sensitivities=True
        ).sensitivities.force_N
        place = Place(
            steps.nadir_body[i],
            float(steps.height_km[i]),
            steps.sun_body[i],
            steps.pole_body[i],
            float(steps.solar_fraction[i]),
        )
        radiation = PlanetLight.of(planet("earth"), float(steps.sunlight_W_m2[i]))
        cap = CapSampling(30.0, "visibility")
        earthly = planet_radiation(model, place, radiation, cap=cap, **light.options(), sensitivities=True)
        total += earthly.sensitivities.force_N
        np.testing.assert_array_equal(result.series["sensitivity_force_N"][i], total)
    assert result.attributes["settings"]["sensitivities"] == ["foil", "cell"]


def test_earth_terms_with_reflections_followed_take_the_cells(model, path):
    """With sensitivities and specular reflections the Earth terms' automatic method is the cells (the
    visibility keeps no derivatives of its chains): each step's derivatives are planet_radiation's by the
    cells, plus the SRP's."""
    times = path.time_s[:2]
    short = propagate(Elements.circular(450.0, 51.6, 20.0), EPOCH, times, "kepler")
    light = SrpSetup(reflections="specular", sampling=SAMPLING)
    loads = OrbitLoads(light, None, AIR, 0.0, EarthTerms(light, cell_deg=30.0), sensitivities=True)
    result = fly(model, short, LAW, loads)
    steps = step_inputs(short, LAW, loads)
    for i in range(len(times)):
        total = np.zeros((2, len(COEFFICIENTS), 3))
        if steps.flux_W_m2[i] > 0:
            total += srp(
                model, steps.sun_body[i], flux_W_m2=steps.flux_W_m2[i], **light.options(), sensitivities=True
            ).sensitivities.force_N
        place = Place(
            steps.nadir_body[i],
            float(steps.height_km[i]),
            steps.sun_body[i],
            steps.pole_body[i],
            float(steps.solar_fraction[i]),
        )
        radiation = PlanetLight.of(planet("earth"), float(steps.sunlight_W_m2[i]))
        cap = CapSampling(30.0, "cells")
        earthly = planet_radiation(model, place, radiation, cap=cap, **light.options(), sensitivities=True)
        total += earthly.sensitivities.force_N
        np.testing.assert_allclose(result.series["sensitivity_force_N"][i], total, rtol=1e-12, atol=1e-24)


def test_the_outputs_hold_the_derivatives_on_material_and_coefficient(model, path, tmp_path):
    result = fly(model, path, LAW, _srp_only())
    table = result.to_dataset()
    force = table["sensitivity_force_N"]
    assert force.dims == ("time", "material", "coefficient", "component") and force.attrs["units"] == "N"
    assert table["sensitivity_torque_Nm"].attrs["units"] == "N m"
    assert table["material"].values.tolist() == ["foil", "cell"]
    assert table["coefficient"].values.tolist() == list(COEFFICIENTS)
    table.to_netcdf(tmp_path / "o.nc")
    again = xr.load_dataset(tmp_path / "o.nc")
    np.testing.assert_array_equal(again["sensitivity_force_N"].values, result.series["sensitivity_force_N"])
    out = json.loads(json.dumps(result.to_json()))
    assert out["materials"] == ["foil", "cell"] and out["coefficients"] == list(COEFFICIENTS)
    assert np.array_equal(np.array(out["sensitivity_torque_Nm"]), result.series["sensitivity_torque_Nm"])
    result.write_csv(tmp_path / "o.csv")
    lines = [line for line in (tmp_path / "o.csv").read_text().splitlines() if not line.startswith("#")]
    header = lines[0].split(",")
    column = header.index("sensitivity_force_N[cell.transmissivity]_z")
    values = np.array([float(line.split(",")[column]) for line in lines[1:]])
    np.testing.assert_array_equal(values, result.series["sensitivity_force_N"][:, 1, 2, 2])
    plain = fly(model, path, LAW, OrbitLoads(SrpSetup(reflections="none", sampling=SAMPLING)))
    assert "sensitivity_force_N" not in plain.to_dataset() and "materials" not in plain.to_json()
    assert "sensitivities" not in plain.attributes["settings"]


def test_an_interrupted_run_with_sensitivities_resumes_to_the_same_series(model, path, tmp_path):
    loads = _srp_only()
    whole = fly(model, path, LAW, loads)
    checkpoint = tmp_path / "run.checkpoint"
    resumed, notices = stopped_then_resumed(lambda run: fly(model, path, LAW, loads, run=run), checkpoint, 4)
    assert notices and notices[0].startswith("checkpoint: kept 1 chunks")
    xr.testing.assert_identical(resumed.to_dataset(), whole.to_dataset())
    assert not checkpoint.exists()


def test_the_thermal_recoil_and_terms_without_them_are_refused(monkeypatch):
    light = SrpSetup(reflections="none")
    with pytest.raises(InputError, match="thermal recoil"):
        OrbitLoads(light, earth=EarthTerms(light, thermal=True), sensitivities=True)

    def old_drag(model, velocity, atmosphere, **options):  # a drag without the keyword
        raise AssertionError("never called")

    monkeypatch.setattr("sunwind.forces.orbit.steps.drag", old_drag)
    with pytest.raises(InputError, match="sensitivities of drag are not available yet"):
        OrbitLoads(light, GasOptions(), sensitivities=True)
    OrbitLoads(light, GasOptions())  # without them, nothing to refuse


def test_the_command_line_writes_them_and_prints_their_orbit_means(run_cli, files, tmp_path):
    mesh, materials = (str(p) for p in files)
    out = tmp_path / "o.nc"
    args = ["orbit", mesh, "-m", materials, "--altitude", "500", "--inclination", "98", "--epoch"]
    args += ["2024-03-20T00:00:00Z", "--duration", "1200", "--step", "300", "--srp", "--samples", "4"]
    code, stdout, err = run_cli(*args, "--reflections", "none", "--sensitivities", "-o", out)
    assert code == 0, err
    assert "orbit means of the derivatives" in stdout and "foil.reflectivity" in stdout
    assert xr.load_dataset(out)["sensitivity_force_N"].dims == (
        "time",
        "material",
        "coefficient",
        "component",
    )
