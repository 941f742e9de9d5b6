"""Sweeps over hinge angles: each listed angle a pose and a table dimension, every entry the
single-attitude call at that pose, resumable like any sweep; formats and plots that hold one pose
refuse several."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from helpers.runs import stopped_then_resumed
from helpers.shapes import hinged_box_wing
from sunwind.forces import explicit, load, srp, sweep
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.tables.jobs import DragSetup, SrpSetup
from sunwind.geometry.directions import azel_to_vector

HINGE = "hinge_deg[wing_*]"
ANGLES = [0.0, 30.0, 75.0]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    return hinged_box_wing(tmp_path_factory.mktemp("hinge-sweeps"))


@pytest.fixture(scope="module")
def model(files):
    return load(*files)


def test_each_listed_angle_is_a_pose_and_each_entry_the_call_at_that_pose(model):
    """The wings (which track the Sun in the file) are held at each listed angle, for SRP and drag."""
    air = explicit(3e-12, 900.0, "O:1")
    drag_setup = DragSetup(
        speed_m_s=7600.0, atmosphere=air, reflections="none", gas_sampling=GasSampling(sky_rays=36)
    )
    table = sweep(
        model,
        srp=SrpSetup(reflections="none"),
        drag=drag_setup,
        step_deg=45.0,
        hinge_angles={"wing_*": ANGLES},
    )
    assert table["srp_force_N"].dims[0] == HINGE and list(table[HINGE].values) == ANGLES
    assert table["sun_vector"].dims == ("sun_azimuth", "sun_elevation", "component")
    for angle in ANGLES:
        held = model.held({"wing_*": angle})
        assert held.hinges[0].law == "fixed"
        for az, el in ((45.0, 0.0), (-135.0, 45.0)):
            u = azel_to_vector(az, el)
            light = srp(held, u, reflections="none").force_N
            entry = table["srp_force_N"].sel({HINGE: angle, "sun_azimuth": az, "sun_elevation": el})
            assert np.allclose(entry, light, rtol=1e-12, atol=0)
        gas = drag_setup.evaluate(held, azel_to_vector(45.0, 0.0)[None])["force_N"][0]
        entry = table["drag_force_N"].sel({HINGE: angle, "flow_azimuth": 45.0, "flow_elevation": 0.0})
        assert np.allclose(entry, gas, rtol=1e-12, atol=0)
    turned = table["srp_force_N"].sel({"sun_azimuth": -135.0, "sun_elevation": 45.0})
    assert np.ptp(turned.values[:, 0]) > 0.1 * np.abs(turned.values).max()  # the angle matters


def test_a_sweep_over_angles_resumes_from_its_checkpoint(model, tmp_path):
    setup = SrpSetup(reflections="none")
    resumed, notices = stopped_then_resumed(
        lambda run: sweep(model, srp=setup, step_deg=45.0, hinge_angles={"wing_*": ANGLES}, run=run),
        tmp_path / "t.checkpoint",
        26,
    )
    whole = sweep(model, srp=setup, step_deg=45.0, hinge_angles={"wing_*": ANGLES})
    assert notices and notices[0].startswith("checkpoint: kept 1 chunks")
    xr.testing.assert_identical(resumed, whole)


def test_the_command_line_tabulates_a_list_and_refuses_it_where_one_pose_is_held(run_cli, files, tmp_path):
    mesh, materials = (str(p) for p in files)
    common = [mesh, "-m", materials, "--srp", "--step", "45", "--reflections", "none"]
    code, _, err = run_cli("sweep", *common, "--articulate", "wing_*=0,30", "-o", tmp_path / "t.nc")
    assert code == 0, err
    table = xr.open_dataset(tmp_path / "t.nc")
    assert (
        list(table[HINGE].values) == [0.0, 30.0]
        and table.attrs["hinge_angles_deg"] == '{"wing_*": [0.0, 30.0]}'
    )
    code, _, err = run_cli("sweep", *common, "--articulate", "wing_*=0,30", "-o", tmp_path / "t.xml")
    assert code == 1 and "--format basilisk takes one pose" in err and not (tmp_path / "t.xml").exists()
    code, _, err = run_cli("sweep", *common, "--articulate", "wing_*=30", "-o", tmp_path / "one.xml")
    assert code == 0, err
    code, _, err = run_cli("plot", tmp_path / "t.nc", "--no-view")
    assert code == 1 and "sunwind plot takes one pose" in err
    code, _, err = run_cli(
        "srp", mesh, "-m", materials, "--sun", "1", "0", "0", "--articulate", "wing_*=0,30"
    )
    assert code == 1 and "a list is a table dimension of sunwind sweep" in err
