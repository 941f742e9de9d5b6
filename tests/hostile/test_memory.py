"""Hostile sizes on the command line (issue 17, items 8 and 11): each is refused before anything big is
allocated, as one error line with the estimate and the limit, never a traceback or numpy's
ArrayMemoryError. ``SUNWIND_MAX_MEMORY`` is set small, so nothing real is allocated."""

from __future__ import annotations

import time

import pytest

import sunwind.forces.cli.attitude as attitude_commands

BOX = ["--reflectivity", "0.3", "--specular-fraction", "0.5"]
SRP = "srp {box} --sun 1 0 0 --reflectivity 0.3 --specular-fraction 0.5"
GAS = "--density 1e-12 --temperature 1000 --composition O:1"
DRAG = f"drag {{box}} --reflectivity 0.3 --specular-fraction 0.5 --velocity 7500 0 0 {GAS}"
SWEEP = "sweep {box} --reflectivity 0.3 --specular-fraction 0.5 -o {tmp}/t.nc"
HUGE = "1" + "0" * 400  # past every float and int64

#: name: (command line, {box} a 12-triangle box, {tmp} a folder; words of the message; exit code)
CASES = {
    "srp --samples 1e9": (
        f"{SRP} --samples 1000000000",
        ["needs ~", "points per side", "lower --samples"],
        1,
    ),
    "srp --samples 10**400": (f"{SRP} --samples {HUGE}", ["more than 1e308 B", "lower --samples"], 1),
    "srp --samples 1e30": (f"{SRP} --samples 1e30", ["not a valid integer"], 2),
    "drag --samples 1e9": (f"{DRAG} --samples 1000000000", ["needs ~", "lower --samples"], 1),
    "srp --view-rays 1e12": (
        f"{SRP} --reflections full --view-rays 1000000000000 --no-cache",
        ["--view-rays 1000000000000 must be a whole number from 1 to 65536"],
        1,
    ),
    "info --view-rays 1e12": (
        "info {box} --reflectivity 0.3 --specular-fraction 0.5 --view-rays 1000000000000 --no-cache",
        ["--view-rays 1000000000000 must be a whole number from 1 to 65536"],
        1,
    ),
    "sweep --step 0.001": (f"{SWEEP} --srp --step 0.001", ["6.48e+10 grid nodes", "raise --step"], 1),
    "sweep --step 1e-300": (f"{SWEEP} --srp --step 1e-300", ["grid nodes", "raise --step"], 1),
    "sweep --step 0.5 (table)": (
        f"{SWEEP} {GAS} --speed 7500 --step 0.5",
        ["a table of 2.6e+05 grid nodes (srp, drag)", "raise --step"],
        1,
    ),
    "mesh sphere --subdivisions 1e5": (
        "mesh sphere --subdivisions 100000 -o {tmp}/m.obj",
        ["lower --subdivisions"],
        1,
    ),
    "mesh plate --divisions 1e6": ("mesh plate --divisions 1000000 -o {tmp}/m.obj", ["lower --divisions"], 1),
    "mesh plate --divisions 1e20": (
        "mesh plate --divisions 99999999999999999999 -o {tmp}/m.obj",
        ["facets"],
        1,
    ),
    "mesh box --divisions 1e5": ("mesh box --divisions 100000 -o {tmp}/m.obj", ["lower --divisions"], 1),
    "mesh cylinder --segments 1e8": (
        "mesh cylinder --segments 100000000 -o {tmp}/m.obj",
        ["--segments or"],
        1,
    ),
    "mesh cone --rings 1e9": (
        "mesh cone --rings 1000000000 -o {tmp}/m.obj",
        ["lower --segments or --rings"],
        1,
    ),
    "mesh dish --segments 1e9": ("mesh dish --segments 1000000000 -o {tmp}/m.obj", ["lower --segments"], 1),
    "mesh box_wing --facet-size 1e-6": (
        "mesh box_wing --facet-size 1e-6 -o {tmp}/m.obj",
        ["raise --facet-size"],
        1,
    ),
    "mesh box_wing --facet-size 1e-320": (
        "mesh box_wing --facet-size 1e-320 -o {tmp}/m.obj",
        ["too many"],
        1,
    ),
    "mesh sample --triangles 1e10": (
        "mesh sample --triangles 10000000000 -o {tmp}/m.obj",
        ["lower --triangles"],
        1,
    ),
    "bench --triangles 1e10": ("bench --triangles 10000000000", ["facets", "lower --triangles"], 1),
    "bench --attitudes 1e12": (
        "bench --mesh {box} -m {tmp}/box.toml --attitudes 1000000000000",
        ["--attitudes 1000000000000 must be from 1 to 10000"],
        1,
    ),
    "bench --sweep --step 0.001": ("bench --sweep --step 0.001", ["grid nodes", "raise --step"], 1),
}


@pytest.fixture
def box(tmp_path, run_cli) -> str:
    path = tmp_path / "box.obj"
    assert run_cli("mesh", "box", "-o", path)[0] == 0
    materials = '[materials.m]\nreflectivity = 0.3\nspecular_fraction = 0.5\n[parts]\nbox = "m"\n'
    (tmp_path / "box.toml").write_text(materials)
    return str(path)


@pytest.mark.parametrize("name", list(CASES))
def test_hostile_size_is_one_error_line(name, box, tmp_path, run_cli, monkeypatch):
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", "100M")
    words, keys, expected = CASES[name]
    start = time.perf_counter()
    code, _, err = run_cli(*words.format(box=box, tmp=tmp_path).split())
    assert time.perf_counter() - start < 30  # refused before the work (a cold start compiles kernels)
    assert code == expected, err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert "error:" in err
    for key in keys:
        assert key in err, err
    if "needs" in err:
        assert "limit 100 MiB (SUNWIND_MAX_MEMORY=100M)" in err


def test_a_request_that_fits_still_runs(box, run_cli, monkeypatch):
    """The limit refuses only what does not fit: 16 points per side on the box is a few kB."""
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", "50M")
    code, _, err = run_cli("srp", box, "--sun", "1", "0", "0", *BOX, "--samples", "16")
    assert code == 0, err


@pytest.mark.parametrize("setting", ["lots", "-4G", "0", "4Q", "nan"])
def test_malformed_limit_is_one_error_line(setting, box, run_cli, monkeypatch):
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", setting)
    code, _, err = run_cli("srp", box, "--sun", "1", "0", "0", *BOX, "--samples", "16")
    assert code == 1 and "Traceback" not in err
    assert f"SUNWIND_MAX_MEMORY={setting!r} is not a memory size" in err


def test_memory_error_that_escapes_is_one_line(box, run_cli, monkeypatch):
    """The last-resort guard of ``main``: a MemoryError no estimate caught becomes one line, exit 1."""

    def exhausted(*args, **kwargs):
        raise MemoryError

    monkeypatch.setattr(attitude_commands, "srp_of", exhausted)
    code, _, err = run_cli("srp", box, "--sun", "1", "0", "0", *BOX)
    assert code == 1
    assert err.startswith("sunwind: error: out of memory") and "SUNWIND_MAX_MEMORY" in err
    assert len(err.strip().splitlines()) == 1


def test_mesh_rings_are_counts(tmp_path, run_cli):
    """``--rings`` (default None) is read as a count, not as a float the builder then refuses."""
    code, out, err = run_cli("mesh", "cone", "--rings", "5", "-o", tmp_path / "c.obj")
    assert code == 0, err
    assert "wrote" in out
