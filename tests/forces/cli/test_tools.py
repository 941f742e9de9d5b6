"""``sunwind validate`` and ``sunwind bench``: the commands run the runner and the benchmark and print
their tables (on a cut-down case list and a small model: the cases themselves are tested in
tests/validation)."""

import json

from sunwind.validation import runner


def test_validate_prints_the_case_table_and_exits_zero(run_cli, monkeypatch):
    plates = tuple(case for case in runner.SRP_CASES if case.name.startswith("plate one-sided"))
    monkeypatch.setattr(runner, "SRP_CASES", plates)
    monkeypatch.setattr(runner, "REFINEMENT_CASES", ())
    code, out, err = run_cli("validate")
    assert code == 0, err
    lines = out.splitlines()
    assert lines[0].split()[:3] == ["case", "worst", "Sun"]
    assert [line.split("/")[0] for line in lines[1:5]] == ["plate one-sided"] * 4
    assert "shadowed plates/mixed" in out and "FAIL" not in out


def test_bench_times_a_small_model_and_reports_json(run_cli):
    code, out, err = run_cli("bench", "--triangles", "3000", "--attitudes", "2", "--json")
    assert code == 0, err
    report = json.loads(out)
    assert report["attitudes"] == 2 and report["samples_per_side"] == 1
    assert report["overhead"] > 0 and report["full_over_direct"] > 0 and report["drag_over_srp"] > 0
    code, _, err = run_cli("bench", "--attitudes", "0")
    assert code == 1 and err.startswith("sunwind: error: --attitudes 0 must be at least 1")
