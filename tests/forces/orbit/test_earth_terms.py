"""The Earth's albedo, infrared and thermal recoil along an orbit: each step is ``planet_radiation`` and
the equilibrium at that step's place, computed apart here; the closed form of an absorbing sphere; the
outputs; one-line errors."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest
import xarray as xr

from helpers.planet import BLACK, R_EARTH, infrared_on_black_sphere, materials_toml, write_sphere
from helpers.runs import stopped_then_resumed
from sunwind.forces import Model
from sunwind.forces.earth import CapSampling, Place, planet_radiation
from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, fly, propagate
from sunwind.forces.orbit.earth_terms import EarthTerms
from sunwind.forces.orbit.sun import AU_M, sun_position
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.tables.jobs import SrpSetup
from sunwind.forces.thermal import ThermalModel
from sunwind.geometry.materials import Material
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.primitives import box_wing

EPOCH = Epoch.of("2024-06-01T00:00:00Z")
PAINT = Material("paint", 0.5, 0.4, 0.0, emissivity=0.85)


@pytest.fixture(scope="module")
def model():
    craft = build_spacecraft(box_wing(facet_size=0.25), uniform=PAINT, two_sided=["wing*"])
    return Model(craft, reference_point_m=np.array([0.1, -0.05, 0.2]))


@pytest.fixture(scope="module")
def run(model):
    times = np.arange(0.0, 5700.0, 600.0)
    path = propagate(Elements.circular(500.0, 51.6, 20.0), EPOCH, times, "kepler")
    surface = SrpSetup(reflections="none")
    earth = EarthTerms(surface, cell_deg=15.0, thermal=True)
    return path, fly(model, path, AttitudeLaw.parse("lvlh:5,-10,3"), OrbitLoads(surface, earth=earth))


def test_each_step_is_the_planet_radiation_and_equilibrium_at_its_place(model, run):
    path, result = run
    s = result.series
    sun = sun_position(EPOCH, path.time_s) - path.position_m
    assert 0 < s["solar_fraction"].sum() < len(path.time_s)  # sunlit and eclipsed steps
    nodes = ThermalModel(model.craft)
    for i in range(len(path.time_s)):
        to_body = result.body_to_eci[i].T
        r = path.position_m[i]
        place = Place(
            to_body @ -r,
            (np.linalg.norm(r) - R_EARTH) / 1e3,
            to_body @ sun[i],
            to_body @ [0.0, 0.0, 1.0],
            float(s["solar_fraction"][i]),
        )
        light = PlanetLight.of(planet("earth"), 1361.0 * (AU_M / np.linalg.norm(sun[i])) ** 2)
        alone = planet_radiation(model, place, light, reflections="none", cap=CapSampling(15.0))
        for band in ("albedo", "infrared"):
            loads = getattr(alone, band)
            assert np.allclose(s[f"{band}_force_body_N"][i], loads.force_N, rtol=1e-10, atol=0)
            assert np.allclose(s[f"{band}_torque_body_Nm"][i], loads.torque_Nm, rtol=1e-10, atol=0)
        absorbed = alone.absorbed_side_W()
        for source, values in absorbed.items():
            assert np.allclose(s[f"part_{source}_W"][i], alone.per_part(values), rtol=1e-10, atol=1e-12)
        state = nodes.equilibrium(sum(absorbed.values()), model.reference()[0])
        assert np.allclose(s["thermal_force_body_N"][i], state.force_N, rtol=1e-9, atol=0)
        assert np.allclose(s["part_temperature_K"][i], alone.part_temperatures(state.temperature_K))
    terms = ("srp", "albedo", "infrared", "thermal")
    assert result.terms == terms
    total = sum(s[f"{term}_force_body_N"] for term in terms)
    assert np.allclose(s["force_body_N"], total, rtol=1e-14, atol=0)
    # the Earth's light is there in eclipse too; the albedo only while the spacecraft sees the day side
    dark = s["solar_fraction"] == 0
    assert np.all(np.linalg.norm(s["infrared_force_body_N"][dark], axis=1) > 0)
    assert np.all(s["part_solar_W"][dark] == 0)


def test_summary_and_files_carry_the_parts(run, tmp_path):
    _, result = run
    summary = result.summary()
    parts = summary["parts"]
    assert set(parts) == set(result.part_names)
    for values in parts.values():
        assert values["min_temperature_K"] <= values["mean_temperature_K"] <= values["max_temperature_K"]
    data = result.to_dataset()
    assert data["part_temperature_K"].dims == ("time", "part")
    assert list(data["part"].values) == list(result.part_names)
    data.to_netcdf(tmp_path / "run.nc")
    assert xr.open_dataset(tmp_path / "run.nc")["albedo_force_body_N"].attrs["units"] == "N"
    result.write_csv(tmp_path / "run.csv")
    with (tmp_path / "run.csv").open() as handle:
        header = next(csv.reader(line for line in handle if not line.startswith("#")))
    assert f"part_temperature_K[{result.part_names[0]}]" in header and "thermal_force_body_N_z" in header


@pytest.fixture(scope="module")
def sphere(tmp_path_factory):
    folder = tmp_path_factory.mktemp("orbit_earth")
    (folder / "area").write_text(repr(write_sphere(folder / "sphere.obj", 24)))
    (folder / "black.toml").write_text(BLACK)
    (folder / "iso.toml").write_text(BLACK + '[thermal."*"]\nisothermal = true\n')
    (folder / "bare.toml").write_text(materials_toml("black", 0.0, 0.0, None))
    return folder


def _orbit(folder, *extra):
    return [
        "orbit", folder / "sphere.obj", "--altitude", "500", "--inclination", "51.6", "--epoch",
        "2024-03-20T00:00:00Z", "--duration", "1200", "--step", "600", "--srp", *extra,
    ]  # fmt: skip


def test_an_absorbing_sphere_has_the_closed_form_infrared_and_an_isothermal_one_no_recoil(run_cli, sphere):
    code, out, err = run_cli(
        *_orbit(sphere, "-m", sphere / "iso.toml", "--earth-radiation", "--thermal", "--earth-ir", "240"),
        "--json",
    )
    assert code == 0, err
    doc = json.loads(out)
    # nadir attitude: the Earth along body +z; the closed form away from it
    expected = -infrared_on_black_sphere(float((sphere / "area").read_text()), 240.0, 500.0)
    infrared = np.array(doc["infrared_force_body_N"])
    assert infrared[:, 2] == pytest.approx(expected, rel=1e-4)  # to the faceting
    assert np.abs(infrared[:, :2]).max() < 1e-12 * abs(expected)
    thermal = np.array(doc["thermal_force_body_N"])
    assert np.abs(thermal).max() < 1e-12 * abs(expected)  # one temperature: no net recoil
    assert "parts" in doc["summary"] and doc["part_names"]


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (("--thermal",), "--thermal needs --earth-radiation"),
        (("--albedo", "0.3"), "--albedo needs --earth-radiation"),
        (("--earth-radiation", "-m", "bare.toml"), "emissivity"),
        (("--earth-radiation", "--albedo", "1.5", "-m", "black.toml"), "albedo"),
        (("--earth-radiation", "--earth-step", "0", "-m", "black.toml"), "--earth-step 0 is not in"),
    ],
)
def test_bad_earth_options_get_one_line(run_cli, sphere, extra, words):
    extra = tuple(sphere / e if e.endswith(".toml") else e for e in extra)
    code, _, err = run_cli(*_orbit(sphere, *extra))
    assert code != 0
    lines = [line for line in err.splitlines() if line.startswith("sunwind: error:")]
    assert len(lines) == 1 and words in lines[0], err
    assert "Traceback" not in err


def test_a_resumed_run_keeps_the_per_part_records_of_its_checkpoint(model, run, tmp_path):
    """Per-part records (one column per part) go through the checkpoint and come back the same bits."""
    path, whole = run
    surface = SrpSetup(reflections="none")
    loads = OrbitLoads(surface, earth=EarthTerms(surface, cell_deg=15.0, thermal=True))
    law = AttitudeLaw.parse("lvlh:5,-10,3")
    resumed, notices = stopped_then_resumed(
        lambda run: fly(model, path, law, loads, run=run), tmp_path / "run.checkpoint", 4
    )
    assert notices == ["checkpoint: kept 1 chunks, recomputing 2"]
    for name in ("part_temperature_K", "part_albedo_W", "thermal_torque_body_Nm", "force_body_N"):
        assert np.array_equal(resumed.series[name], whole.series[name])
