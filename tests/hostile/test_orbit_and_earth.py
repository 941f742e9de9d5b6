"""Hostile command lines of issue 33 against ``orbit``, ``earth``, ``forces`` and ``sweep``'s Earth table:
each gives one ``sunwind: error:`` line and exit 1, or the right answer with a ``warning:`` line, and no
traceback."""

import json

import numpy as np
import pytest

BOX = ["--reflectivity", "0", "--specular-fraction", "0"]
LEO = ["--altitude", "500", "--inclination", "51.6", "--epoch", "2025-03-20T00:00:00Z"]
SHORT = ["--duration", "600", "--step", "60", "--srp"]
WARM = ["--emissivity", "0.8"]
AIR = ["--density", "3e-12", "--temperature", "900", "--composition", "O:1"]
PLANET_BELOW = ["--altitude", "500", "--sun", "1", "0", "0", "--earth", "0", "0", "-1"]
EARTH = ["earth", "{d}/box.obj", *BOX, *WARM, *PLANET_BELOW]
EARTH_TABLE = ["sweep", "{d}/box.obj", *BOX, *WARM, "--step", "30", "--srp", "--earth-radiation"]
EARTH_TABLE += ["--earth-altitude", "500", "--earth-sun", "1", "0", "0"]
ISS_1 = "1 25544U 98067A   25079.50000000  .00016717  00000-0  10270-3 0  9005"
ISS_2 = "2 25544  51.6400 208.9163 0006317  69.9862  25.2906 15.49560066 12340"


def _with_checksum(line: str) -> str:
    from sunwind.forces.orbit.tle import checksum

    return line[:68] + str(checksum(line))


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A 1 m box, TLEs good and broken, and ephemerides in the wrong unit and with a byte-order mark."""
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import box

    d = tmp_path_factory.mktemp("hostile-orbit")
    save_mesh(box(), d / "box.obj")
    one, two = _with_checksum(ISS_1), _with_checksum(ISS_2)
    (d / "good.tle").write_text(f"ISS (ZARYA)\n{one}\n{two}\n")
    (d / "latin1.tle").write_bytes(b"SAT \xe9\xe8\n" + f"{one}\n{two}\n".encode())
    altered = one[:68] + str((int(one[68]) + 1) % 10)
    (d / "checksum.tle").write_text(f"{altered}\n{two}\n")
    (d / "truncated.tle").write_text(f"{one[:40]}\n{two}\n")
    (d / "epoch.tle").write_text(f"{_with_checksum(one[:18] + 'ABCDE.FGHIJKLM' + one[32:])}\n{two}\n")
    (d / "two_satellites.tle").write_text(f"{one}\n{_with_checksum(two[:2] + '99999' + two[7:])}\n")
    (d / "list.csv").write_text("azimuth_deg,elevation_deg\n0,0\n90,0\n")
    header = "time,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s\n"
    rows = "2025-03-20T00:00:00Z,{},0,0,0,{},0\n2025-03-20T00:01:00Z,{},{},0,{},{},0\n"
    (d / "km.csv").write_text(header + rows.format(6878.137, 7.6127, 6874.0, 456.7, -0.5, 7.6))
    metres = rows.format(6878137, 7612.7, 6874000, 456700, -500, 7600)
    (d / "bom.csv").write_bytes(b"\xef\xbb\xbf" + (header + metres).encode())
    return d


CASES = {
    "tle not utf-8 (a Latin-1 name line)": (
        ["orbit", "{d}/box.obj", *BOX, "--tle", "{d}/latin1.tle", *SHORT],
        0,
        [],
    ),
    "tle checksum": (["orbit", "{d}/box.obj", *BOX, "--tle", "{d}/checksum.tle", *SHORT], 1, ["checksum"]),
    "tle truncated": (
        ["orbit", "{d}/box.obj", *BOX, "--tle", "{d}/truncated.tle", *SHORT],
        1,
        ["40 characters, not 69"],
    ),
    "tle epoch not a number": (
        ["orbit", "{d}/box.obj", *BOX, "--tle", "{d}/epoch.tle", *SHORT],
        1,
        ["epoch 'ABCDE.FGHIJKLM'"],
    ),
    "tle of two satellites": (
        ["orbit", "{d}/box.obj", *BOX, "--tle", "{d}/two_satellites.tle", *SHORT],
        1,
        ["two satellites"],
    ),
    "tle a year from its epoch": (
        ["orbit", "{d}/box.obj", *BOX, "--tle", "{d}/good.tle", "--epoch", "2026-03-20T00:00:00Z", *SHORT],
        0,
        ["warning: the run reaches 365 days from the TLE's epoch"],
    ),
    "tle without --duration flies one period": (
        ["orbit", "{d}/box.obj", *BOX, "--tle", "{d}/good.tle", "--step", "600", "--srp"],
        0,
        ["notice: 10 steps in "],  # 86400 / 15.4956 rev/day = 5576 s
    ),
    "step 5e-324": (
        ["orbit", "{d}/box.obj", *BOX, *LEO, "--duration", "600", "--step", "5e-324"],
        1,
        ["--step"],
    ),
    "step longer than the run": (
        ["orbit", "{d}/box.obj", *BOX, *LEO, "--duration", "60", "--step", "600", "--srp"],
        1,
        ["--step 600 s is longer than the run"],
    ),
    "600 011 steps": (
        ["orbit", "{d}/box.obj", *BOX, *LEO, "--duration", "36000600", "--step", "60", "--srp"],
        1,
        ["600011 steps", "--max-steps 600011", "h"],
    ),
    "inclination 951": (
        ["orbit", "{d}/box.obj", *BOX, "--altitude", "500", "--inclination", "951", *SHORT],
        1,
        ["inclination 951 deg is outside 0-180"],
    ),
    "elements 1e30 km": (
        ["orbit", "{d}/box.obj", *BOX, "--elements", "1e30", "0", "0", "0", "0", "0", *SHORT[:4], "--srp"],
        1,
        ["sphere of influence"],
    ),
    "ephemeris in km under metre columns": (
        ["orbit", "{d}/box.obj", *BOX, "--ephemeris", "{d}/km.csv", "--srp"],
        1,
        ["inside the Earth", "look like km in metre columns", "x_km"],
    ),
    "ephemeris with a byte-order mark": (
        ["orbit", "{d}/box.obj", *BOX, "--ephemeris", "{d}/bom.csv", "--srp"],
        0,
        [],
    ),
    "epoch 1900 names --epoch": (
        ["orbit", "{d}/box.obj", *BOX, "--altitude", "500", "--inclination", "51.6", "--epoch", "1900-01-01"],
        1,
        ["--epoch year 1900"],
    ),
    "plot to a text file": (
        ["orbit", "{d}/box.obj", *BOX, *LEO, *SHORT, "--plot", "{tmp}/o.txt"],
        1,
        ["picture"],
    ),
    "plot over the mesh": (
        ["orbit", "{d}/box.obj", *BOX, *LEO, *SHORT, "--plot", "{d}/box.obj"],
        1,
        ["picture"],
    ),
    "output over the ephemeris": (
        ["orbit", "{d}/box.obj", *BOX, "--ephemeris", "{d}/bom.csv", "--srp", "-o", "{d}/bom.csv"],
        1,
        ["also another file of this run"],
    ),
    "checkpoint path is a file": (
        ["orbit", "{d}/box.obj", *BOX, *LEO, *SHORT, "-o", "{tmp}/o.nc", "--resume"],
        1,
        ["a file is where the run keeps its checkpoint"],
    ),
    "inertial quaternion not unit": (
        ["orbit", "{d}/box.obj", *BOX, *LEO, *SHORT, "--attitude", "inertial:2,0,0,0"],
        1,
        ["not of unit length", "|q| = 2"],
    ),
    "earth cap step 1e-4": (
        [*EARTH, "--step", "1e-4"],
        1,
        ["--step 0.0001 cuts the planet's disc", "at least 0.8 deg"],
    ),
    "orbit earth step 0.01": (
        ["orbit", "{d}/box.obj", *BOX, *WARM, *LEO, *SHORT, "--earth-radiation", "--earth-step", "0.01"],
        1,
        ["--earth-step 0.01 cuts"],
    ),
    "sweep earth step 0.01": (
        [*EARTH_TABLE, "--earth-step", "0.01", "-o", "{tmp}/s.nc"],
        1,
        ["--earth-step 0.01 cuts"],
    ),
    "no emissivity names --emissivity": (
        ["earth", "{d}/box.obj", *BOX, *PLANET_BELOW],
        1,
        ["material 'uniform' has no emissivity", "--emissivity E"],
    ),
    "sweep list written over itself": (
        ["sweep", "{d}/box.obj", *BOX, "--srp", "--attitudes", "{d}/list.csv", "-o", "{d}/list.csv"],
        1,
        ["also another file of this run"],
    ),
    "velocity in km/s": (
        ["drag", "{d}/box.obj", "--velocity", "7.6", "0", "0", *AIR],
        0,
        ["warning: --velocity gives a speed of 7.6 m/s: that looks like km/s"],
    ),
}


@pytest.mark.parametrize("name", list(CASES))
def test_hostile_orbit_and_earth_input(run_cli, files, tmp_path, name):
    args, code, words = CASES[name]
    (tmp_path / "o.nc.checkpoint").write_text("not a directory")
    code_, _, err = run_cli(*(a.replace("{d}", str(files)).replace("{tmp}", str(tmp_path)) for a in args))
    assert code_ == code, err
    assert "Traceback" not in err
    if code:
        assert err.startswith("sunwind: error: ") and err.count("\n") == 1, err
    for word in words:
        assert word in err, err
    assert len(set(err.splitlines())) == len(err.splitlines()), err  # nothing said twice


def test_orbit_json_with_a_reference_point_gives_it_as_numbers(run_cli, files):
    """Every orbit run with --ref-point and --json raised 'Object of type ndarray is not JSON
    serializable'."""
    code, out, err = run_cli(
        "orbit", files / "box.obj", *BOX, *LEO, *SHORT, "--ref-point", "0", "0.1", "0", "--json"
    )
    assert code == 0, err
    document = json.loads(out)
    assert document["attributes"]["reference_point_m"] == [0.0, 0.1, 0.0]


def test_a_fixed_sun_of_1e308_is_a_direction_at_one_au(run_cli, files):
    """--sun-eci 1e308 0 0 overflowed the norm: the Sun sat at the Earth's centre and the box felt -920 N."""
    forces = []
    for size in ("1", "1e308"):
        code, out, err = run_cli(
            "orbit", files / "box.obj", *BOX, *LEO, *SHORT, "--sun-eci", size, "0", "0", "--json"
        )
        assert code == 0, err
        forces.append(np.array(json.loads(out)["srp_force_body_N"]))
    assert np.array_equal(forces[0], forces[1]) and np.abs(forces[0]).max() < 1e-5


@pytest.mark.slow
def test_ctrl_c_on_a_sweep_says_what_was_kept_and_how_to_resume(run_cli, files, tmp_path, monkeypatch):
    """Interrupted after its first chunk, a sweep keeps it and prints the command that resumes it; the
    resumed table is the uninterrupted one."""
    import sunwind.forces.tables.engine as engine

    output = tmp_path / "t.nc"
    args = ["sweep", files / "box.obj", *BOX, "--srp", "--step", "45", "--chunk", "8", "-o", output]
    finished = engine._Finished.__call__

    def interrupt_after_one(self, job, lo, hi, values):
        finished(self, job, lo, hi, values)
        raise KeyboardInterrupt

    monkeypatch.setattr(engine._Finished, "__call__", interrupt_after_one)
    code, _, err = run_cli(*args)
    assert code == 130 and "Traceback" not in err
    resume = f"resume with: sunwind sweep {files / 'box.obj'} "
    assert "sunwind: notice: 1 finished chunks are kept in " in err and resume in err and "--resume" in err
    assert err.rstrip().endswith("sunwind: aborted")  # click turns Ctrl-C into its Abort
    monkeypatch.undo()
    code, _, err = run_cli(*args, "--resume")
    assert code == 0 and "kept 1 chunks" in err, err


def test_ctrl_c_without_an_output_says_nothing_was_kept(run_cli, files, monkeypatch):
    import sunwind.forces.cli.orbit as orbit_cli

    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(orbit_cli, "fly", interrupt)
    code, _, err = run_cli("orbit", files / "box.obj", *BOX, *LEO, *SHORT)
    assert code == 130 and "nothing was kept: a run keeps its finished entries only with -o" in err


def test_orbit_files_carry_their_provenance_and_a_cf_time(run_cli, files, tmp_path):
    """The CSV starts with the same '#' lines as a sweep's (epoch, frame, reference point, the model's
    digest); the netCDF's time is a coordinate in seconds since the epoch, decoded as UTC times."""
    import xarray as xr

    for suffix in ("csv", "nc"):
        code, _, err = run_cli("orbit", files / "box.obj", *BOX, *LEO, *SHORT, "-o", tmp_path / f"o.{suffix}")
        assert code == 0, err
    header = [line for line in (tmp_path / "o.csv").read_text().splitlines() if line.startswith("#")]
    keys = {line[2:].split(":")[0] for line in header}
    assert {"epoch_utc", "frame", "reference_point_m", "reference_point", "mesh", "mesh_sha256"} <= keys
    with xr.open_dataset(tmp_path / "o.nc") as series:
        assert str(series["time"].values[1]) == "2025-03-20T00:01:00.000000000"
        assert series.attrs["mesh_sha256"] in "\n".join(header)


def test_the_top_level_help_names_every_commands_job_whole(run_cli):
    from sunwind.forces.cli.app import JOBS, app

    code, out, _ = run_cli("--help")
    commands = out.split("Commands:")[1]
    assert code == 0 and "..." not in commands
    assert set(JOBS) == set(app.commands)
    width = max(len(name) for name in JOBS)
    for name, job in JOBS.items():
        assert f"  {name:<{width}}  {job}" in commands  # each job on its line, whole


def test_mesh_help_lists_every_kinds_parameters(run_cli):
    import inspect

    from sunwind import meshes

    code, out, _ = run_cli("mesh", "cylinder", "--help")
    assert code == 0 and "Parameters of each kind" in out
    for name in inspect.signature(meshes.cylinder).parameters:
        assert name.replace("_", "-") in out.split("cylinder ", 1)[1]
