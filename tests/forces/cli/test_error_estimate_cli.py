"""The shadow pass's error estimate in every output: JSON ``error_estimate``, the text line, a variable
per attitude of a sweep's table, series of an orbit, and one warning line when it exceeds the
tolerance."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
import xarray as xr

from sunwind.forces.tables.dataset import open_table
from sunwind.geometry.rays.certificate import LoadsError, ShadowCheck

AIR = ["--density", "3e-12", "--temperature", "900", "--composition", "O:0.8,N2:0.2"]
ORBIT = ["--altitude", "500", "--inclination", "51.6", "--epoch", "2024-06-01T00:00:00Z"]
ORBIT += ["--duration", "600", "--step", "120"]


@pytest.fixture(scope="module")
def craft(tmp_path_factory):
    """A coarse box-wing, one uniform material, its wings two-sided sheets (the bus shadows them)."""
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import box_wing

    path = tmp_path_factory.mktemp("estimate-cli") / "box_wing.obj"
    save_mesh(box_wing(facet_size=0.25), path)
    return [str(path), "--reflectivity", "0.5", "--specular-fraction", "0.4", "--two-sided", "wing*"]


@pytest.fixture
def huge_errors(monkeypatch):
    """Make every other shadow check report an error of 1 N and 1 N m, far beyond any tolerance."""
    calls = []

    def fake(check, craft, load_per_area, reference_m):
        calls.append(1)
        return LoadsError(1.0, 1.0) if len(calls) % 2 else LoadsError(0.0, 0.0)

    monkeypatch.setattr(ShadowCheck, "loads_error", fake)
    return calls


def _warnings(err: str) -> list[str]:
    return [line for line in err.splitlines() if line.startswith("sunwind: warning:")]


@pytest.mark.parametrize(
    "command",
    [["srp", "--sun-azel", "30", "40"], ["drag", "--flow-azel", "30", "10", "--speed", "7600", *AIR]],
    ids=["srp", "drag"],
)
def test_json_has_the_estimate_and_null_with_fixed_sampling(run_cli, craft, command):
    args = [command[0], *craft, *command[1:], "--reflections", "none"]
    args += ["--sky-rays", "36"] if command[0] == "drag" else []
    code, out, err = run_cli(*args, "--json")
    assert code == 0, err
    estimate = json.loads(out)["error_estimate"]
    assert set(estimate) == {"force", "torque"}
    assert all(isinstance(v, float) and 0 <= v < 1e-3 for v in estimate.values())
    code, out, err = run_cli(*args, "--json", "--samples", "4")
    assert code == 0, err
    assert json.loads(out)["error_estimate"] is None
    code, out, err = run_cli(*args)
    assert code == 0 and not _warnings(err), err
    assert "  shadow error     force " in out and "(relative, estimated)" in out


def test_one_warning_line_when_the_estimate_exceeds_the_tolerance(run_cli, craft, huge_errors):
    args = ["srp", *craft, "--sun-azel", "30", "40", "--reflections", "none"]
    code, _, err = run_cli(*args)
    assert code == 0 and huge_errors
    lines = _warnings(err)
    assert len(lines) == 1, err
    assert lines[0].startswith(
        "sunwind: warning: the shadow pass's estimated error exceeds the tolerance 0.001: srp "
    )
    assert "--tolerance" in lines[0] and "--samples" in lines[0]
    code, _, err = run_cli(*args, "--samples", "4")  # fixed sampling: no check, no estimate, no warning
    assert code == 0 and not _warnings(err), err


def test_sweep_tables_hold_an_estimate_per_attitude(run_cli, craft, tmp_path):
    args = ["sweep", *craft, "--srp", "--step", "90", "--reflections", "none"]
    code, out, err = run_cli(*args, "-o", tmp_path / "t.nc")
    assert code == 0 and not _warnings(err), err
    assert "  shadow error     srp worst force " in out
    table = open_table(tmp_path / "t.nc")
    for what in ("force", "torque"):
        variable = table[f"srp_error_estimate_{what}"]
        assert variable.dims == ("sun_azimuth", "sun_elevation") and variable.shape == (5, 3)
        assert np.all(np.isfinite(variable.values)) and np.all(variable.values >= 0)
        assert variable.attrs["units"] == "1" and "shadow pass" in variable.attrs["long_name"]
        assert "|d" in variable.attrs["comment"]
    code, _, err = run_cli(*args, "-o", tmp_path / "t.csv")
    assert code == 0, err
    header = next(line for line in (tmp_path / "t.csv").read_text().splitlines() if not line.startswith("#"))
    assert "srp_error_estimate_force[1]" in header.split(",")
    code, _, err = run_cli(*args, "--samples", "1", "-o", tmp_path / "fixed.nc")
    assert code == 0, err
    assert not [name for name in open_table(tmp_path / "fixed.nc").data_vars if "error_estimate" in name]


def test_a_sweep_says_in_one_line_how_many_attitudes_exceed_the_tolerance(
    run_cli, craft, tmp_path, huge_errors
):
    code, _, err = run_cli(
        "sweep", *craft, "--srp", "--step", "90", "--reflections", "none", "-o", tmp_path / "t.nc"
    )
    assert code == 0, err
    assert len(huge_errors) == 6  # the distinct directions of a 90-degree grid: the poles once each
    lines = _warnings(err)
    assert len(lines) == 1, err
    assert "srp at 3 of 6 attitudes (worst force " in lines[0] and "--tolerance" in lines[0]


def test_orbit_series_carry_the_estimate_of_each_step(run_cli, craft, tmp_path):
    args = ["orbit", *craft, *ORBIT, *AIR, "--srp", "--drag", "--reflections", "none"]
    args += ["--gas-reflections", "none", "--sky-rays", "36"]
    code, out, err = run_cli(*args, "--json")
    assert code == 0 and not _warnings(err), err
    document = json.loads(out)
    for what in ("force", "torque"):
        series = np.array(document[f"error_estimate_{what}"])
        assert series.shape == (6,) and np.all(np.isfinite(series)) and np.all(series >= 0)
        assert document["summary"]["error_estimate_worst"][what] == series.max()
    code, out, err = run_cli(*args, "-o", tmp_path / "run.nc")
    assert code == 0, err
    assert "  shadow error   worst step: force " in out
    with xr.open_dataset(tmp_path / "run.nc") as run:
        assert run["error_estimate_torque"].dims == ("time",)
        assert np.array_equal(run["error_estimate_torque"].values, document["error_estimate_torque"])
        assert (
            run["error_estimate_force"].attrs["units"] == "1"
            and "long_name" in run["error_estimate_force"].attrs
        )
    code, out, err = run_cli(*args, "--samples", "1", "--json")
    assert code == 0, err
    document = json.loads(out)
    assert "error_estimate_force" not in document and "error_estimate_worst" not in document["summary"]


def test_an_orbit_says_in_one_line_how_many_steps_exceed_the_tolerance(run_cli, craft, huge_errors):
    args = ["orbit", *craft, *ORBIT, "--srp", "--reflections", "none"]
    code, out, err = run_cli(*args)
    assert code == 0, err
    lines = _warnings(err)
    assert len(lines) == 1, err
    assert "orbit at " in lines[0] and " of 6 steps (worst force " in lines[0]
    worst = re.search(r"  shadow error   worst step: force (\S+), torque", out)
    assert worst and float(worst.group(1)) > 1e3  # 1 N on a force of some 1e-5 N
