"""``sunwind orbit`` from the command line: the JSON, netCDF and CSV carry the same series by the
issue's names, a run resumes from its checkpoint, and bad orbits get one line."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

from sunwind.forces.orbit import SERIES

EPOCH = ["--epoch", "2024-06-01T00:00:00Z"]
ORBIT = ["--altitude", "500", "--inclination", "51.6", *EPOCH, "--duration", "600", "--step", "120"]
AIR = ["--density", "3e-12", "--temperature", "900", "--composition", "O:0.8,N2:0.2"]


@pytest.fixture(scope="module")
def craft(tmp_path_factory):
    """A coarse box-wing with one uniform material."""
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import box_wing

    path = tmp_path_factory.mktemp("orbit-cli") / "box_wing.obj"
    save_mesh(box_wing(facet_size=0.25), path)
    return [str(path), "--reflectivity", "0.5", "--specular-fraction", "0.4", "--two-sided", "wing*"]


def test_json_netcdf_and_csv_hold_the_same_series(run_cli, craft, tmp_path):
    args = ["orbit", *craft, *ORBIT, *AIR, "--reflections", "none", "--mass", "80", "--sky-rays", "36"]
    code, out, err = run_cli(*args, "--json")
    assert code == 0, err
    assert "notice: with drag" in err
    document = json.loads(out)
    assert set(SERIES) <= set(document)
    assert len(document["time_s"]) == 6 and document["angular_impulse_eci_Nms"][0] == [0.0, 0.0, 0.0]
    assert document["summary"]["mass_kg"] == 80
    code, out, err = run_cli(*args, "-o", tmp_path / "run.nc", "--plot", tmp_path / "run.png")
    assert code == 0, err
    assert "C_D A / m" in out and (tmp_path / "run.png").stat().st_size > 10_000
    table = xr.open_dataset(tmp_path / "run.nc")
    for name in SERIES:
        assert np.allclose(table[name].values, np.array(document[name]), rtol=1e-12, atol=0)
    assert table["torque_body_Nm"].attrs["units"] == "N m"
    code, _, err = run_cli(*args, "-o", tmp_path / "run.csv")
    assert code == 0, err
    lines = (tmp_path / "run.csv").read_text().splitlines()
    header = next(line for line in lines if not line.startswith("#")).split(",")  # after the provenance
    assert header[:4] == ["time_s", "position_eci_m_x", "position_eci_m_y", "position_eci_m_z"]


def test_a_geo_orbit_leaves_drag_out_and_says_so(run_cli, craft):
    args = ["orbit", *craft, "--elements", "42164", "0", "0", "0", "0", "0", *EPOCH, "--step", "21600"]
    code, out, err = run_cli(*args, "--json")
    assert code == 0, err
    assert "without drag" in err
    document = json.loads(out)
    assert document["time_s"] == [0.0, 21600.0, 43200.0, 64800.0]  # steps of 6 h within one 86164 s period
    assert np.allclose(document["drag_force_body_N"], 0.0)


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        ([*EPOCH], ["give an orbit"]),
        (["--altitude", "500", *EPOCH], ["--altitude and --inclination"]),
        (["--altitude", "500", "--inclination", "10", "--tle", "x.tle", *EPOCH], ["give one orbit"]),
        (["--elements", "6000", "0", "0", "0", "0", "0", *EPOCH], ["inside the Earth"]),
        (["--altitude", "500", "--inclination", "10"], ["give --epoch"]),
        ([*ORBIT, "--attitude", "spin"], ["attitude law 'spin'"]),
        ([*ORBIT, "--step", "0"], ["--step 0 s"]),
        ([*ORBIT, "--step", "1e-9", "--duration", "1e9"], ["steps", "--step"]),
        ([*ORBIT, "--resume"], ["--resume", "-o"]),
        ([*ORBIT, "-o", "run.txt"], [".nc or .csv"]),
        ([*ORBIT, "--moon", "--sun-eci", "1", "0", "0"], ["Moon", "drop --sun-eci or --moon"]),
        ([*ORBIT, "--sun-eci", "0", "0", "0"], ["--sun-eci", "non-zero"]),
        (["--tle", "missing.tle", *EPOCH, "--duration", "60"], ["missing.tle", "cannot read"]),
        (
            ["--elements", "9000", "0", "60", "0", "0", "0", *EPOCH, "--drag"],
            ["above 2000 km", "NRLMSIS", "--srp"],
        ),
    ],
)
def test_bad_orbits_get_one_line(run_cli, craft, extra, words):
    code, out, err = run_cli("orbit", *craft, *extra)
    assert code == 1 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("sunwind: error: "), err
    for word in words:
        assert word in lines[0]


def test_steps_above_the_fitted_range_of_nrlmsis_are_said_once(run_cli, craft):
    args = ["orbit", *craft, "--altitude", "1200", "--inclination", "60", *EPOCH, "--step", "900"]
    code, _, err = run_cli(*args, "--drag", "--reflections", "none", "--sky-rays", "36", "--json")
    assert code == 0, err
    warnings = [line for line in err.splitlines() if line.startswith("sunwind: warning:")]
    assert warnings == [
        "sunwind: warning: 8 of 8 steps are above 1000 km, where NRLMSIS's exosphere is extrapolated"
    ]
