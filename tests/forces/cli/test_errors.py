"""Library errors name Python parameters; the command line writes its flags in their place."""

import pytest

from helpers import REPO
from sunwind.forces.cli.options import FLAGS
from sunwind.forces.radiation import solar_flux
from sunwind.geometry.errors import InputError

SAMPLE = "meshes/data/sample_spacecraft.usda"


def test_an_error_renamed_writes_the_flags_of_its_parameters_only():
    with pytest.raises(InputError) as caught:
        solar_flux(-5.0)
    error = caught.value
    assert str(error).startswith("flux_W_m2 -5.0 is not") and error.parameters == ("flux_W_m2",)
    renamed = error.renamed(FLAGS)
    assert str(renamed).startswith("--flux -5.0 is not") and str(error).startswith("flux_W_m2")
    plain = InputError("the time is up", hint="wait")
    assert str(plain.renamed(FLAGS)) == "the time is up; wait"  # "time" is no parameter of this one


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["srp", SAMPLE, "--sun", "1", "0", "0", "--flux", "-1"], "--flux -1.0 is not a finite non-negative"),
        (
            ["srp", SAMPLE, "--sun", "1", "0", "0", "--tolerance", "2"],
            "--tolerance 2.0 must lie in [1e-06, 1)",
        ),
        (
            ["srp", SAMPLE, "--sun", "1", "0", "0", "--tolerance", "1e-7"],
            "--tolerance 1e-07 must lie in [1e-06, 1)",
        ),
        (["srp", SAMPLE, "--sun", "1", "0", "0", "--samples", "0"], "--samples 0 must be a whole number"),
        (
            ["srp", SAMPLE, "--sun", "1", "0", "0", "--reflection-cutoff", "2"],
            "--reflection-cutoff 2.0 is not",
        ),
        (
            ["srp", SAMPLE, "--sun", "1", "0", "0", "--view-rays", "0"],
            "--view-rays 0 must be a whole number from 1 to 65536",
        ),
        (["drag", SAMPLE, "--flow-azel", "0", "0", "--altitude", "-5"], "--altitude -5.0 km is below 0"),
        (["drag", SAMPLE, "--flow-azel", "0", "0", "--altitude", "400", "--lat", "95"], "--lat 95.0 deg"),
        (["drag", SAMPLE, "--flow-azel", "0", "0", "--altitude", "400", "--epoch", "soon"], "--epoch 'soon'"),
        (["sweep", SAMPLE, "--srp", "--step", "7", "-o", "{tmp}/t.nc"], "--step 7 deg does not divide"),
        (["sweep", SAMPLE, "--srp", "--step", "90", "--chunk", "0", "-o", "{tmp}/t.nc"], "--chunk 0 must be"),
        (
            ["sweep", SAMPLE, "--srp", "--step", "90", "--workers", "0", "-o", "{tmp}/t.nc"],
            "--workers 0 must be a whole number >= 1",
        ),
    ],
)
def test_the_command_line_names_its_flags(run_cli, monkeypatch, tmp_path, args, expected):
    monkeypatch.chdir(REPO)
    code, _out, err = run_cli(*(a.format(tmp=tmp_path) for a in args))
    assert code == 1, err
    assert err.startswith("sunwind: error: ") and err.count("\n") == 1
    assert expected in err and "_m2" not in err and "_km" not in err
