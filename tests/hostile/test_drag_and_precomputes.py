"""Hostile command lines of issue 17 for drag inputs, caches and precomputes (items 7, 12, 15, 17, 28):
each gives the right exit status and one line, and no traceback."""

import json
import math

import pytest

AIR = ["--density", "3e-12", "--temperature", "900", "--composition", "O:0.8,N2:0.2"]
V = ["--velocity", "7600", "0", "0"]


@pytest.fixture(scope="module")
def sphere(tmp_path_factory):
    """A coarse sphere without any material: drag needs none, SRP needs optics."""
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import sphere

    path = tmp_path_factory.mktemp("hostile-drag") / "sphere.obj"
    save_mesh(sphere(1.0, 4), path)
    return path


CASES = {
    # item 7: speeds too small or too large to be a flow, and the atmosphere's siblings
    "velocity 1e-300": (["drag", "--velocity", "1e-300", "0", "0", *AIR], 1, ["--velocity", "below 1 m/s"]),
    "velocity 0.5": (
        ["drag", "--velocity", "0.5", "0", "0", *AIR],
        1,
        ["--velocity", "too slow to be a flow"],
    ),
    "velocity 1e300": (["drag", "--velocity", "1e300", "0", "0", *AIR], 1, ["--velocity", "above 1e+06 m/s"]),
    "velocity nan": (["drag", "--velocity", "nan", "0", "0", *AIR], 1, ["--velocity", "finite"]),
    "sky rays 0": (["drag", *V, *AIR, "--sky-rays", "0"], 1, ["--sky-rays 0", "from 1 to 65536"]),
    "sky rays 1e9": (["drag", *V, *AIR, "--sky-rays", "1000000000"], 1, ["--sky-rays", "from 1 to 65536"]),
    "sweep sky rays 1e9": (
        [
            "sweep",
            "--drag",
            "--step",
            "30",
            "--speed",
            "7600",
            "--sky-rays",
            "1000000000",
            *AIR,
            "-o",
            "{tmp}/d.nc",
        ],
        1,
        ["--sky-rays", "from 1 to 65536"],
    ),
    "speed 1e-300": (
        ["drag", "--flow-azel", "0", "0", "--speed", "1e-300", *AIR],
        1,
        ["--speed", "below 1 m/s"],
    ),
    "forces velocity 1e-300": (
        ["forces", "--sun", "1", "0", "0", "--velocity", "1e-300", "0", "0", *AIR],
        1,
        ["--velocity", "below 1 m/s"],
    ),
    "sweep speed 1e-300": (
        ["sweep", "--drag", "--step", "30", "--speed", "1e-300", *AIR, "-o", "{tmp}/d.nc"],
        1,
        ["--speed", "below 1 m/s"],
    ),
    "temperature 1e300": (
        ["drag", *V, "--density", "3e-12", "--temperature", "1e300", "--composition", "O:1"],
        1,
        ["--temperature", "above 100000"],
    ),
    "temperature 1e-300": (
        ["drag", *V, "--density", "3e-12", "--temperature", "1e-300", "--composition", "O:1"],
        1,
        ["--temperature", "below 1"],
    ),
    "wall temperature 1e300": (
        ["drag", *V, *AIR, "--wall-temperature", "1e300"],
        1,
        ["wall_temperature = 1e+300 K is above 10000 K"],
    ),
    "wall temperature 0": (["drag", *V, *AIR, "--wall-temperature", "0"], 1, ["wall_temperature = 0 K"]),
    "density 1e300": (
        ["drag", *V, "--density", "1e300", "--temperature", "900", "--composition", "O:1"],
        1,
        ["number density", "not a finite"],
    ),
    # item 15: drag asks for no optics; SRP still does, even when gas flags are given
    "drag without optics": (["drag", *V, *AIR], 0, []),
    "sweep drag without optics": (
        ["sweep", "--drag", "--step", "45", "--speed", "7600", *AIR, "-o", "{tmp}/d.nc"],
        0,
        [],
    ),
    "forces gas flags only": (
        ["forces", "--sun", "1", "0", "0", *V, *AIR, "--gsi", "sentman"],
        1,
        ["has no material", "--reflectivity"],
    ),
    "sweep srp gas flags only": (
        ["sweep", "--srp", "--step", "45", "--gsi", "sentman", "-o", "{tmp}/s.nc"],
        1,
        ["has no material", "--reflectivity"],
    ),
    # item 17: --corotating turns v_rel; a crosswind needs --nadir to be placed
    "corotating polar, no nadir": (
        ["drag", "--flow-azel", "0", "0", "--altitude", "400", "--corotating", "--heading", "0"],
        1,
        ["crosses the track at 494.3 m/s", "--nadir"],
    ),
    "corotating nadir along the track": (
        [
            "drag",
            "--flow-azel",
            "0",
            "0",
            "--altitude",
            "400",
            "--corotating",
            "--heading",
            "0",
            "--nadir",
            "1",
            "0",
            "0",
        ],
        1,
        ["--nadir is 90 deg off perpendicular"],
    ),
    "nadir without corotating": (
        ["drag", "--flow-azel", "0", "0", "--altitude", "400", "--nadir", "0", "0", "1"],
        1,
        ["--nadir", "--corotating"],
    ),
    "sweep nadir": (
        [
            "sweep",
            "--drag",
            "--altitude",
            "400",
            "--corotating",
            "--nadir",
            "0",
            "0",
            "1",
            "-o",
            "{tmp}/d.nc",
        ],
        1,
        ["drop --nadir"],
    ),
}


@pytest.mark.parametrize("name", list(CASES))
def test_hostile_drag_input(run_cli, sphere, tmp_path, name):
    args, code, words = CASES[name]
    command, *rest = args
    code_, _, err = run_cli(command, sphere, *(a.replace("{tmp}", str(tmp_path)) for a in rest))
    assert code_ == code, err
    assert "Traceback" not in err
    if code:
        assert err.startswith("sunwind: error: ") and err.count("\n") == 1, err
    for word in words:
        assert word in err


def test_drag_without_optics_uses_the_default_gas_law(run_cli, sphere):
    """No material at all: the documented defaults of the gas flags (sentman, T_w 300 K)."""
    runs = [run_cli("drag", sphere, *V, *AIR, *extra, "--json") for extra in ([], ["--gsi", "sentman"])]
    assert all(code == 0 for code, _, _ in runs)
    assert json.loads(runs[0][1])["force_N"] == json.loads(runs[1][1])["force_N"]


@pytest.mark.parametrize(
    "heading, nadir, expected",
    [
        ("90", [], lambda v, w: [v - w, 0.0, 0.0]),
        ("0", ["--nadir", "0", "0", "1"], lambda v, w: [v, -w, 0.0]),
    ],
    ids=["prograde equatorial", "polar at the equator"],
)
def test_corotating_drag_turns_v_rel_as_a_hand_computation(run_cli, sphere, heading, nadir, expected):
    """Body x along the orbit velocity, z to the Earth's centre: the air moves east (+y heading north)
    at omega r, so v_rel loses omega r along x going east, and gains -omega r along y going north."""
    code, out, err = run_cli(
        "drag",
        sphere,
        "--flow-azel",
        "0",
        "0",
        "--altitude",
        "400",
        "--corotating",
        "--heading",
        heading,
        *nadir,
        "--json",
    )
    assert code == 0, err
    v, omega_r = math.sqrt(3.986004418e14 / 6778.137e3), 7.292115e-5 * 6778.137e3
    assert json.loads(out)["velocity_m_s"] == pytest.approx(expected(v, omega_r), abs=1e-6)


@pytest.fixture(scope="module")
def box_wing(tmp_path_factory):
    """A small concave model: its wings see the bus, so it has view factors to cache."""
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import box_wing

    path = tmp_path_factory.mktemp("hostile-cache") / "box_wing.usda"
    save_mesh(box_wing(facet_size=0.5), path)
    return path


def test_a_forged_view_factor_cache_full_of_nan_is_rebuilt_with_a_warning(run_cli, box_wing, tmp_path):
    """Item 12: a cache entry under the right key and a valid checksum, its values NaN."""
    import numpy as np

    from sunwind.geometry.views.disk_cache import write_entry

    args = ["srp", box_wing, "--sun", "1", "0.3", "0.2", "--reflectivity", "0.5", "--specular-fraction", "0"]
    args += ["--reflections", "full", "--view-rays", "16", "--cache-dir", tmp_path, "--json"]
    code, fresh, err = run_cli(*args)
    assert code == 0 and "warning" not in err, err
    [path] = tmp_path.glob("view_factors-*.npz")
    stored = dict(np.load(path))
    arrays = {
        name: np.full_like(value, np.nan) if value.dtype.kind == "f" else value
        for name, value in stored.items()
    }
    write_entry(path, str(stored["key"]), {k: v for k, v in arrays.items() if k not in ("key", "checksum")})
    code, out, err = run_cli(*args)
    assert code == 0 and "Traceback" not in err
    assert (
        err.startswith("sunwind: warning: cache entry") and "was corrupt (values not finite): rebuilt" in err
    )
    assert json.loads(out)["force_N"] == json.loads(fresh)["force_N"]


def test_a_precompute_shows_its_steps_on_stderr_not_in_the_json(run_cli, box_wing, monkeypatch):
    """Item 28: every precompute step that runs for DELAY seconds prints a line (DELAY 0 here)."""
    import sunwind.forces.cli.progress as progress

    monkeypatch.setattr(progress, "DELAY", 0.0)
    args = ["drag", box_wing, *V, *AIR, "--reflections", "full", "--view-rays", "16", "--no-cache", "--json"]
    code, out, err = run_cli(*args)
    assert code == 0, err
    json.loads(out)  # stdout is the JSON alone
    for name in ("view factors", "molecular exchange"):
        assert f"sunwind: {name} ...\n" in err and f"sunwind: {name} done in " in err
    monkeypatch.setattr(progress, "DELAY", 60.0)
    assert run_cli(*args)[2] == ""  # quick steps print nothing
