"""``sunwind validate`` and ``sunwind bench``: the commands run the runner and the benchmark and print
their tables (on stand-in families and a small model: the cases themselves are tested in
tests/validation; the quick validation run once, slow)."""

import json

import pytest

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
    """Every family but the refinement study (full run only); 16-25 s on 2 cores (not asserted: the
    machine may be shared)."""
    code, out, err = run_cli("validate", "--quick")
    assert code == 0, out + err
    families = {line[:21].strip() for line in out.splitlines()[1:-1]}
    assert families == {f.name for f in runner.FAMILIES} - {"mesh refinement"}
    passed = int(out.splitlines()[-1].split()[0])
    assert out.splitlines()[-1] == f"{passed} passed, 0 failed" and passed > 150


def test_bench_times_a_small_model_and_reports_json(run_cli):
    code, out, err = run_cli("bench", "--triangles", "3000", "--attitudes", "2", "--json")
    assert code == 0, err
    report = json.loads(out)
    assert report["attitudes"] == 2 and report["samples_per_side"] == 1
    assert report["overhead"] > 0 and report["full_over_direct"] > 0 and report["drag_over_srp"] > 0
    code, _, err = run_cli("bench", "--attitudes", "0")
    assert code == 1 and err.startswith("sunwind: error: --attitudes 0 must be at least 1")
