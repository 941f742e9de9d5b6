"""``sunwind earth``: output contract, the closed form it reproduces, and one-line errors for bad input."""

import csv
import json

import numpy as np
import pytest

from helpers.planet import BLACK, EARTH_EXITANCE, infrared_on_black_sphere, materials_toml, write_sphere


@pytest.fixture(scope="module")
def sphere(tmp_path_factory):
    """A 1 m black sphere and its materials file."""
    folder = tmp_path_factory.mktemp("earth")
    write_sphere(folder / "sphere.obj", 24)
    (folder / "black.toml").write_text(BLACK)
    (folder / "bare.toml").write_text(materials_toml("black", 0.0, 0.0, None))
    return folder


def _args(folder, *extra):
    return ["earth", folder / "sphere.obj", "-m", folder / "black.toml", "--earth", "0", "0", "-1", *extra]


def test_json_has_the_documented_keys_and_the_closed_form(run_cli, sphere):
    code, out, err = run_cli(
        *_args(sphere, "--altitude", "500", "--sun", "0", "0", "1", "--thermal", "--json")
    )
    assert code == 0, err
    doc = json.loads(out)
    for key in ("albedo", "infrared", "thermal", "solar"):
        assert {"force_N", "torque_Nm"} <= set(doc[key])
    part = doc["parts"]["sphere"] if "sphere" in doc["parts"] else next(iter(doc["parts"].values()))
    assert {"area_m2", "solar_W", "albedo_W", "infrared_W", "reflected_W", "temperature_K"} <= set(part)
    # an absorbing sphere under a uniform emitter, away from the planet, to the faceting
    expected = infrared_on_black_sphere(part["area_m2"], EARTH_EXITANCE, 500.0)
    assert doc["infrared"]["force_N"][2] == pytest.approx(expected, rel=1e-4)
    assert abs(doc["thermal"]["imbalance"]) < 1e-9
    assert doc["solar_fraction"] == 1.0


def test_behind_the_planet_the_sun_is_gone_and_the_sides_file_is_written(run_cli, sphere, tmp_path):
    sides = tmp_path / "sides.csv"
    code, out, err = run_cli(
        *_args(sphere, "--altitude", "500", "--sun", "0", "0", "-1", "--sides", sides, "--json")
    )
    assert code == 0, err
    doc = json.loads(out)
    assert doc["solar_fraction"] == 0.0
    assert all(part["solar_W"] == 0.0 for part in doc["parts"].values())
    with sides.open() as handle:
        rows = list(csv.DictReader(handle))
    assert sum(float(r["infrared[W]"]) for r in rows) == pytest.approx(
        sum(p["infrared_W"] for p in doc["parts"].values()), rel=1e-12
    )


def test_text_report(run_cli, sphere):
    code, out, err = run_cli(*_args(sphere, "--altitude", "35786", "--sun", "1", "0", "0", "--thermal"))
    assert code == 0, err
    assert "infrared force" in out and "temperature [K]" in out


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--altitude", "-5", "--sun", "1", "0", "0"], "--altitude -5.0 is not in"),
        (["--altitude", "500", "--sun", "1", "0", "0", "--albedo-model", "knocke"], "needs --epoch"),
        (["--altitude", "500", "--sun", "1", "0", "0", "--step", "0"], "--step 0.0 is not in"),
        (["--altitude", "500", "--sun", "1", "0", "0", "--albedo", "1.5"], "--albedo 1.5 is outside"),
        (["--altitude", "500", "--sun", "0", "0", "0"], "--sun"),
    ],
)
def test_bad_input_is_one_line(run_cli, sphere, extra, message):
    code, out, err = run_cli(*_args(sphere, *extra))
    assert code == 1 and out == ""
    assert err.startswith("sunwind: error:") and message in err and err.count("\n") == 1, err


def test_missing_emissivity_and_unwritable_sides_are_one_line(run_cli, sphere, tmp_path):
    args = _args(sphere, "--altitude", "500", "--sun", "1", "0", "0")
    args[3] = sphere / "bare.toml"
    code, _, err = run_cli(*args)
    assert code == 1 and "material 'black' has no emissivity" in err and err.count("\n") == 1, err
    code, _, err = run_cli(
        *_args(sphere, "--altitude", "500", "--sun", "1", "0", "0", "--sides", tmp_path / "no" / "x.csv")
    )
    assert code == 1 and "directory does not exist" in err and err.count("\n") == 1, err


def _forces(folder, *extra):
    return [
        "forces", folder / "sphere.obj", "-m", folder / "black.toml", "--sun", "0.6", "0", "-0.8",
        "--flow-azel", "0", "0", "--altitude", "500", *extra,
    ]  # fmt: skip


def test_forces_adds_the_earth_terms_of_sunwind_earth_to_its_total(run_cli, sphere):
    code, out, err = run_cli(
        *_forces(sphere, "--earth-radiation", "--earth", "0", "0", "1", "--thermal", "--json")
    )
    assert code == 0, err
    doc = json.loads(out)
    args = _args(sphere, "--altitude", "500", "--sun", "0.6", "0", "-0.8", "--thermal", "--json")
    args[7] = "1"  # the same place: the Earth along +z
    code, out, err = run_cli(*args)
    assert code == 0, err
    alone = json.loads(out)
    for key in ("albedo", "infrared", "thermal"):
        assert (
            doc[key]["force_N"] == alone[key]["force_N"] and doc[key]["torque_Nm"] == alone[key]["torque_Nm"]
        )
    terms = ("srp", "drag", "albedo", "infrared", "thermal")
    total = sum(np.array(doc[key]["force_N"]) for key in terms)
    assert np.allclose(doc["total"]["force_N"], total, rtol=1e-14, atol=0)
    assert doc["planet"]["nadir"] == [0.0, 0.0, 1.0] and "temperature_K" in next(iter(doc["parts"].values()))
    code, out, err = run_cli(*_forces(sphere, "--earth-radiation", "--earth", "0", "0", "1"))
    assert code == 0 and "planet:" in out and "albedo   force" in out, err


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--earth-radiation"], "--earth-radiation needs --earth X Y Z"),
        (["--thermal"], "--thermal needs --earth-radiation"),
        (["--earth", "0", "0", "1", "--albedo", "0.2"], "--albedo, --earth need --earth-radiation"),
        (["--earth-radiation", "--earth", "0", "0", "1", "-m", "bare.toml"], "has no emissivity"),
    ],
)
def test_forces_earth_options_are_checked_in_one_line(run_cli, sphere, extra, message):
    extra = [sphere / e if str(e).endswith(".toml") else e for e in extra]
    code, out, err = run_cli(*_forces(sphere, *extra))
    assert code == 1 and out == ""
    assert err.startswith("sunwind: error:") and message in err and err.count("\n") == 1, err


def test_earth_without_the_earth_direction_is_one_line(run_cli, sphere):
    code, _, err = run_cli(
        "earth",
        sphere / "sphere.obj",
        "-m",
        sphere / "black.toml",
        "--altitude",
        "500",
        "--sun",
        "1",
        "0",
        "0",
    )
    assert code == 1 and "give --earth X Y Z" in err and err.count("\n") == 1, err


def test_the_plate_mode_casts_no_ray_and_says_so(run_cli, sphere):
    code, out, err = run_cli(
        *_args(sphere, "--altitude", "500", "--sun", "1", "0", "0", "--plates", "--json")
    )
    assert code == 0, err
    doc = json.loads(out)
    assert doc["rays"] == 0 and doc["reflections"] == "plates"


def _geo(folder, *extra):
    """``forces`` in GEO: SRP and the Earth's terms, no flow."""
    return [
        "forces", folder / "sphere.obj", "-m", folder / "black.toml", "--sun", "0.6", "0", "-0.8",
        "--altitude", "35786", "--earth-radiation", "--earth", "0", "0", "1", "--json", *extra,
    ]  # fmt: skip


def test_forces_without_a_flow_is_srp_and_the_earth_terms_with_a_notice(run_cli, sphere):
    code, out, err = run_cli(*_geo(sphere))
    assert code == 0, err
    assert "notice: no flow direction" in err and "no drag" in err
    doc = json.loads(out)
    assert doc["drag"] is None
    total = sum(np.array(doc[key]["force_N"]) for key in ("srp", "albedo", "infrared"))
    assert np.allclose(doc["total"]["force_N"], total, rtol=1e-14, atol=0)
    assert doc["total"]["error_estimate"] is not None  # the SRP and Earth passes' estimates, no drag's
    code, out, err = run_cli(*_geo(sphere)[:-1])
    assert code == 0 and "drag:            none (no flow direction" in out, err


def test_forces_takes_the_albedo_season_from_epoch_as_earth_does(run_cli, sphere):
    knocke = ["--albedo-model", "knocke", "--pole", "0", "1", "0"]
    albedo = {}
    for epoch in ("2024-01-01", "2024-07-01"):
        code, out, err = run_cli(*_geo(sphere, *knocke, "--epoch", epoch))
        assert code == 0, err
        albedo[epoch] = json.loads(out)["albedo"]["force_N"]
        args = _args(sphere, "--altitude", "35786", "--sun", "0.6", "0", "-0.8", *knocke, "--json")
        args[7] = "1"  # the Earth along +z, as in _geo
        code, out, err = run_cli(*args, "--epoch", epoch)
        assert code == 0, err
        assert json.loads(out)["albedo"]["force_N"] == albedo[epoch]  # the same date, the same albedo
    assert albedo["2024-01-01"] != albedo["2024-07-01"]  # the season enters


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--f107", "100"], "--f107 sets the drag, which needs the flow's direction"),
        (["--density", "1e-12"], "--density sets the drag"),
        (["--gsi", "cll", "--wall-temperature", "200"], "--gsi, --wall-temperature set the drag"),
        (["--time", "2024-01-01", "--epoch", "2024-01-02"], "--time is the former name of --epoch"),
    ],
)
def test_forces_without_a_flow_refuses_the_drag_flags(run_cli, sphere, extra, message):
    code, out, err = run_cli(*_geo(sphere, *extra))
    assert code == 1 and out == ""
    assert err.startswith("sunwind: error:") and message in err and err.count("\n") == 1, err


def test_time_is_taken_as_epoch_with_a_warning(run_cli, sphere):
    code, out, err = run_cli(*_forces(sphere, "--time", "2020-06-01", "--json"))
    assert code == 0 and "warning: --time is now called --epoch" in err, err
    assert "2020-06-01" in json.loads(out)["drag"]["atmosphere"]["source"]
