"""The command line: output contracts, negative numbers, and one-line errors for every bad input."""

import json
import subprocess
import sys

import numpy as np
import pytest
import trimesh

BOX_OBJ = """o bus
v -0.5 -0.5 -0.5
v 0.5 -0.5 -0.5
v 0.5 0.5 -0.5
v -0.5 0.5 -0.5
v -0.5 -0.5 0.5
v 0.5 -0.5 0.5
v 0.5 0.5 0.5
v -0.5 0.5 0.5
usemtl paint
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
o wing
v 0.6 -0.5 0
v 2.6 -0.5 0
v 2.6 0.5 0
v 0.6 0.5 0
usemtl cell
f 9 10 11 12
"""

MATERIALS = """[materials.paint]
reflectivity = 0.8
specular_fraction = 0.1
[materials.cell]
reflectivity = 0.2
specular_fraction = 0.8
[materials.cfrp]
reflectivity = 0.1
specular_fraction = 0.0
[parts]
"wing" = { front = "cell", back = "cfrp" }
"""


@pytest.fixture
def craft_files(tmp_path):
    mesh = tmp_path / "craft.obj"
    mesh.write_text(BOX_OBJ)
    materials = tmp_path / "craft.toml"
    materials.write_text(MATERIALS)
    return mesh, materials


def test_srp_json_has_the_documented_keys_and_units(run_cli, craft_files):
    mesh, materials = craft_files
    code, out, err = run_cli("srp", mesh, "--materials", materials, "--sun", "-1", "0", "-0.5", "--json")
    assert code == 0, err
    doc = json.loads(out)
    for key in ("force_N", "torque_Nm", "reference_point_m", "sun_vector"):
        assert len(doc[key]) == 3
    for key in ("flux_W_m2", "lit_area_m2", "projected_area_m2"):
        assert isinstance(doc[key], float)
    assert doc["reference_point"] == "area centroid (default)" and doc["frame"].startswith("body")
    assert np.allclose(doc["sun_vector"], np.array([-1, 0, -0.5]) / np.sqrt(1.25))
    assert doc["force_N"][0] > 0  # pushed away from the Sun, which is toward -x


def test_sun_azel_with_negative_angles_matches_the_vector_form(run_cli, craft_files):
    mesh, materials = craft_files
    _, by_vector, _ = run_cli("srp", mesh, "-m", materials, "--sun", "0", "-0.866025403784", "-0.5", "--json")
    _, by_azel, _ = run_cli("srp", mesh, "-m", materials, "--sun-azel", "-90", "-30", "--json")
    assert np.allclose(json.loads(by_vector)["force_N"], json.loads(by_azel)["force_N"], rtol=1e-9)


def test_text_output_names_frame_units_and_reference_point(run_cli, craft_files):
    mesh, materials = craft_files
    code, out, _ = run_cli(
        "srp",
        mesh,
        "-m",
        materials,
        "--sun",
        "1",
        "1",
        "1",
        "--distance-au",
        "1.5",
        "--ref-point",
        "0",
        "0",
        "-0.1",
    )
    assert code == 0
    assert "body frame" in out and "force   [N]" in out and "torque  [N m]" in out
    assert "(user)" in out and "604.889 W/m^2" in out


def test_info_reports_parts_materials_and_checks(run_cli, craft_files):
    mesh, materials = craft_files
    code, out, _ = run_cli("info", mesh, "-m", materials, "--json")
    report = json.loads(out)
    assert code == 0 and report["triangles"] == 14 and report["closed"] is False
    parts = {p["name"]: p for p in report["parts"]}
    assert parts["bus"]["surface"] == "closed body" and parts["wing"]["surface"] == "two-sided sheet"
    assert np.isclose(report["area_m2"], 8.0)
    code, out, _ = run_cli("info", mesh)  # no materials: still a report, with what is missing
    assert code == 0 and "has material key 'paint', which is not defined" in out


def test_mesh_repairs_are_reported_as_notices(run_cli, tmp_path):
    box = trimesh.creation.box()
    path = tmp_path / "inverted.stl"
    trimesh.Trimesh(box.vertices, box.faces[:, ::-1], process=False).export(path)
    code, _, err = run_cli(
        "srp", path, "--sun", "1", "0", "0", "--reflectivity", "0", "--specular-fraction", "0"
    )
    assert code == 0 and "sunwind: notice:" in err and "wound inward" in err


def bad_inputs(tmp_path, mesh, materials):
    """(arguments, words the one-line error must contain) for every kind of bad input."""
    uniform = ["--reflectivity", "0.5", "--specular-fraction", "0.5"]
    sun = ["--sun", "1", "0", "0"]
    (tmp_path / "craft.xyz").write_text("nothing")
    (tmp_path / "garbage.stl").write_bytes(b"\x00\x01garbage" * 10)
    (tmp_path / "empty.obj").write_text("# no faces\n")
    (tmp_path / "nan.obj").write_text(
        "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n"
    )
    (tmp_path / "open.obj").write_text("o panel\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n")
    (tmp_path / "unknown_key.toml").write_text(
        "[materials.paint]\nreflectivity = 0.5\nspecular_fraction = 0\nshine = 1\n"
    )
    (tmp_path / "range.toml").write_text(
        "[materials.paint]\nreflectivity = 0.9\nspecular_fraction = 0\ntransmissivity = 0.2\n"
    )
    (tmp_path / "partial.toml").write_text("[materials.paint]\nreflectivity = 0.5\nspecular_fraction = 0\n")
    return [
        (["srp", tmp_path / "absent.obj", *sun, *uniform], ["absent.obj", "not found"]),
        (["srp", tmp_path / "craft.xyz", *sun, *uniform], ["craft.xyz", ".obj"]),
        (["srp", tmp_path / "garbage.stl", *sun, *uniform], ["garbage.stl"]),
        (["srp", tmp_path / "empty.obj", *sun, *uniform], ["empty.obj"]),
        (["srp", tmp_path / "nan.obj", *sun, *uniform], ["nan.obj", "NaN"]),
        (["srp", tmp_path / "open.obj", *sun, *uniform], ["open surface", "--two-sided"]),
        (["srp", mesh, "--sun", "0", "0", "0", *uniform], ["zero length"]),
        (["srp", mesh, "--sun", "nan", "0", "1", *uniform], ["finite"]),
        (["srp", mesh, *sun, "--flux", "nan", "-m", materials], ["--flux"]),
        (["srp", mesh, *sun, "--flux", "-5", "-m", materials], ["--flux"]),
        (["srp", mesh, *sun, "--distance-au", "0", "-m", materials], ["--distance-au"]),
        (["srp", mesh, *sun, "--ref-point", "0", "nan", "0", "-m", materials], ["--ref-point"]),
        (["srp", mesh, *sun, "--reflectivity", "nan", "--specular-fraction", "0"], ["reflectivity"]),
        (
            [
                "srp",
                mesh,
                *sun,
                "--reflectivity",
                "0.9",
                "--specular-fraction",
                "0",
                "--transmissivity",
                "0.2",
            ],
            ["exceeds 1"],
        ),
        (["srp", mesh, *sun, "--reflectivity", "0.5"], ["--specular-fraction"]),
        (["srp", mesh, *sun, "--sun-azel", "0", "0", *uniform], ["one of them"]),
        (["srp", mesh, "--sun-azel", "0", "95", *uniform], ["elevation"]),
        (["srp", mesh, *sun, "--samples", "0", *uniform], ["--samples"]),
        (
            ["srp", mesh, *sun, "-m", tmp_path / "unknown_key.toml"],
            ["unknown_key.toml", "unknown key 'shine'"],
        ),
        (["srp", mesh, *sun, "-m", tmp_path / "range.toml"], ["range.toml", "exceeds 1"]),
        (["srp", mesh, *sun, "-m", tmp_path / "partial.toml"], ["part 'wing'", "cell"]),
        (["srp", mesh, *sun, "-m", tmp_path / "absent.toml"], ["absent.toml", "no such file"]),
        (["srp", mesh, *sun], ["part 'bus'", "--reflectivity"]),
        (["srp", mesh, *sun, "-m", materials, "--unit", "furlong"], ["furlong", "mm"]),
        (["srp", mesh, "-m", materials], ["--sun"]),
        (["srp", mesh, "--sun", "1", "0", "-m", materials], ["--sun"]),
        (["srp", mesh, *sun, "-m", materials, "--reflections", "most"], ["--reflections", "most"]),
        (["srp", mesh, *sun, "-m", materials, "--reflection-cutoff", "2"], ["cutoff", "[0, 1)"]),
        (["srp", mesh, *sun, "-m", materials, "--reflection-depth", "0"], ["depth"]),
        (["srp", mesh, *sun, "-m", materials, "--view-rays", "0"], ["--view-rays"]),
    ]


def test_every_bad_input_gives_one_line_and_a_non_zero_exit(run_cli, craft_files, tmp_path):
    mesh, materials = craft_files
    for args, words in bad_inputs(tmp_path, mesh, materials):
        code, out, err = run_cli(*args)
        line = err.strip()
        assert code != 0, (args, out)
        first, *listed = line.splitlines()  # several problems: a heading, one line each, the fixes
        assert not listed or first.endswith(" problems:"), (args, err)
        assert "Traceback" not in line, (args, err)
        assert line.startswith("sunwind"), (args, line)
        for word in words:
            assert word in line, (args, word, line)


def test_the_installed_program_exits_cleanly_without_a_traceback(tmp_path):
    run = subprocess.run(
        [
            sys.executable,
            "-c",
            "from sunwind.forces.cli.app import main; main()",
            "srp",
            str(tmp_path / "none.stl"),
            "--sun",
            "1",
            "0",
            "0",
        ],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 1
    assert run.stderr.count("\n") == 1 and "Traceback" not in run.stderr


def test_mesh_command_writes_primitives_that_srp_reads(run_cli, tmp_path):
    path = tmp_path / "plate.obj"
    code, out, err = run_cli(
        "mesh", "plate", "--size-x", "2", "--size-y", "0.5", "--divisions", "4", "-o", path
    )
    assert code == 0, err
    code, out, err = run_cli(
        "srp",
        path,
        "--sun",
        "0",
        "0",
        "1",
        "--reflectivity",
        "0",
        "--specular-fraction",
        "0",
        "--two-sided",
        "plate",
        "--json",
    )
    assert code == 0, err
    doc = json.loads(out)
    assert np.isclose(doc["projected_area_m2"], 1.0) and np.isclose(doc["force_N"][2], -doc["pressure_Pa"])
    code, out, _ = run_cli(
        "mesh", "cylinder", "--radius", "0.5", "--no-caps", "--segments", "32", "-o", tmp_path / "tube.stl"
    )
    assert code == 0 and "lateral" in out


@pytest.mark.slow
def test_mesh_sample_writes_its_materials_file_beside_an_obj(run_cli, tmp_path):
    path = tmp_path / "craft.obj"
    code, out, err = run_cli("mesh", "sample", "--triangles", "3000", "-o", path)
    assert code == 0, err
    assert "craft.toml" in out and (tmp_path / "craft.toml").exists()
    code, _out, err = run_cli("srp", path, "-m", tmp_path / "craft.toml", "--sun", "1", "0", "0", "--json")
    assert code == 0, err


@pytest.mark.parametrize(
    "args, words",
    [
        (["mesh", "torus"], ["unknown mesh kind 'torus'", "cylinder"]),
        (["mesh", "sphere", "--colour", "3"], ["no parameter --colour", "--radius"]),
        (["mesh", "sphere", "--radius", "abc"], ["bad value for --radius"]),
        (["mesh", "sphere", "--radius", "-1"], ["radius"]),
        (["mesh", "box", "--size", "1", "2", "3", "-o", "/nonexistent/dir/box.obj"], ["does not exist"]),
    ],
)
def test_bad_mesh_requests_give_one_line(run_cli, tmp_path, args, words):
    if "-o" not in args:
        args = [*args, "-o", tmp_path / "out.obj"]
    code, _, err = run_cli(*args)
    assert code != 0 and err.count("\n") == 1
    for word in words:
        assert word in err


def test_reflections_in_json_split_direct_and_reflected_and_balance_power(run_cli, craft_files, tmp_path):
    mesh, materials = craft_files
    cache = tmp_path / "cache"
    args = ("srp", mesh, "-m", materials, "--sun", "0.3", "-0.4", "1", "--json", "--cache-dir", cache)
    code, out, err = run_cli(*args, "--reflections", "full")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["reflections"] == "full" and doc["reflections_requested"] == "full"
    assert doc["k_is"] > 0  # the wing sees the bus
    total = np.add(doc["direct"]["force_N"], doc["reflected"]["force_N"])
    np.testing.assert_allclose(doc["force_N"], total, rtol=1e-12)
    assert abs(doc["power"]["imbalance"]) < 1e-9
    assert "cache" in doc["view_factors"]["origin"] or "computed" in doc["view_factors"]["origin"]
    assert any(cache.iterdir())  # kept for the next run
    code, out, _ = run_cli(*args, "--reflections", "full")
    assert "cache" in json.loads(out)["view_factors"]["origin"]
    code, out, _ = run_cli(*args, "--reflections", "none")
    doc = json.loads(out)
    assert doc["reflections"] == "none" and doc["reflected"]["force_N"] == [0.0, 0.0, 0.0]
    assert doc["k_is"] is None  # no view factors were asked for, so none are computed for the report


def test_no_cache_leaves_no_file_and_info_reports_k_is(run_cli, craft_files, tmp_path):
    mesh, materials = craft_files
    cache = tmp_path / "cache"
    code, out, err = run_cli("info", mesh, "-m", materials, "--cache-dir", cache, "--no-cache")
    assert code == 0, err
    assert "k_is" in out and "open sky" in out
    assert not cache.exists() or not any(cache.iterdir())
    code, out, _ = run_cli("info", mesh, "-m", materials, "--json", "--no-k-is")
    assert "k_is" not in json.loads(out)
