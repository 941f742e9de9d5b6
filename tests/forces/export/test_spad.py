"""SPAD files: every file passes a strict reader written from GMAT's rules, holds the right areas, and gives
back the table's force when used the way GMAT uses it."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from helpers.tables import ATTRS, field, grid_table, list_table
from sunwind.forces.export.spad import read_spad, spad_paths, write_spad
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, SPEED_OF_LIGHT
from sunwind.forces.tables.interpolation import azel_directions
from sunwind.geometry.errors import InputError

MOTIONS = (("Azimuth", -180, 180, 360), ("Elevation", -90, 90, 180))


def strict_read(path: Path) -> dict:
    """Parse a SPAD file, asserting every rule GMAT R2020a's SPADFileReader applies (and row order).

    Returns the header, the two steps and the areas (n_az, n_el, 3) [m^2].
    """
    lines = [line.strip() for line in path.read_text(encoding="ascii").splitlines()]
    lines = [line for line in lines if line]
    # header: key : value pairs (exactly one colon) up to the first Motion line
    first_motion = next(i for i, line in enumerate(lines) if line.startswith("Motion"))
    header = {}
    for line in lines[:first_motion]:
        assert line.count(":") == 1, f"header line not a key : value pair: {line!r}"
        key, value = (part.strip() for part in line.split(":"))
        assert key and not key.startswith(("Azimuth", "Current")), line
        header[key] = value
    assert header["Analysis Type"] == "Area"
    # two Motion blocks, then ': END', then the record count
    position = first_motion
    steps = []
    for number, (name, low, high, span) in enumerate(MOTIONS, start=1):
        block = [tuple(part.strip() for part in line.split(":")) for line in lines[position : position + 6]]
        assert all(len(pair) == 2 for pair in block), block
        assert [key for key, _ in block] == ["Motion", "Name", "Method", "Minimum", "Maximum", "Step"]
        values = dict(block)
        assert values["Motion"] == str(number) and values["Name"] == name and values["Method"] == "Step"
        assert float(values["Minimum"]) == low and float(values["Maximum"]) == high
        step = int(values["Step"])  # GMAT reads the step as an integer
        assert step > 0 and span % step == 0
        steps.append(step)
        position += 6
    assert lines[position] == ": END"
    key, count = (part.strip() for part in lines[position + 1].split(":"))
    assert key == "Record count"
    count = int(count)
    # titles, units, dashes
    assert lines[position + 2].split()[:2] == ["Azimuth", "Elevation"]
    assert lines[position + 3].split() == ["degrees", "degrees", "m^2", "m^2", "m^2"]
    assert set(lines[position + 4]) <= {"-", " "} and "--" in lines[position + 4]
    rows = np.array([[float(v) for v in line.split()] for line in lines[position + 5 :]])
    n_az, n_el = 360 // steps[0] + 1, 180 // steps[1] + 1
    assert rows.shape == (count, 5) and count == n_az * n_el
    # azimuth the outer loop, elevation the inner one, whole degrees, both ends present
    az = np.repeat(np.arange(-180, 181, steps[0]), n_el)
    el = np.tile(np.arange(-90, 91, steps[1]), n_az)
    np.testing.assert_array_equal(rows[:, 0], az)
    np.testing.assert_array_equal(rows[:, 1], el)
    return {"header": header, "steps": steps, "area": rows[:, 2:].reshape(n_az, n_el, 3)}


def gmat_area(spad: dict, direction: np.ndarray) -> np.ndarray:
    """The area GMAT takes from a parsed file for a body-frame direction (SPADFileReader::GetSRPArea)."""
    x, y, z = direction
    azimuth = math.degrees(math.atan2(y, x))
    elevation = math.degrees(math.atan2(z, math.hypot(x, y)))
    az_step, el_step = spad["steps"]
    i = int((azimuth + 180) / az_step)
    j = int((elevation + 90) / el_step)
    ta = (azimuth - (i * az_step - 180)) / az_step
    te = (elevation - (j * el_step - 90)) / el_step
    a = spad["area"]
    low = (1 - ta) * a[i, j] + ta * a[i + 1, j]
    high = (1 - ta) * a[i, j + 1] + ta * a[i + 1, j + 1]
    return (1 - te) * low + te * high


def test_srp_file_holds_the_area_at_1_au(tmp_path):
    table = grid_table(10.0, kinds=("srp",))
    spad = strict_read(write_spad(table, tmp_path / "craft.spo", "srp"))
    assert spad["steps"] == [10, 10]
    sun = azel_directions(np.arange(-180, 181, 10)[:, None], np.arange(-90, 91, 10)[None, :])
    force_1au = field(sun, 1e-6)[0] * SOLAR_FLUX_1AU / ATTRS["flux_W_m2"]
    np.testing.assert_allclose(spad["area"], force_1au / (SOLAR_FLUX_1AU / SPEED_OF_LIGHT), rtol=1e-14)
    assert spad["header"]["System"] == "craft.obj"
    assert "spacecraft-to-Sun" in spad["header"]["Direction"]


def test_drag_file_holds_minus_force_over_q_looked_up_at_minus_v_rel(tmp_path):
    table = grid_table(10.0, kinds=("drag",))
    spad = strict_read(write_spad(table, tmp_path / "craft.spo", "drag"))
    row_direction = azel_directions(np.arange(-180, 181, 10)[:, None], np.arange(-90, 91, 10)[None, :])
    expected = -field(-row_direction, 1e-3)[0] / ATTRS["dynamic_pressure_Pa"]
    np.testing.assert_allclose(spad["area"], expected, rtol=1e-13, atol=1e-12 * np.abs(expected).max())


@pytest.mark.parametrize("kind", ["srp", "drag"])
def test_gmat_gets_back_the_force(tmp_path, kind):
    """GMAT's SRP: a = P A / m along A; drag: A looked up at -v_rel, a = -rho |v|^2 A / (2 m)."""
    spad = strict_read(write_spad(grid_table(5.0, kinds=(kind,)), tmp_path / "craft.spo", kind))
    rng = np.random.default_rng(3)
    for d in azel_directions(rng.uniform(-179, 179, 40), rng.uniform(-85, 85, 40)):
        if kind == "srp":
            force = SOLAR_FLUX_1AU / SPEED_OF_LIGHT * gmat_area(spad, d) * ATTRS["flux_W_m2"] / SOLAR_FLUX_1AU
            exact = field(d, 1e-6)[0]
        else:
            force = -ATTRS["dynamic_pressure_Pa"] * gmat_area(spad, -d)
            exact = field(d, 1e-3)[0]
        assert np.linalg.norm(force - exact) < 5e-3 * np.linalg.norm(exact), (kind, d)


def test_read_spad_round_trip(tmp_path):
    path = write_spad(grid_table(15.0), tmp_path / "craft.spo", "drag")
    table = read_spad(path)
    np.testing.assert_array_equal(table["area_m2"].values, strict_read(path)["area"])
    assert table.attrs["Analysis Type"] == "Area"
    np.testing.assert_array_equal(table["azimuth"].values, np.arange(-180, 181, 15))


def test_read_spad_refuses_what_is_not_a_spad_file_and_reads_a_byte_order_mark(tmp_path):
    path = write_spad(grid_table(15.0), tmp_path / "craft.spo", "drag")
    text = path.read_text()
    (tmp_path / "bom.spo").write_bytes(b"\xef\xbb\xbf" + text.encode())
    np.testing.assert_array_equal(read_spad(tmp_path / "bom.spo")["area_m2"], read_spad(path)["area_m2"])
    rows = text.splitlines()
    cases = {
        "missing.spo": (None, "cannot read the SPAD file"),
        "binary.spo": (b"\xff\xfe\x00garbage", "not text"),
        "letters.spo": ("\n".join([*rows[:-1], "0 0 x 1 1"]).encode(), "not numbers"),
        "zero.spo": (text.replace("Step    : 15", "Step    : 0").encode(), "do not fill"),
        "nan.spo": (text.replace("Step    : 15", "Step    : nan").encode(), "do not fill"),
        "short.spo": ("\n".join(rows[:-3]).encode(), "do not fill"),
        "narrow.spo": ("\n".join([*rows[:-1], "0 0 1 1"]).encode(), "not numbers|5 columns"),
    }
    for name, (data, match) in cases.items():
        if data is not None:
            (tmp_path / name).write_bytes(data)
        with pytest.raises(InputError, match=match):
            read_spad(tmp_path / name)


def test_spad_paths_name_one_or_two_files(tmp_path):
    assert spad_paths(tmp_path / "run.spo", ["srp"]) == {"srp": tmp_path / "run.spo"}
    assert spad_paths(tmp_path / "run", ["srp", "drag"]) == {
        "srp": tmp_path / "run.srp.spo",
        "drag": tmp_path / "run.drag.spo",
    }
    with pytest.raises(InputError, match="unknown SPAD kind"):
        spad_paths(tmp_path / "run.spo", ["aero"])


def test_bad_input(tmp_path):
    path = tmp_path / "craft.spo"
    with pytest.raises(InputError, match="needs an azimuth/elevation grid, not an attitude list"):
        write_spad(list_table(), path, "srp")
    with pytest.raises(InputError) as error:
        write_spad(grid_table(15.0, kinds=("srp",)), path, "drag")
    assert str(error.value) == (
        "cannot write a drag SPAD file: the table has no drag_force_N; run the sweep with drag included"
    )
    with pytest.raises(InputError, match=r"sun azimuth step 51.4286 deg is not a whole number of degrees"):
        write_spad(grid_table(360 / 7, el_step_deg=10.0), path, "srp")
    with pytest.raises(
        InputError, match=r"flow elevation step 25.7143 deg .*divides 180 deg, e.g. 18, 20, 30, 36"
    ):
        write_spad(grid_table(10.0, el_step_deg=180 / 7), path, "drag")
    with pytest.raises(InputError, match=r"no point opposite each azimuth .* step that divides 180"):
        write_spad(grid_table(40.0, el_step_deg=10.0), path, "drag")
    with pytest.raises(InputError, match="unknown SPAD kind 'aero'"):
        write_spad(grid_table(15.0), path, "aero")
    assert not path.exists()


def test_sweep_of_a_sphere_writes_the_analytic_sphere(run_cli, tmp_path):
    """End to end: ``sunwind sweep`` of a meshed sphere to SPAD; the strict reader takes the file and
    its areas are the analytic sphere's ``A = pi R^2 (1 - sigma + 4 rho (1 - beta) / 9) (-u)`` to the
    mesh's own accuracy (48 latitude bands: ~0.1 %)."""
    from sunwind.validation.analytic_srp import sphere_srp
    from sunwind.validation.analytic_srp_law import Optics

    mesh = tmp_path / "sphere.stl"
    assert run_cli("mesh", "sphere", "--radius", "1", "--subdivisions", "48", "-o", mesh)[0] == 0
    table = tmp_path / "sphere.spo"
    code, out, err = run_cli(
        "sweep",
        mesh,
        "--reflectivity",
        "0.4",
        "--specular-fraction",
        "0.5",
        "--transmissivity",
        "0.1",
        "--srp",
        "--samples",
        "1",
        "--reflections",
        "none",
        "--step",
        "30",
        "--distance-au",
        "2",
        "-o",
        table,
    )
    assert code == 0, err
    assert str(table) in out
    spad = strict_read(table)
    az, el = np.meshgrid(np.arange(-180, 181, 30.0), np.arange(-90, 91, 30.0), indexing="ij")
    pressure = SOLAR_FLUX_1AU / SPEED_OF_LIGHT
    for d, area in zip(azel_directions(az, el).reshape(-1, 3), spad["area"].reshape(-1, 3), strict=True):
        expected = sphere_srp(1.0, d, Optics(0.4, 0.5, 0.1)).force_N / pressure
        assert np.linalg.norm(area - expected) <= 2e-3 * np.linalg.norm(expected)
