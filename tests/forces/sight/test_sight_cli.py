"""``sunwind visibility`` from the command line: its three modes, its files, and one line for each
bad input (METHOD.md "Lines of sight")."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

POINTS = (
    "name,x,y,z,boresight_x,boresight_y,boresight_z,half_angle_deg\n"
    "top,0.0,0.0,0.5,0,0,1,80\n"
    "bottom,0.0,0.0,-0.5,0,0,-1,80\n"
    "free,0.0,0.0,3.0,,,,\n"
)
ORBIT = ["--altitude", "500", "--inclination", "0", "--epoch", "2024-03-20T00:00:00Z", "--step", "60"]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes import box

    folder = tmp_path_factory.mktemp("sight-cli")
    save_mesh(box(), folder / "box.obj")
    (folder / "points.csv").write_text(POINTS)
    return folder


def test_directions_print_and_give_json_with_frame_and_ranging(run_cli, files):
    args = ["visibility", files / "box.obj", "--points", files / "points.csv", "--direction", "0", "0", "2"]
    code, out, err = run_cli(*args, "--direction", "0", "0", "-1", "--ranging")
    assert code == 0, err
    assert "body frame of the mesh" in out and "top - free" not in out
    code, out, err = run_cli(*args, "--json")
    assert code == 0, err
    document = json.loads(out)
    top, bottom, free = document["points"]
    assert document["frame"].startswith("body frame") and top["lines"][0]["visible"]
    assert bottom["lines"][0]["blocked_by"] == "box" and bottom["lines"][0]["distance_m"] == pytest.approx(
        1.0
    )
    assert free["lines"][0]["visible"] and free["half_angle_deg"] is None


def test_a_map_writes_netcdf_and_a_plot(run_cli, files, tmp_path):
    args = ["visibility", files / "box.obj", "--points", files / "points.csv", "--map", "--step", "5"]
    code, out, err = run_cli(*args, "-o", tmp_path / "map.nc", "--plot", tmp_path / "map.png")
    assert code == 0, err
    assert "estimate" in out and (tmp_path / "map.png").stat().st_size > 10_000
    table = xr.open_dataset(tmp_path / "map.nc")
    assert table["blocking_part"].dims == ("point", "elevation_deg", "azimuth_deg")
    assert table["azimuth_deg"].attrs["units"] == "degree" and "atan2(y, x)" in table.attrs["conventions"]
    fraction = table["blocked_fraction"].sel(point="free").item()
    exact = (1 - np.cos(np.arctan(np.sqrt(0.5) / 2.5))) / 2  # about the cube's solid angle, for scale
    assert 0.2 * exact < fraction < 2 * exact


def test_along_an_orbit_the_sun_earth_and_a_station(run_cli, files):
    base = ["visibility", files / "box.obj", "--points", files / "points.csv", *ORBIT, "--json"]
    code, out, err = run_cli(*base, "--target", "sun", "--attitude", "sun:+z,+x")
    assert code == 0, err
    sun = json.loads(out)
    seen = np.array(sun["points"][0]["visible"])
    assert np.array_equal(seen, np.array(sun["solar_fraction"]) > 0)  # +z at the Sun: only eclipses hide it
    assert not any(sun["points"][1]["visible"]) and len(sun["points"][0]["intervals"]) == 2
    code, out, err = run_cli(*base, "--target", "earth")
    earth = json.loads(out)
    assert code == 0 and all(earth["points"][0]["visible"]) and not any(earth["points"][1]["visible"])
    code, out, err = run_cli(
        *base, "--station", "0", "0", "0", "--min-elevation", "10", "--duration", "86400"
    )
    assert code == 0, err
    station = json.loads(out)
    up = np.array(station["elevation_deg"]) >= 10
    assert up.any() and np.array_equal(np.array(station["points"][0]["visible"]), up)
    offsets = station["range_offsets"]["directions"]
    assert all(("top" in row["offsets_m"]) == bool(k) for row, k in zip(offsets, up, strict=True))


BAD = [
    ("name,x,y\na,1,2\n", [], "p.csv: no column 'z'"),
    ("name,x,y,z\na,1,two,3\n", [], "p.csv: line 2: column y is 'two', not a finite number"),
    ("name,x,y,z\na,1,2,3\na,0,0,0\n", [], "line 3: the name 'a' is given twice"),
    ("x,y,z,name\n1,2,3\n", [], "line 2: the name is empty"),
    (POINTS.replace("0,0,1,80", "0,0,0,80"), [], "the boresight has zero length"),
    (POINTS.replace("0,0,1,80", "0,0,1,0"), [], "half_angle_deg 0 must be in (0, 180]"),
    (POINTS.replace("0,0,1,80", "0,0,1,"), [], "the cone cells half_angle_deg are empty"),
    (POINTS, ["--direction", "0", "0", "0"], "--direction: direction 0 has zero length"),
    (POINTS, ["--map", "--step", "40"], "--step 40 must be from 0.1 to 15 degrees"),
    (POINTS, ["--station", "95", "0", "0", *ORBIT], "the station's latitude 95 deg must be from -90 to 90"),
    (POINTS, ["--direction", "0", "0", "1", "--map"], "give one of --direction, --map and --target"),
    (POINTS, ["--direction", "0", "0", "1", "-o", "x.nc"], "this run is written as .json"),
]


@pytest.mark.parametrize(("text", "extra", "message"), BAD, ids=[m for *_, m in BAD])
def test_a_bad_input_gets_one_line_and_exit_1(run_cli, files, tmp_path, text, extra, message):
    (tmp_path / "p.csv").write_text(text)
    args = extra or ["--direction", "0", "0", "1"]
    code, _, err = run_cli("visibility", files / "box.obj", "--points", tmp_path / "p.csv", *args)
    lines = err.strip().splitlines()
    assert code == 1 and len(lines) == 1 and lines[0].startswith("sunwind: error: "), err
    assert message in lines[0] and "Traceback" not in err


def test_a_missing_points_file_is_named(run_cli, files):
    code, _, err = run_cli("visibility", files / "box.obj", "--points", "nowhere.csv", "--map")
    assert code == 1 and err.strip() == (
        "sunwind: error: nowhere.csv: file not found; check the path and its spelling"
    )
