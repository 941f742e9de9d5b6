"""The earth table: the Earth's albedo and infrared (and thermal recoil) over body-frame directions to the
Earth's centre, at a fixed altitude with the Sun fixed in the body frame. Every node is
``planet_radiation`` at that node's Earth direction and solar fraction; an absorbing sphere gives the
closed form of a uniform emitter; the command line writes it and refuses what cannot hold it in one line."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from helpers.planet import (
    BLACK,
    EARTH_EXITANCE,
    R_EARTH,
    infrared_on_black_sphere,
    materials_toml,
    write_sphere,
)
from helpers.runs import stopped_then_resumed
from helpers.shapes import HINGED_MATERIALS, hinged_box_wing
from sunwind.forces import export
from sunwind.forces.earth import CapSampling, Place, planet_radiation
from sunwind.forces.model import load
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.planet.shadow import sphere_visible
from sunwind.forces.tables import EarthSetup, SrpSetup, TableInterpolator, open_table, sweep
from sunwind.forces.tables.attitudes import read_attitude_csv
from sunwind.forces.thermal import thermal_model
from sunwind.geometry.errors import InputError, SunwindError

AU_M = 149_597_870_700.0
PAINT = materials_toml("paint", 0.4, 0.5, 0.8)
#: The fixed Sun of most tables: 45 deg grids put the Earth in front of it at some nodes.
SUN = (0.6, 0.0, 0.8)


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """Small spheres (12 and 16 bands), their painted, black and emissivity-less materials."""
    folder = tmp_path_factory.mktemp("earth-table")
    write_sphere(folder / "sphere.obj", 12)
    write_sphere(folder / "fine.obj", 16)
    (folder / "paint.toml").write_text(PAINT)
    (folder / "black.toml").write_text(BLACK)
    (folder / "bare.toml").write_text(materials_toml("paint", 0.4, 0.5, None))
    return folder


@pytest.fixture(scope="module")
def painted(folder):
    return load(folder / "sphere.obj", folder / "paint.toml")


@pytest.fixture(scope="module")
def thermal_table(painted):
    setup = EarthSetup(altitude_km=500.0, sun_vector=SUN, reflections="none", thermal=True, cell_deg=15.0)
    return setup, sweep(painted, earth=setup, step_deg=45.0)


def _node_fraction(u, altitude_km, sun):
    position = -(R_EARTH + altitude_km * 1e3) * u
    return float(sphere_visible(position, position + AU_M * np.asarray(sun), R_EARTH, "conical")[0])


# ------------------------------------------------------------------------------------------ the nodes


def test_every_node_is_earth_radiation_at_its_earth_direction(painted, thermal_table):
    """(a) each entry is the direct call with the node's Earth direction, the fixed Sun and the node's
    solar fraction; the thermal recoil the equilibrium of that call's absorbed power."""
    setup, table = thermal_table
    assert table["earth_force_N"].dims == ("earth_azimuth", "earth_elevation", "component")
    light = PlanetLight.of(planet("earth"), 1361.0)
    nodes = thermal_model(painted.craft, "none")
    fractions = set()
    for a in range(table.sizes["earth_azimuth"]):
        for e in range(table.sizes["earth_elevation"]):
            u = table["earth_vector"].values[a, e]
            fraction = _node_fraction(u, 500.0, SUN)
            fractions.add(fraction)
            place = Place(u, 500.0, np.array(setup.sun_vector), None, fraction)
            result = planet_radiation(painted, place, light, reflections="none", cap=CapSampling(15.0))
            state = nodes.equilibrium(sum(result.absorbed_side_W().values()), result.reference_point_m)
            at = {"earth_azimuth": a, "earth_elevation": e}
            expected = {
                "albedo_force_N": result.albedo.force_N,
                "albedo_torque_Nm": result.albedo.torque_Nm,
                "infrared_force_N": result.infrared.force_N,
                "infrared_torque_Nm": result.infrared.torque_Nm,
                "thermal_force_N": state.force_N,
                "thermal_torque_Nm": state.torque_Nm,
                "force_N": result.force_N + state.force_N,
                "torque_Nm": result.torque_Nm + state.torque_Nm,
                "solar_fraction": fraction,
            }
            for name, value in expected.items():
                np.testing.assert_allclose(table[f"earth_{name}"].isel(at).values, value, rtol=1e-12, atol=0)
    assert fractions == {0.0, 1.0}  # the Earth hides the Sun at some nodes: the heat budget sees it
    total = table["earth_force_N"] - table["earth_thermal_force_N"]
    np.testing.assert_allclose(
        total, table["earth_albedo_force_N"] + table["earth_infrared_force_N"], rtol=1e-13, atol=1e-25
    )


def test_the_table_states_its_slice_units_and_settings(thermal_table):
    _, table = thermal_table
    attrs = table.attrs
    assert attrs["earth_altitude_km"] == 500.0
    np.testing.assert_array_equal(attrs["earth_sun_vector"], SUN)
    assert "Sun fixed in the body" in attrs["earth_slice"] and "earth_vector" in attrs["comment"]
    assert attrs["earth_infrared_W_m2"] == pytest.approx(0.7 * 1361 / 4)
    assert attrs["earth_thermal"] == 1 and attrs["earth_reflections"] == "none"
    assert attrs["earth_half_angle_deg"] == pytest.approx(math.degrees(math.asin(R_EARTH / (R_EARTH + 5e5))))
    assert table["earth_force_N"].attrs["units"] == "N"
    assert "thermal recoil" in table["earth_force_N"].attrs["long_name"]
    assert "Sun fixed in the body frame" in table["earth_azimuth"].attrs["long_name"]
    assert table["earth_solar_fraction"].attrs["units"] == "1"


@pytest.mark.slow
def test_an_absorbing_sphere_feels_the_closed_form_of_a_uniform_emitter(folder):
    """(b) a black sphere of radius a under the Earth's uniform infrared M: pi a^2 M sin^2(theta_0)/c
    away from the Earth at every node, sin(theta_0) = R/(R + h), pi a^2 the faceted sphere's area/4."""
    model = load(folder / "fine.obj", folder / "black.toml")
    area = float(model.craft.facet_areas.sum())
    for infrared, exitance in ((None, EARTH_EXITANCE), (200.0, 200.0)):
        setup = EarthSetup(
            altitude_km=400.0, sun_vector=(1, 0, 0), infrared_W_m2=infrared, reflections="none"
        )
        table = sweep(model, earth=setup, step_deg=45.0)
        u = table["earth_vector"].values
        expected = -infrared_on_black_sphere(area, exitance, 400.0) * u
        force = table["earth_infrared_force_N"].values
        scale = np.linalg.norm(expected, axis=-1, keepdims=True)
        assert np.all(np.abs(force - expected) <= 1e-4 * scale)


# ------------------------------------------------------------------------------ runs, poses, formats


def test_a_tracking_hinge_is_turned_to_the_fixed_sun_and_listed_angles_are_poses(tmp_path):
    mesh, materials = hinged_box_wing(tmp_path)
    materials.write_text(
        HINGED_MATERIALS.replace("specular_fraction = 0.4\n", "specular_fraction = 0.4\nemissivity = 0.8\n")
    )
    model = load(mesh, materials)
    setup = EarthSetup(altitude_km=500.0, sun_vector=SUN, reflections="none", cell_deg=30.0)
    table = sweep(model, earth=setup, step_deg=90.0)
    assert table.attrs["earth_tracking_hinges"] == "wing_*"
    u = table["earth_vector"].values[1, 1]
    place = Place(u, 500.0, np.array(SUN), None, _node_fraction(u, 500.0, SUN))
    posed = model.posed(model.angles_at(np.array(SUN)))
    light = PlanetLight.of(planet("earth"), 1361.0)
    direct = planet_radiation(posed, place, light, reflections="none", cap=CapSampling(30.0))
    np.testing.assert_allclose(table["earth_force_N"].values[1, 1], direct.force_N, rtol=1e-12, atol=0)
    poses = sweep(model, earth=setup, step_deg=90.0, hinge_angles={"wing_*": [0.0, 60.0]})
    assert poses["earth_force_N"].dims == (
        "hinge_deg[wing_*]",
        "earth_azimuth",
        "earth_elevation",
        "component",
    )
    held = planet_radiation(
        model.held({"wing_*": 60.0}), place, light, reflections="none", cap=CapSampling(30.0)
    )
    entry = poses["earth_force_N"].sel({"hinge_deg[wing_*]": 60.0}).values[1, 1]
    np.testing.assert_allclose(entry, held.force_N, rtol=1e-12, atol=0)


def test_an_earth_sweep_resumes_from_its_checkpoint(painted, tmp_path):
    setup = EarthSetup(altitude_km=500.0, sun_vector=SUN, reflections="none", thermal=True, cell_deg=30.0)
    resumed, notices = stopped_then_resumed(
        lambda run: sweep(painted, earth=setup, step_deg=45.0, run=run), tmp_path / "t.checkpoint", 13
    )
    assert notices and notices[0].startswith("checkpoint: kept 1 chunks")
    xr.testing.assert_identical(resumed, sweep(painted, earth=setup, step_deg=45.0))


def test_csv_interpolation_and_plots_take_the_earth_table_spad_leaves_it_out(
    thermal_table, painted, tmp_path
):
    from sunwind.forces.tables.plots import plot_table

    _, table = thermal_table
    assert [p.name for p in export.write(table, tmp_path / "t.csv")] == ["t.csv"]
    lines = (tmp_path / "t.csv").read_text().splitlines()
    header = next(line for line in lines if not line.startswith("#"))
    assert header.startswith("earth_azimuth_deg,earth_elevation_deg,earth_force_N_x[N]")
    at = table["earth_vector"].values[3, 2]
    interpolated = TableInterpolator(table).values(["earth_force_N"], at)
    np.testing.assert_allclose(interpolated, table["earth_force_N"].values[3, 2], rtol=1e-12, atol=1e-25)
    assert [p.name for p in plot_table(table, tmp_path / "maps", "t")] == [
        "t.earth_force_N.png",
        "t.earth_torque_Nm.png",
    ]
    with pytest.raises(InputError, match="format spad holds srp and drag only, not earth"):
        export.write(table, tmp_path / "t.spo")
    cheap = EarthSetup(altitude_km=500.0, sun_vector=SUN, reflections="none", cell_deg=45.0)
    both = sweep(painted, srp=SrpSetup(reflections="none"), earth=cheap, step_deg=90.0)
    with pytest.warns(UserWarning, match="spad holds srp and drag only: earth is not written"):
        assert [p.name for p in export.write(both, tmp_path / "b.spo")] == ["b.spo"]


def test_library_refusals(painted, folder, tmp_path):
    setup = EarthSetup(altitude_km=500.0, sun_vector=SUN, reflections="none")
    path = tmp_path / "a.csv"
    path.write_text("sun_x,sun_y,sun_z\n1,0,0\n")
    with pytest.raises(InputError, match="an attitude list has no Earth direction"):
        sweep(painted, earth=setup, attitudes=read_attitude_csv(path))
    with pytest.raises(SunwindError, match="has no emissivity"):
        sweep(load(folder / "sphere.obj", folder / "bare.toml"), earth=setup, step_deg=90.0)
    for bad, match in (
        ({"altitude_km": 0.0}, "altitude_km 0.0 is not in"),
        ({"sun_vector": (0, 0, 0)}, "sun_vector .* has zero length"),
        ({"cell_deg": 95.0}, r"cell_deg 95.0 is not in \(0, 90\]"),
        ({"albedo": 1.5}, "albedo 1.5 is outside"),
    ):
        with pytest.raises(InputError, match=match):
            EarthSetup(**({"altitude_km": 500.0, "sun_vector": SUN} | bad))


# ---------------------------------------------------------------------------------- the command line


def _sweep(folder, *extra, materials="paint.toml"):
    return ["sweep", folder / "sphere.obj", "-m", folder / materials, "--reflections", "none", *extra]


EARTH = ("--earth-radiation", "--earth-altitude", "500", "--earth-sun", "0.6", "0", "0.8")


def test_the_command_line_writes_the_earth_table_alone_or_beside_srp(run_cli, folder, painted, tmp_path):
    """(c) --earth-radiation alone tabulates the Earth only; with --srp both; the netCDF holds
    earth_force_N over (earth_azimuth, earth_elevation, component), each entry the library's."""
    out = tmp_path / "e.nc"
    code, text, err = run_cli(
        *_sweep(folder, *EARTH, "--earth-step", "15", "--thermal", "--step", "45", "-o", out)
    )
    assert code == 0, err
    assert "26 attitudes (earth)" in text
    table = open_table(out)
    assert table["earth_force_N"].dims == ("earth_azimuth", "earth_elevation", "component")
    assert not [name for name in table.data_vars if not str(name).startswith("earth_")]
    setup = EarthSetup(altitude_km=500.0, sun_vector=SUN, reflections="none", thermal=True, cell_deg=15.0)
    library = sweep(painted, earth=setup, step_deg=45.0)
    for name in ("earth_force_N", "earth_thermal_torque_Nm", "earth_solar_fraction"):
        np.testing.assert_array_equal(table[name].values, library[name].values)
    code, text, err = run_cli(*_sweep(folder, "--srp", *EARTH, "--step", "90", "-o", tmp_path / "b.nc"))
    assert code == 0, err
    assert {"srp_force_N", "earth_force_N"} <= set(open_table(tmp_path / "b.nc").data_vars)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (EARTH[:3], "--earth-radiation in a sweep needs --earth-sun X Y Z"),
        (("--earth-radiation", "--earth-sun", "1", "0", "0"), "needs --earth-altitude H_KM"),
        (("--earth-altitude", "500"), "--earth-altitude needs --earth-radiation"),
        (("--thermal",), "--thermal needs --earth-radiation"),
        ((*EARTH, "--attitudes", "LIST"), "--attitudes has no Earth direction"),
        ((*EARTH, "-o", "OUT:t.spo"), "--format spad holds srp and drag only, not earth"),
        ((*EARTH, "-o", "OUT:t.xml"), "--format basilisk holds srp only, not earth"),
        ((*EARTH, "--format", "tudat", "-o", "OUT:aero"), "--format tudat holds drag only, not earth"),
        ((*EARTH, "--albedo-model", "knocke"), "--albedo-model knocke needs a date and the Earth's pole"),
        ((*EARTH, "--earth-step", "0"), "--earth-step 0 is not in (0, 90]"),
        (
            ("--earth-radiation", "--earth-altitude", "-3", "--earth-sun", "1", "0", "0"),
            "--earth-altitude -3.0",
        ),
        (("--earth-radiation", "--earth-altitude", "500", "--earth-sun", "0", "0", "0"), "--earth-sun"),
        ((*EARTH, "--albedo", "2"), "--albedo 2.0 is outside [0, 1]"),
        ((*EARTH, "--materials", "bare.toml"), "material 'paint' has no emissivity"),
    ],
)
def test_bad_earth_sweeps_are_one_line(run_cli, folder, tmp_path, extra, message):
    listed = tmp_path / "a.csv"
    listed.write_text("sun_x,sun_y,sun_z\n1,0,0\n")
    extra = [
        str(listed) if e == "LIST" else str(tmp_path / e[4:]) if e.startswith("OUT:") else e for e in extra
    ]
    if "--materials" in extra:
        extra[-1] = str(folder / extra[-1])
    if "-o" not in extra:
        extra += ["-o", str(tmp_path / "t.nc")]
    if "--attitudes" not in extra:
        extra += ["--step", "90"]
    code, out, err = run_cli(*_sweep(folder, *extra))
    assert code == 1 and out == "", err
    assert err.startswith("sunwind: error:") and message in err and err.count("\n") == 1, err
    assert not (tmp_path / "t.nc").exists()
