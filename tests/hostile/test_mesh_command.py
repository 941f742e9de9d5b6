"""Bad parameters of `sunwind mesh`: one line naming the command's own flag, never a traceback."""

import pytest

CASES = {
    "radius negative": (["sphere", "--radius", "-1"], "--radius -1.0 must be a finite number > 0"),
    "radius nan": (["sphere", "--radius", "nan"], "--radius nan must be a finite number > 0"),
    "size zero": (["plate", "--size-x", "0"], "--size-x 0.0 must be a finite number > 0"),
    "divisions zero": (["box", "--divisions", "0"], "--divisions 0 must be an integer >= 1 or 3 of them"),
    "divisions two of three": (["box", "--divisions", "2", "2"], "--divisions (2, 2) must be an integer"),
    "segments too few": (["dish", "--segments", "2"], "--segments"),
}


@pytest.mark.parametrize("name", list(CASES))
def test_a_bad_mesh_parameter_names_its_flag(run_cli, tmp_path, name):
    args, words = CASES[name]
    code, _out, err = run_cli("mesh", *args, "-o", tmp_path / "m.obj")
    assert code == 1 and err.startswith("sunwind: error: ") and err.count("\n") == 1, err
    assert words in err and "Traceback" not in err and not (tmp_path / "m.obj").exists()
