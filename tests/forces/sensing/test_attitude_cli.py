"""``sunwind attitude`` from the command line: text and JSON on the bundled example, and one error line
for each bad input (METHOD.md "Attitude from heat fluxes")."""

from __future__ import annotations

import json

import numpy as np
import pytest

import sunwind as sw

DATA = sw.meshes.sample_path().parent
OPTICS = ["--reflectivity", "0.07", "--specular-fraction", "0", "--emissivity", "0.82"]
HEADER = "time_s,sensor_px,sensor_mx,sensor_py,sensor_my,sensor_pz,sensor_mz"


def command(fluxes, *extra):
    return ["attitude", DATA / "sensor_cube.obj", *OPTICS, "--fluxes", fluxes, "--altitude", "500", *extra]


def test_the_example_gives_every_row_with_its_frame_and_the_eclipses(run_cli):
    """Text: the frame and the model's error said, twelve rows, the last two in eclipse (nadir only, a
    notice each); JSON: the issue's keys, quaternions and angles where the Sun is seen."""
    code, out, err = run_cli(*command(DATA / "sensor_cube_fluxes.csv"))
    assert code == 0, err
    assert "body frame of the mesh" in out and "flux model against the full forward model" in out
    assert out.count("t = ") == 12 and out.count("(eclipse)") == 2
    assert err.count("sunwind: notice:") == 2 and "in eclipse" in err and "Traceback" not in err
    assert "warning" not in err  # every row explained within the noise, none ambiguous
    code, out, err = run_cli(*command(DATA / "sensor_cube_fluxes.csv", "--json"))
    assert code == 0, err
    document = json.loads(out)
    rows = document["rows"]
    assert document["frame"].startswith("body frame") and len(rows) == 12
    keys = {"time_s", "sun_body", "nadir_body", "pitch_yaw_roll_deg", "quaternion", "sigma_deg", "misfit"}
    assert keys | {"ambiguous", "eclipse", "alternatives", "explained"} <= set(rows[0])
    assert all(row["explained"] for row in rows)
    assert all(row["quaternion"] is not None and len(row["pitch_yaw_roll_deg"]) == 3 for row in rows[:10])
    assert all(row["eclipse"] and row["sun_body"] is None and row["quaternion"] is None for row in rows[10:])
    assert all(row["misfit"] < 3.0 for row in rows)
    assert np.allclose([np.linalg.norm(row["nadir_body"]) for row in rows], 1.0)


@pytest.mark.slow
def test_noise_smaller_than_the_data_warns_that_rows_are_not_explained(run_cli):
    """--sigma 0.002 on fluxes with 1 % noise: the rows' misfits are well above 1, and each row the best
    attitude cannot explain gets a warning naming its time."""
    code, out, err = run_cli(*command(DATA / "sensor_cube_fluxes.csv", "--sigma", "0.002", "--json"))
    assert code == 0, err
    rows = json.loads(out)["rows"]
    unexplained = [row["time_s"] for row in rows if not row["explained"]]
    assert len(unexplained) >= 6
    for time in unexplained:
        assert f"t = {time:g} s: the best attitude does not explain the fluxes" in err


@pytest.mark.slow
def test_a_subset_of_sensors(run_cli):
    """``--sensors`` keeps the matching columns (the model's parts of the same names)."""
    code, out, err = run_cli(*command(DATA / "sensor_cube_fluxes.csv", "--sensors", "sensor_p*", "--json"))
    assert code == 0, err
    assert json.loads(out)["sensors"] == ["sensor_px", "sensor_py", "sensor_pz"]


BAD = [
    ("missing", None, "file not found"),
    ("no_time", "sensor_px,sensor_mx\n1,2\n", "no column time_s"),
    ("nan", f"{HEADER}\n0,1,2,3,nan,5,6\n", "line 2: column sensor_my is 'nan'"),
    ("unsorted", f"{HEADER}\n10,1,2,3,4,5,6\n5,1,2,3,4,5,6\n", "comes before"),
    ("stranger", "time_s,sensor_px,lens\n0,1,2\n", "column lens is not a part of the model"),
    ("half_group", f"{HEADER},sun_eci_x,sun_eci_y\n0,1,2,3,4,5,6,1,0\n", "column sun_eci_z missing"),
    ("sun_only", f"{HEADER},sun_eci_x,sun_eci_y,sun_eci_z\n0,1,2,3,4,5,6,1,0,0\n", "without nadir_eci"),
    (
        "zero_sun",
        f"{HEADER},sun_eci_x,sun_eci_y,sun_eci_z,nadir_eci_x,nadir_eci_y,nadir_eci_z\n"
        "0,1,2,3,4,5,6,0,0,0,0,0,-1\n",
        "sun_eci_* is zero",
    ),
    (
        "milliwatts",  # the first row of the example in mW/m^2
        f"{HEADER}\n0,681310,35670,174170,1183080,252090,8310\n",
        "t = 0 s: sensor_px 681310 W/m^2 is more than 3 times the most any attitude gives it",
    ),
]


@pytest.mark.parametrize(("name", "text", "words"), BAD, ids=[b[0] for b in BAD])
def test_a_bad_fluxes_file_is_one_error_line(run_cli, tmp_path, name, text, words):
    path = tmp_path / f"{name}.csv"
    if text is not None:
        path.write_text(text)
    code, out, err = run_cli(*command(path))
    assert code == 1 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("sunwind: error:") and words in lines[0], err
    assert str(path) in lines[0]


def test_an_output_over_the_fluxes_file_is_refused_and_the_file_kept(run_cli, tmp_path):
    fluxes = tmp_path / "fluxes.csv"
    fluxes.write_text((DATA / "sensor_cube_fluxes.csv").read_text())
    code, _, err = run_cli(*command(fluxes, "-o", fluxes))
    lines = err.strip().splitlines()
    assert code == 1 and len(lines) == 1 and "the output is also another file of this run" in lines[0], err
    assert fluxes.read_text() == (DATA / "sensor_cube_fluxes.csv").read_text()


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (["--sigma", "0"], "sigma"),
        (["--floor", "-1"], "floor"),
        (["--altitude", "-3"], "altitude"),
        (["--sensors", "lens*"], "matches no sensor column"),
        (["-o", "rows.txt"], "written as .json or .csv"),
        (["--resume"], "--resume takes up the checkpoint of an output"),
        (["-o", "rows.csv", "--chunk", "0"], "chunk"),
        (["--smooth", "0"], "--smooth 0 is not a smoothing window > 0 [s]"),
        (["--smooth", "nan"], "--smooth nan is not"),
    ],
)
def test_bad_settings_are_one_error_line(run_cli, extra, words):
    code, _, err = run_cli(*command(DATA / "sensor_cube_fluxes.csv", *extra))
    lines = err.strip().splitlines()
    assert code == 1 and len(lines) == 1 and lines[0].startswith("sunwind: error:") and words in lines[0], err


@pytest.mark.slow
def test_smoothing_the_example_finds_the_rate_it_was_made_with(run_cli, tmp_path):
    """The bundled rows (300 s apart, the cube turning at a constant rate) with --smooth 900: every row
    with two sunlit neighbours is smoothed, and the body rate is the one the rows were made with (the
    inertial rate of ``test_sample_fluxes`` in body axes) within 3 sigma; the first and last sunlit rows
    are said not smoothed, the eclipses are not, and the CSV gains the smoothed columns."""
    from scipy.spatial.transform import Rotation

    start = Rotation.from_euler("xyz", [20.0, -35.0, 60.0], degrees=True)
    rate = np.degrees(start.inv().apply([0.002, -0.001, 0.003]))
    code, out, err = run_cli(*command(DATA / "sensor_cube_fluxes.csv", "--smooth", "900", "--json"))
    assert code == 0, err
    document = json.loads(out)
    assert document["smooth_window_s"] == 900.0
    smoothed = [row["smoothed"] for row in document["rows"]]
    assert [s is not None for s in smoothed] == [False] + [True] * 8 + [False] * 3
    for s in smoothed[1:9]:
        assert s["rows"] == 3 and s["explained"] and len(s["quaternion"]) == 4
        assert np.linalg.norm(np.subtract(s["rate_deg_s"], rate)) <= 3.0 * s["sigma_rate_deg_s"]
    assert "2 sunlit rows (the first at t = 0 s) have fewer than 3 sunlit rows within --smooth 900 s" in err
    output = tmp_path / "rows.csv"
    code, out, err = run_cli(*command(DATA / "sensor_cube_fluxes.csv", "--smooth", "900", "-o", output))
    assert code == 0, err
    header = next(line for line in output.read_text().splitlines() if not line.startswith("#"))
    assert (
        header.endswith("smoothed_pitch_deg,smoothed_yaw_deg,smoothed_roll_deg") and "rate_deg_s_x" in header
    )
