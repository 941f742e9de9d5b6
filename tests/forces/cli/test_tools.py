"""``sunwind validate`` and ``sunwind bench``: the commands run the runner and the benchmark and print
their tables (on stand-in families and a small model: the cases themselves are tested in
tests/validation; the quick validation run once, slow)."""

import json

import numpy as np
import pytest

from sunwind.forces.bench import LoadError
from sunwind.validation import runner
from sunwind.validation.checks import Check, Family, Measure


def _family(name: str, *values: float) -> Family:
    """A family of one case whose checks measure ``values`` against a limit of 1."""
    return Family(
        name,
        "a stand-in",
        lambda quick: (
            Check(name, "case", f"at {k}", (Measure("error", v, 1.0),)) for k, v in enumerate(values)
        ),
    )


def test_validate_prints_every_case_and_ends_with_the_count(run_cli, monkeypatch):
    monkeypatch.setattr(runner, "FAMILIES", (_family("good", 0.5, 0.25), _family("bad", 0.1, 2.0)))
    code, out, err = run_cli("validate")
    assert code == 1, err
    lines = out.splitlines()
    assert lines[0].split()[:3] == ["family", "case", "checks"]
    assert lines[1].split()[:4] == ["good", "case", "2", "at"] and "FAIL" not in lines[1]
    assert lines[2].split()[:3] == ["bad", "case", "2"] and lines[2].endswith("FAIL (1)")
    assert lines[-1] == "3 passed, 1 failed"
    assert "validate: [2/2] bad: 2 checks, 1 failed" in err  # progress on stderr
    code, out, _ = run_cli("validate", "--json")
    document = json.loads(out)
    assert code == 1 and (document["passed"], document["failed"]) == (3, 1)
    assert document["checks"][3]["measures"] == [{"name": "error", "value": 2.0, "limit": 1.0}]


def test_validate_exits_zero_when_every_check_passes(run_cli, monkeypatch):
    monkeypatch.setattr(runner, "FAMILIES", (_family("good", 1.0),))
    code, out, _ = run_cli("validate", "--quick")
    assert code == 0 and out.splitlines()[-1] == "1 passed, 0 failed"


def test_a_family_that_raises_is_a_failed_check_and_the_others_still_run(run_cli, monkeypatch):
    def broken(quick):
        yield Check("broken", "case", "at 0", (Measure("error", 0.0, 1.0),))
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(runner, "FAMILIES", (Family("broken", "a stand-in", broken), _family("good", 0.5)))
    code, out, err = run_cli("validate")
    assert code == 1 and "Traceback" not in out + err
    assert "(stopped)" in out and "ZeroDivisionError: division by zero" in out and "FAIL" in out
    assert out.splitlines()[-1] == "2 passed, 1 failed"


@pytest.mark.slow
def test_validate_quick_runs_every_family_within_its_limits(run_cli):
    """Every family but the refinement study (full run only); about 30 s on 2 cores (not asserted: the
    machine may be shared)."""
    code, out, err = run_cli("validate", "--quick")
    assert code == 0, out + err
    families = {line[:21].strip() for line in out.splitlines()[1:-1]}
    assert families == {f.name for f in runner.FAMILIES} - {"mesh refinement"}
    passed = int(out.splitlines()[-1].split()[0])
    assert out.splitlines()[-1] == f"{passed} passed, 0 failed" and passed > 150


@pytest.mark.slow
def test_bench_times_a_small_model_and_reports_json(run_cli):
    code, out, err = run_cli("bench", "--triangles", "3000", "--attitudes", "2", "--json")
    assert code == 0, err
    report = json.loads(out)
    assert report["attitudes"] == 2 and report["samples_per_side"] == 1
    assert report["overhead"] > 0 and report["full_over_direct"] > 0 and report["drag_over_srp"] > 0
    assert report["default_over_fixed"] > 0 and report["batch_default_over_fixed"] > 0
    assert report["batch_identical"] is True  # attitudes side by side give what they give one at a time
    # every timed setting has its error against the tighter reference beside it; the default converges
    # (its error is below its own tolerance, 1e-3), one point per side does not
    for key in ("default", "fixed", "full", "fixed_full", "drag", "fixed_drag", "drag_full"):
        error = report[f"{key}_error"]
        assert 0 <= error["force_median"] <= error["force_worst"] and error["torque_worst"] >= 0, key
    assert report["default_error"]["force_worst"] < 1e-3 < report["fixed_error"]["force_worst"]
    code, _, err = run_cli("bench", "--attitudes", "0")
    assert code == 1 and err.startswith("sunwind: error: --attitudes 0 must be from 1 to 10000")


def test_load_error_is_relative_to_the_reference_attitude_by_attitude():
    unit = np.eye(3)
    references = [(unit[0], unit[1]), (2 * unit[0], unit[2]), (unit[2], unit[0])]
    loads = [(unit[0] * 1.01, unit[1]), (2 * unit[0] + 0.002 * unit[1], unit[2] * 0.5)]  # the first two
    error = LoadError.of(loads, references, size_m=2.0)
    assert error.force_worst == pytest.approx(0.01) and error.force_median == pytest.approx(0.0055)
    assert error.torque_worst == pytest.approx(0.5) and error.torque_median == pytest.approx(0.25)
    assert error.torque_of_force_worst == pytest.approx(0.5 / (2.0 * 2.0))  # |dM| 0.5 over |F| 2 x L 2
    assert str(error).startswith("error force 1.0e-02 worst, 5.5e-03 median; torque 5.0e-01 worst")
    assert str(error).endswith("1.2e-01 of |F| L worst")


@pytest.mark.slow
def test_bench_sweep_reports_the_error_of_its_entries(run_cli):
    code, out, err = run_cli("bench", "--sweep", "--triangles", "3000", "--step", "45", "--json")
    assert code == 0, err
    report = json.loads(out)
    assert report["distinct_directions"] == 26 and report["checked_directions"] == 24
    # SRP runs the default shadow pass: within its tolerance (1e-3) of the tighter reference
    srp_error, drag_error = report["srp_error"], report["drag_error"]
    assert 0 <= srp_error["force_median"] <= srp_error["force_worst"] < 1e-3
    assert srp_error["torque_worst"] < 1e-3
    # drag's open-sky integral is sampled: against the reference sampled 16 times as finely, its noise
    # is reported (not zero) and well inside the 2 % the molecule tracer validates it to
    assert 0 < drag_error["force_median"] <= drag_error["force_worst"] < 1e-2
    assert 0 < drag_error["torque_of_force_worst"] < 1e-3
    assert report["projected_1_deg_s"] > 0
    assert report["dask_identical"] is True


@pytest.mark.slow
def test_bench_orbit_times_every_case(run_cli):
    """Every case of the orbit benchmark reports a time per step (not asserted: the machine may be
    shared), on a small sample."""
    code, out, err = run_cli("bench", "--orbit", "--triangles", "2000", "--json")
    assert code == 0, err
    report = json.loads(out)
    assert set(report["ms_per_step"]) == {"LEO SRP + drag", "LEO SRP", "LEO drag", "GEO SRP"}
    assert all(ms > 0 for ms in report["ms_per_step"].values()) and report["steps"] == 40


@pytest.mark.slow
def test_bench_earth_reports_time_memory_and_error_against_the_cells(run_cli, tmp_path):
    """``sunwind bench --earth`` on a small box-and-wing: the visibility's build and size, the time per
    attitude against SRP, the error against the 2.5 deg cells (under 1e-3) and the estimate's ratio to it."""
    from sunwind.geometry.io.obj import write_obj
    from sunwind.meshes.primitives import box_wing

    write_obj(box_wing(facet_size=0.5), tmp_path / "craft.obj")
    white = "[materials.white]\nreflectivity = 0.6\nspecular_fraction = 0.5\nemissivity = 0.8\n"
    parts = '[parts]\n"wing_*" = { front = "white", back = "white" }\nbus = "white"\n'
    (tmp_path / "craft.toml").write_text(white + parts)
    mesh, materials = str(tmp_path / "craft.obj"), str(tmp_path / "craft.toml")
    code, out, err = run_cli("bench", "--earth", "--mesh", mesh, "-m", materials, "--places", "3", "--json")
    assert code == 0, err
    report = json.loads(out)
    assert report["grid_nodes"] == 642 and report["visibility_MB"] > 0 and report["build_s"] > 0
    assert report["earth_ms"] > 0 and report["srp_ms"] > 0 and report["places"] == 3
    assert report["error"]["force_worst"] < 1e-3 and report["torque_scaled_worst"] < 1e-2
    low, high = report["estimate_over_error"]  # at errors of 1e-5 the passes' own estimate dominates
    assert 0.5 < low <= high < 30
