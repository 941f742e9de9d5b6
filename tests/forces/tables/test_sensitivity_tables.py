"""Sweeps with sensitivities: every entry the single-attitude call's derivatives bit for bit, on
(..., material, coefficient, component), resumable, refused where they cannot go."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from helpers.runs import stopped_then_resumed
from sunwind.forces import explicit, load, planet_radiation, srp, sweep
from sunwind.forces.drag import drag
from sunwind.forces.earth import CapSampling, Place
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.sensitivity import COEFFICIENTS
from sunwind.forces.tables import EarthSetup, SweepRun, read_attitude_csv
from sunwind.forces.tables.jobs import DragSetup, SrpSetup
from sunwind.forces.tables.sensitivities import sensitivity_keyword
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.sampling import ShadowSampling

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
SAMPLING = ShadowSampling(samples=4)
AIR = explicit(3e-12, 900.0, "O:0.8,N2:0.2")


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """The box-wing written by ``sunwind mesh``, a foil bus and wings of cells on foil."""
    from sunwind.forces.cli.app import main

    folder = tmp_path_factory.mktemp("sensitivity-sweeps")
    main(["mesh", "box_wing", "-o", str(folder / "craft.obj")])
    (folder / "craft.toml").write_text(MATERIALS)
    return folder / "craft.obj", folder / "craft.toml"


@pytest.fixture(scope="module")
def model(files):
    return load(*files)


def _drag_setup(**more):
    return DragSetup(
        speed_m_s=7600.0,
        atmosphere=AIR,
        sampling=SAMPLING,
        reflections="none",
        gas_sampling=GasSampling(sky_rays=36),
        **more,
    )


def _same(table_values, derivatives):
    np.testing.assert_array_equal(table_values["force"], derivatives.force_N)
    np.testing.assert_array_equal(table_values["torque"], derivatives.torque_Nm)


def _entry(table, kind, **where):
    entry = table.sel(where)
    return {what: entry[f"{kind}_sensitivity_{what}_{unit}"].values for what, unit in _UNITS}


_UNITS = (("force", "N"), ("torque", "Nm"))


def test_the_command_line_table_holds_the_srp_derivatives_of_every_attitude(run_cli, files, model, tmp_path):
    mesh, materials = (str(p) for p in files)
    out = tmp_path / "t.nc"
    args = ["sweep", mesh, "-m", materials, "--srp", "--step", "45", "--samples", "4", "--reflections"]
    code, _, err = run_cli(*args, "none", "--sensitivities", "-o", out)
    assert code == 0, err
    table = xr.load_dataset(out)
    force = table["srp_sensitivity_force_N"]
    assert force.dims == ("sun_azimuth", "sun_elevation", "material", "coefficient", "component")
    assert table["material"].values.tolist() == list(model.craft.materials.names) == ["foil", "cell"]
    assert table["coefficient"].values.tolist() == list(COEFFICIENTS)
    assert force.attrs["units"] == "N" and table["srp_sensitivity_torque_Nm"].attrs["units"] == "N m"
    assert "d force / d coefficient" in force.attrs["long_name"]
    for az in table["sun_azimuth"].values:
        for el in table["sun_elevation"].values:
            u = table["sun_vector"].sel(sun_azimuth=az, sun_elevation=el).values
            light = srp(model, u, sampling=SAMPLING, reflections="none", sensitivities=True)
            _same(_entry(table, "srp", sun_azimuth=az, sun_elevation=el), light.sensitivities)
    assert np.abs(force.sel(material="cell", coefficient="transmissivity")).max() > 0


def test_srp_and_drag_lists_and_grids_hold_the_calls_derivatives(model, tmp_path):
    path = tmp_path / "attitudes.csv"
    path.write_text(
        "sun_x,sun_y,sun_z,flow_x,flow_y,flow_z\n0,0,1,1,0,0\n1,1,0.5,-0.2,1,0\n-1,0.3,-0.2,0,0,-1\n"
    )
    attitudes = read_attitude_csv(path)
    light = SrpSetup(sampling=SAMPLING, reflections="plates", sensitivities=True)
    table = sweep(model, srp=light, drag=_drag_setup(sensitivities=True), attitudes=attitudes)
    assert table["drag_sensitivity_force_N"].dims == ("attitude", "material", "coefficient", "component")
    for k in range(len(attitudes)):
        sun, flow = table["sun_vector"].values[k], table["flow_vector"].values[k]
        expected = srp(model, sun, sampling=SAMPLING, reflections="plates", sensitivities=True)
        _same(_entry(table, "srp", attitude=k), expected.sensitivities)
        gas = drag(model, 7600.0 * flow, AIR, **_drag_setup().options(), sensitivities=True)
        _same(_entry(table, "drag", attitude=k), gas.sensitivities)
    accommodation = table["drag_sensitivity_force_N"].sel(coefficient="energy_accommodation")
    assert np.abs(accommodation).max() > 0
    plain = sweep(model, srp=SrpSetup(sampling=SAMPLING, reflections="plates"), attitudes=attitudes)
    assert "srp_sensitivity_force_N" not in plain and "material" not in plain.dims
    xr.testing.assert_identical(plain["srp_force_N"], table["srp_force_N"])  # the loads are the same


def test_the_earth_table_holds_the_albedo_and_infrared_derivatives(model):
    setup = EarthSetup(
        altitude_km=500.0,
        sun_vector=(1.0, 0.0, 0.0),
        cell_deg=30.0,
        sampling=SAMPLING,
        reflections="none",
        sensitivities=True,
    )
    table = sweep(model, earth=setup, step_deg=90.0)
    for az, el in ((0.0, 0.0), (90.0, 0.0), (180.0, 0.0), (0.0, -90.0)):
        u = table["earth_vector"].sel(earth_azimuth=az, earth_elevation=el).values
        place = Place(u, 500.0, np.array([1.0, 0.0, 0.0]), None, setup.solar_fraction(u))
        result = planet_radiation(
            model, place, setup.light(), cap=CapSampling(30.0), **setup.options(), sensitivities=True
        )
        _same(_entry(table, "earth", earth_azimuth=az, earth_elevation=el), result.sensitivities)
    with pytest.raises(InputError, match="thermal recoil"):
        EarthSetup(altitude_km=500.0, sun_vector=(1.0, 0.0, 0.0), thermal=True, sensitivities=True)


def test_an_interrupted_sweep_with_sensitivities_resumes_to_the_same_table(model, tmp_path):
    setups = {
        "srp": SrpSetup(sampling=SAMPLING, reflections="none", sensitivities=True),
        "drag": _drag_setup(sensitivities=True),
    }
    checkpoint = tmp_path / "t.checkpoint"
    resumed, notices = stopped_then_resumed(
        lambda run: sweep(model, **setups, step_deg=45.0, run=run), checkpoint, 5
    )
    whole = sweep(model, **setups, step_deg=45.0)
    assert notices and notices[0].startswith("checkpoint: kept 1 chunks")
    xr.testing.assert_identical(resumed, whole)
    assert not checkpoint.exists()


def test_a_checkpoint_without_sensitivities_is_not_taken_up_with_them(model, tmp_path):
    checkpoint = tmp_path / "t.checkpoint"

    def stop(done: int) -> None:
        if done >= 5:
            raise KeyboardInterrupt

    plain = SrpSetup(sampling=SAMPLING, reflections="none")
    with pytest.raises(KeyboardInterrupt):
        sweep(model, srp=plain, step_deg=45.0, run=SweepRun(chunk=5, checkpoint=checkpoint, progress=stop))
    asked = SrpSetup(sampling=SAMPLING, reflections="none", sensitivities=True)
    with pytest.raises(InputError, match="srp_settings differ"):
        sweep(model, srp=asked, step_deg=45.0, run=SweepRun(chunk=5, checkpoint=checkpoint, resume=True))


def test_a_sweep_over_hinge_angles_keeps_the_derivatives_of_each_pose(files, tmp_path):
    from helpers.shapes import hinged_box_wing

    hinged = load(*hinged_box_wing(tmp_path))
    setup = SrpSetup(sampling=SAMPLING, reflections="none", sensitivities=True)
    table = sweep(hinged, srp=setup, step_deg=90.0, hinge_angles={"wing_*": [0.0, 30.0]})
    force = table["srp_sensitivity_force_N"]
    assert force.dims[0] == "hinge_deg[wing_*]" and force.dims[-3:] == (
        "material",
        "coefficient",
        "component",
    )
    held = hinged.held({"wing_*": 30.0})
    u = table["sun_vector"].sel(sun_azimuth=90.0, sun_elevation=0.0).values
    expected = srp(held, u, sampling=SAMPLING, reflections="none", sensitivities=True).sensitivities
    entry = force.sel({"hinge_deg[wing_*]": 30.0, "sun_azimuth": 90.0, "sun_elevation": 0.0})
    np.testing.assert_array_equal(entry.values, expected.force_N)


def test_a_kind_whose_function_takes_no_sensitivities_is_one_error_line(
    run_cli, files, tmp_path, monkeypatch
):
    def old_drag(model, velocity, atmosphere, **options):  # a drag without the keyword
        raise AssertionError("never called")

    monkeypatch.setattr(DragSetup, "computes", property(lambda self: old_drag))
    mesh, materials = (str(p) for p in files)
    flow = ["--speed", "7600", "--density", "3e-12", "--temperature", "900", "--composition", "O:1"]
    code, _, err = run_cli(
        "sweep",
        mesh,
        "-m",
        materials,
        "--drag",
        *flow,
        "--step",
        "90",
        "--sensitivities",
        "-o",
        tmp_path / "t.nc",
    )
    assert code == 1 and err.startswith("sunwind: error: sensitivities of drag are not available yet")
    assert err.count("\n") == 1
    assert not (tmp_path / "t.nc").exists() and not (tmp_path / "t.nc.checkpoint").exists()
    with pytest.raises(InputError, match="sensitivities of drag"):
        sensitivity_keyword(old_drag, "drag", True)
    assert sensitivity_keyword(old_drag, "drag", False) == {}


def test_formats_without_a_place_for_them_are_refused_before_the_mesh_is_read(run_cli, tmp_path):
    code, _, err = run_cli(
        "sweep", tmp_path / "absent.obj", "--srp", "--sensitivities", "-o", tmp_path / "t.csv"
    )
    assert code == 1 and "--sensitivities go to a netCDF table" in err and err.count("\n") == 1


def test_a_setup_with_sensitivities_is_sized_for_its_model(model):
    setup = SrpSetup(sensitivities=True)
    with pytest.raises(InputError, match="size it for its model"):
        _ = setup.fields
    sized = setup.sized(model)
    assert sized.materials == ("foil", "cell") and sized.fields["sensitivity_force_N"] == 2 * 7 * 3
    assert "sensitivities" not in SrpSetup().describe()  # a run without them is described as before
    assert sized.describe()["materials"] == ["foil", "cell"]
